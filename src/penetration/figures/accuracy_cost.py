"""Accuracy against cost over the fidelity ladder: prediction errors (tasks.accuracy) against wall time per shot."""
from __future__ import annotations

import numpy as np

from .common import figure, save

STYLE = {"analytic": ("tab:gray", "s"), "trajectory": ("tab:orange", "^"), "cavity": ("tab:blue", "o"),
         "fe": ("tab:green", "D")}
PANELS = (("table3_other_noses_mean_abs_rel_dev", 100, "mean |deviation| (%)",
           "Table 3 of the paper's simulation,\nthe noses not calibrated on (CRH 4.5, CRH 3: 8 cells)"),
          ("contrast_mean_abs_points", 1, "mean |difference| (points)",
           "the paper's simulated nose contrasts\n(3 contrasts x 4 velocities)"),
          ("validation_median_abs_rel_err", 100, "median |error| (%)",
           "the 25 published development shots\n(each level scored on shots it was not fitted to)"))


def _label(row):
    if row.level == "fe":
        return row.setting.split(" elements")[0] + " across"
    return {"S stated (Li & Chen)": "S stated", "S calibrated on DO1": "S on DO1"}.get(row.setting, "")


def accuracy_cost_drawing(d, path, dpi):
    """One panel per prediction error; each level's settings against their wall time per shot (log scale); an
    analytic setting calibrated on DO1 hollow."""
    fig, axes = figure(3, 4.2, 4.0)
    for ax, (column, scale, ylabel, title) in zip(axes, PANELS):
        for level, g in d.dropna(subset=[column, "wall_time_per_shot_s"]).groupby("level", sort=False):
            c, mk = STYLE[level]
            g = g.sort_values("wall_time_per_shot_s")
            if level == "fe":
                ax.plot(g.wall_time_per_shot_s, scale * g[column], mk + "-", color=c, ms=6, label="fe (per mesh)")
            for row in g.itertuples():
                if level != "fe":
                    hollow = "calibrated" in row.setting
                    ax.plot(row.wall_time_per_shot_s, scale * getattr(row, column), mk, color=c, ms=6,
                            mfc="white" if hollow else c, label=f"{level}" + (" (hollow: S calibrated on DO1)"
                                                                              if hollow else ""))
            for k, row in enumerate(g.itertuples()):
                text = _label(row)
                if text:  # the FE meshes' labels alternate above and below their points
                    ax.annotate(text, (row.wall_time_per_shot_s, scale * getattr(row, column)), fontsize=7,
                                xytext=(4, 3 if level != "fe" or k % 2 == 0 else -11), textcoords="offset points")
        ax.set(xscale="log", xlabel="wall time per shot (s)", ylabel=ylabel, title=title)
        ax.title.set_fontsize(9)
        top = ax.get_ylim()[1]
        ax.set_ylim(0, 1.15 * top if np.isfinite(top) else 1)
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8, bbox_to_anchor=(0.5, -0.04))
    machine = d.machine.dropna().iloc[0] if "machine" in d and d.machine.notna().any() else "this machine"
    fig.suptitle(f"Prediction error against cost over the fidelity ladder (wall times on {machine})", fontsize=10, y=1.02)
    fig.subplots_adjust(wspace=0.3, bottom=0.2)
    save(fig, path, dpi)
