"""Accuracy against cost of the cavity level: error versus wall time for each solver control.

The errors (``figures/accuracy_cavity.csv``) do not depend on the machine;
the wall times and the figure that plots against them do, and live under
``figures/timing/``.
"""
from __future__ import annotations

import pandas as pd
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ..pipeline.io import task, write_csv
from .common import figure, save

PANELS = {"zones": "cavity solver: zones", "cfl": "cavity solver: CFL number",
          "table_nodes": "sigma_n table: nodes (DO1 depth)", "trajectory_rtol": "cavity-level trajectory: rtol",
          "quasi_static": "v = 0 node: rate-free, vs slowest direct run"}


@task
def accuracy_cavity(inputs, outputs, params):
    data = pd.read_csv(inputs.csv)
    write_csv(data.drop(columns="wall_time_s"), outputs.csv)
    write_csv(data[["study", "setting", "wall_time_s"]], outputs.timing)
    fig, axes = figure(len(PANELS), 4.2, 3.6)
    fig.subplots_adjust(wspace=0.4)  # room for each panel's y label
    data["panel"] = data.study.str.replace(r"_(pchip_v2|linear_v|pair|direct)$", "", regex=True)
    for ax, (panel, title) in zip(axes, PANELS.items()):
        for study, g in data[data.panel == panel].groupby("study", sort=False):
            if not study.endswith(("linear_v", "quasi_static_pair")):
                g = g.iloc[:-1]  # the finest run is the reference
            label = study[len(panel) + 1:] or None
            ax.loglog(g.wall_time_s * 1e3, g.rel_error_vs_finest.clip(lower=1e-12), "o-", label=label)
            for r in g.itertuples():
                ax.annotate(f"{r.setting:g}", (r.wall_time_s * 1e3, max(r.rel_error_vs_finest, 1e-12)), fontsize=6,
                            textcoords="offset points", xytext=(3, 3))
            if label:
                ax.legend(fontsize=7)
        ax.set(xlabel="wall time (ms)", ylabel="relative error vs finest", title=title)
        # a narrow log range: label 1-2-5 steps, never the (overlapping) minor ticks
        ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
        ax.xaxis.set_minor_formatter(NullFormatter())
    save(fig, outputs.png, params.dpi)
