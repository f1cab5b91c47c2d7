"""Validation: measured against predicted DOP for the development shots (the task: tasks.analytic.validation; the
scores: laboratory.errors_summary)."""
from __future__ import annotations

import numpy as np

from .common import figure, save


def validation_eq9_figure(shots, summary, path, dpi, law):
    """Eq 9's predicted depth of every development shot against the measured one, the shots grouped by series (mass
    and calibre), with the summary's median and 90th percentile of |error|."""
    fig, (ax,) = figure(1, 5.2, 5.0)
    top = 1.1 * max(shots.dop_m.max(), shots.dop_pred_m.max())
    line = np.array([0, top])
    groups = shots.assign(series=[f"{round(m, 1):g} kg, {1e3 * d:.1f} mm" for m, d in zip(shots.mass_kg, shots.diameter_m)])
    ax.fill_between(line, 0.8 * line, 1.2 * line, color="0.85", label="+-20 %")
    ax.plot(line, line, "k-", lw=0.8)
    for (s, g), mk in zip(groups.groupby("series"), "osd^v<>ph*"):
        ax.plot(g.dop_m, g.dop_pred_m, mk, label=s)
    ax.text(0.04, 0.96, f"{summary['shots']} shots, Eq 9 with S from {law}\n"
            f"median |error| {100 * summary['median_abs_rel_err']:.1f} %\n"
            f"90th percentile |error| {100 * summary['p90_abs_rel_err']:.1f} %", transform=ax.transAxes, va="top", fontsize=8)
    ax.set(xlabel="measured DOP (m)", ylabel="predicted DOP (m)", xlim=(0, top), ylim=(0, top), aspect="equal",
           title="Validation on development shots")
    ax.legend(loc="lower right", fontsize=7)
    save(fig, path, dpi)
