"""Validation: measured against predicted DOP for the development shots."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..io import task, write_csv
from .common import figure, save


@task
def validation(inputs, outputs, params):
    shots = pd.read_csv(inputs.predictions)
    shots["rel_err"] = shots.dop_pred_m / shots.dop_m - 1
    write_csv(shots[["shot_id", "mass_kg", "diameter_m", "nose_shape", "crh", "fc_MPa", "velocity_ms", "dop_m",
                     "dop_pred_m", "rel_err"]], outputs.csv)
    abs_err = shots.rel_err.abs()
    med, p90 = float(np.median(abs_err)), float(np.percentile(abs_err, 90))
    fig, (ax,) = figure(1, 5.2, 5.0)
    top = 1.1 * max(shots.dop_m.max(), shots.dop_pred_m.max())
    line = np.array([0, top])
    groups = shots.assign(series=[f"{round(m, 1):g} kg, {1e3 * d:.1f} mm" for m, d in zip(shots.mass_kg, shots.diameter_m)])
    ax.fill_between(line, 0.8 * line, 1.2 * line, color="0.85", label="+-20 %")
    ax.plot(line, line, "k-", lw=0.8)
    for (s, g), mk in zip(groups.groupby("series"), "osd^v<>ph*"):
        ax.plot(g.dop_m, g.dop_pred_m, mk, label=s)
    ax.text(0.04, 0.96, f"{len(shots)} shots, Eq 9 with S from {params.law}\nmedian |error| {100 * med:.1f} %\n"
            f"90th percentile |error| {100 * p90:.1f} %", transform=ax.transAxes, va="top", fontsize=8)
    ax.set(xlabel="measured DOP (m)", ylabel="predicted DOP (m)", xlim=(0, top), ylim=(0, top), aspect="equal",
           title="Validation on development shots")
    ax.legend(loc="lower right", fontsize=7)
    save(fig, outputs.png, params.dpi)
