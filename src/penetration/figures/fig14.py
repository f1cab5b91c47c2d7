"""Fig 14: deceleration histories of the three noses (cavity level).

Filter: none. The rigid-body model's deceleration is smooth, so no low-pass
filter is applied (the declared output setting); the paper's LS-DYNA curves
are filtered by an unstated method.
"""
from __future__ import annotations

import pandas as pd

from ..io import task, write_csv
from ..units import G0
from .common import color, figure, save

LABELS = {"crh3": "CRH 3", "crh45": "CRH 4.5", "double_ogive": "double ogive"}


@task
def fig14(inputs, outputs, params):
    hist = pd.read_csv(inputs.histories)
    data = hist.assign(t_ms=hist.t * 1e3, deceleration_g=hist.deceleration / G0, filter="none")[
        ["nose", "velocity", "t_ms", "deceleration_g", "filter"]]
    write_csv(data, outputs.csv)
    vel = sorted(data.velocity.unique())
    fig, axes = figure(len(vel), 4.0, 3.4)
    for ax, v in zip(axes, vel):
        for n, g in data[data.velocity == v].groupby("nose", sort=False):
            ax.plot(g.t_ms, g.deceleration_g, color=color(n), label=LABELS[n])
        ax.set(xlabel="t (ms)", ylabel="deceleration (g)", title=f"Fig 14: vs = {v:.0f} m/s")
        ax.legend(fontsize=7)
    save(fig, outputs.png, params.dpi)
