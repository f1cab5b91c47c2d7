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


def _fe_labels(ax, d, column, scale):
    """The FE meshes' labels in a column to the right of their points, each joined to its point by a thin line and
    spaced at least 7 % of the axis apart in the order of their values (the meshes' costs lie too close together on
    the log axis to label beside each point)."""
    fe = d[d.level == "fe"]
    if fe.empty:
        return
    fe = fe.assign(y=scale * fe[column]).sort_values("y")
    low, high = ax.get_ylim()
    gap = 0.07 * (high - low)
    x_text = 10 * fe.wall_time_per_shot_s.max()
    placed = []
    for y in fe.y:
        placed.append(max(y, placed[-1] + gap) if placed else y)
    shift = max(0.0, placed[-1] - (high - gap))   # keep the column inside the axis
    for row, y_text in zip(fe.itertuples(), placed):
        ax.annotate(_label(row), (row.wall_time_per_shot_s, row.y), xytext=(x_text, y_text - shift),
                    textcoords="data", fontsize=7, va="center",
                    arrowprops={"arrowstyle": "-", "lw": 0.5, "color": "0.6", "shrinkA": 0, "shrinkB": 3})
    left, right = ax.get_xlim()
    ax.set_xlim(left, max(right, 60 * x_text))


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
            if level != "fe":
                for row in g.itertuples():
                    if _label(row):
                        ax.annotate(_label(row), (row.wall_time_per_shot_s, scale * getattr(row, column)), fontsize=7,
                                    xytext=(4, 3), textcoords="offset points")
        ax.set(xscale="log", xlabel="wall time per shot (s)", ylabel=ylabel, title=title)
        ax.title.set_fontsize(9)
        top = ax.get_ylim()[1]
        ax.set_ylim(0, 1.15 * top if np.isfinite(top) else 1)
        _fe_labels(ax, d.dropna(subset=[column, "wall_time_per_shot_s"]), column, scale)
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
