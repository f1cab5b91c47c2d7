"""Accuracy against cost of the trajectory engine: DOP error versus wall time per shot.

The errors (``figures/accuracy_trajectory.csv``) do not depend on the
machine; the wall times and the figure that plots against them do, and
live under ``figures/timing/``.
"""
from __future__ import annotations

import pandas as pd

from ..pipeline.io import task, write_csv
from .common import figure, save


@task
def accuracy_trajectory(inputs, outputs, params):
    data = pd.read_csv(inputs.csv)
    write_csv(data.drop(columns="wall_time_s"), outputs.csv)
    write_csv(data[["method", "rtol", "wall_time_s"]], outputs.timing)
    fig, (ax,) = figure(1, 5.6, 4.2)
    for method, g in data.groupby("method"):
        ax.loglog(g.wall_time_s * 1e3, g.rel_error.clip(lower=1e-16), "o-", label=method)
        for r in g.itertuples():
            ax.annotate(f"{r.rtol:.0e}", (r.wall_time_s * 1e3, max(r.rel_error, 1e-16)), fontsize=6,
                        textcoords="offset points", xytext=(3, 3))
    ax.axhline(1e-6, color="k", ls=":", lw=1, label="1e-6 target")
    ax.set(xlabel="wall time per shot (ms)", ylabel="relative DOP error vs Eq 9",
           title="Trajectory engine: DO1 shot, labels = rtol")
    ax.legend(fontsize=7)
    save(fig, outputs.png, params.dpi)
