"""Accuracy against cost over the fidelity ladder (the data from tasks.levels.accuracy_cost)."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..io import task
from .common import figure, save

STYLE = {"analytic": ("tab:gray", "s"), "trajectory": ("tab:orange", "^"), "cavity": ("tab:blue", "o"),
         "fe": ("tab:green", "D")}


@task
def accuracy_cost_figure(inputs, outputs, params):
    d = pd.read_csv(inputs.csv).merge(pd.read_csv(inputs.timing), on=["level", "setting"])
    fig, axes = figure(3, 4.9, 4.2)
    ax_sim, ax_do1, ax_self = axes
    for level, g in d.groupby("level", sort=False):
        c, mk = STYLE[level]
        t = g.wall_time_per_shot_s
        sim = g.dropna(subset=["table3_mean_abs_rel_dev"])
        if level == "analytic":
            for row in sim.itertuples():
                ax_sim.plot(row.wall_time_per_shot_s, 100 * row.table3_mean_abs_rel_dev, mk, color=c,
                            mfc=c if not row.calibrated_on_do1 else "white", label=f"analytic, {row.setting}")
        elif len(sim):
            ax_sim.plot(sim.wall_time_per_shot_s, 100 * sim.table3_mean_abs_rel_dev, mk + "-", color=c, mfc="white",
                        label=f"{level}" + (" (per mesh)" if level == "fe" else ""))
        do1 = g.dropna(subset=["do1_rel_error"])
        for row in do1.itertuples():
            ax_do1.plot(row.wall_time_per_shot_s, max(abs(row.do1_rel_error), 1e-12), mk, color=c,
                        mfc="white" if row.calibrated_on_do1 else c)
        self_ = g.dropna(subset=["self_rel_error"])
        self_ = self_[self_.self_rel_error > 0]
        if len(self_):
            ax_self.plot(self_.wall_time_per_shot_s, self_.self_rel_error, mk + "-", color=c, label=level)
        if level == "fe":
            for row in g.itertuples():
                ax_sim.annotate(row.setting.split(" (")[0].replace(" elements across", "/a"),
                                (row.wall_time_per_shot_s, 100 * row.table3_mean_abs_rel_dev), fontsize=6,
                                xytext=(3, 3), textcoords="offset points")
    ax_sim.set(xscale="log", xlabel="wall time per shot (s)", ylabel="mean |deviation| (%)",
               title="against the paper's simulated Table 3 (12 cells)\n(trajectory: the analytic level's model)")
    ax_sim.set_ylim(0, 1.15 * ax_sim.get_ylim()[1])
    ax_sim.legend(fontsize=6, loc="center right")
    ax_do1.set(xscale="log", yscale="log", xlabel="wall time per shot (s)", ylabel="|relative error|",
               title="against the DO1 shot (5.1 m)\n(hollow: calibrated on it, a residual)")
    ax_self.set(xscale="log", yscale="log", xlabel="wall time per shot (s)", ylabel="|relative error|",
                title="each level's convergence study\n(against its finest setting; trajectory: against Eq 9)")
    ax_self.legend(fontsize=7)
    for ax in axes:
        ax.title.set_fontsize(8)
    fig.suptitle(f"Accuracy against cost over the fidelity ladder (wall times on {d.machine.iloc[0]})", fontsize=9, y=1.04)
    save(fig, outputs.png, params.dpi)
