"""Fig 14: deceleration histories of the three noses (cavity level).

Filter: none. The rigid-body model's deceleration is smooth, so no low-pass
filter is applied (the declared output setting); the paper's LS-DYNA curves
are filtered by an unstated method. Each trace ends with a point at zero at
the time of rest: the static resistance acts only while the projectile
moves, so the deceleration drops from its plateau to zero when it stops.
The paper's axis ranges (the only values of Fig 14 that survive) are drawn
as the frame of each panel: the largest deceleration and time ticks.
"""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv
from ..units import G0
from .common import color, ending_at_rest, figure, save

LABELS = {"crh3": "CRH 3", "crh45": "CRH 4.5", "double_ogive": "double ogive"}


@task
def fig14(inputs, outputs, params):
    hist = pd.read_csv(inputs.histories)
    refs = load_reference(inputs.reference)
    hist = ending_at_rest(hist, ["nose", "velocity"])
    data = hist.assign(t_ms=hist.t * 1e3, deceleration_g=hist.deceleration / G0, filter="none")[
        ["nose", "velocity", "t_ms", "deceleration_g", "filter"]]
    write_csv(data, outputs.csv)
    vel = sorted(data.velocity.unique())
    fig, axes = figure(len(vel), 4.0, 3.4)
    fig.subplots_adjust(wspace=0.3)
    for ax, v in zip(axes, vel):
        for n, g in data[data.velocity == v].groupby("nose", sort=False):
            ax.plot(g.t_ms, g.deceleration_g, color=color(n), label=LABELS[n])
        g_max, t_max = refs[f"fig14.g_axis_max.{v:.0f}"].value, refs[f"fig14.t_axis_max.{v:.0f}"].value
        ax.plot([0, t_max, t_max], [g_max, g_max, 0], color="k", ls="--", lw=0.8,
                label=f"paper's axes: {g_max:g} g, {t_max:g} ms")
        ax.set(xlabel="t (ms)", ylabel="deceleration (g)", title=f"Fig 14: vs = {v:.0f} m/s",
               ylim=(0, 1.05 * max(g_max, data[data.velocity == v].deceleration_g.max())))
        ax.legend(fontsize=7)
    save(fig, outputs.png, params.dpi)
