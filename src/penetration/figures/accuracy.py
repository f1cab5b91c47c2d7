"""Accuracy against cost: trajectory DOP error versus wall time (machine-dependent)."""
from __future__ import annotations

import pandas as pd

from ..tasks import task, write_csv
from .common import figure, save


@task
def accuracy_trajectory(inputs, outputs, params):
    data = pd.read_csv(inputs.csv)
    write_csv(data, outputs.csv)
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


@task
def accuracy_cavity(inputs, outputs, params):
    data = pd.read_csv(inputs.csv)
    write_csv(data, outputs.csv)
    fig, axes = figure(3, 4.2, 3.6)
    titles = {"zones": "cavity solver: zones", "cfl": "cavity solver: CFL number",
              "trajectory_rtol": "cavity-level trajectory: rtol"}
    for ax, (study, g) in zip(axes, data.groupby("study", sort=False)):
        g = g.iloc[:-1]  # the finest run is the reference
        ax.loglog(g.wall_time_s * 1e3, g.rel_error_vs_finest.clip(lower=1e-12), "o-")
        for r in g.itertuples():
            ax.annotate(f"{r.setting:g}", (r.wall_time_s * 1e3, max(r.rel_error_vs_finest, 1e-12)), fontsize=6,
                        textcoords="offset points", xytext=(3, 3))
        ax.set(xlabel="wall time (ms)", ylabel="relative error vs finest", title=titles.get(study, study))
    save(fig, outputs.png, params.dpi)
