"""Shared drawing helpers: style, atomic PNG output, paper-value markers."""
from __future__ import annotations

import matplotlib
import pandas as pd

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..pipeline.io import atomic  # noqa: E402

PAPER_STYLE = dict(color="black", linestyle="none", marker="x", markersize=8, mew=1.6)
NOSE_COLORS = {"crh3": "tab:red", "crh5": "tab:blue", "crh45": "tab:blue", "double_ogive": "tab:green",
               "cone": "tab:orange", "minimum_nstar": "tab:purple"}


def figure(ncols=1, width=6.4, height=4.2):
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3})
    fig, axes = plt.subplots(1, ncols, figsize=(width * ncols, height), squeeze=False)
    return fig, axes[0]


def save(fig, path, dpi):
    try:
        with atomic(path) as tmp:
            fig.savefig(tmp, dpi=dpi, bbox_inches="tight", format="png", metadata={"Software": None})
    finally:
        plt.close(fig)


def ending_at_rest(hist, keys):
    """Histories with a last point per trace (``keys``) at zero deceleration at the time of rest.

    The resistance acts only while the projectile moves, so the deceleration
    drops from its final plateau to zero when it stops.
    """
    rest = hist.groupby(keys, sort=False).tail(1).assign(deceleration=0.0)
    return pd.concat([hist, rest]).sort_index(kind="stable").reset_index(drop=True)


def color(name):
    return NOSE_COLORS.get(name.removeprefix("fig4_"), "gray")


def do1_histories(t_ms, pd_over_d, velocity, refs, level, title, xlim):
    """Fig 12's drawing: Pd/d and velocity of the DO1 shot against time, with the measured depth."""
    fig, (ax,) = figure(1, 6.2, 4.2)
    ax.plot(t_ms, pd_over_d, color="tab:green", label=f"Pd/d (ours, {level})")
    exp = refs["table2.dop"].si / refs["table2.diameter"].si
    ax.axhline(exp, color=PAPER_STYLE["color"], ls="--", lw=1,
               label=f"experiment DO1: {refs['table2.dop'].value} m (Pd/d = {exp:.1f})")
    ax.set(xlabel="t (ms)", ylabel="Pd/d", ylim=(0, 40), xlim=xlim, title=title)
    ax2 = ax.twinx()
    ax2.plot(t_ms, velocity, color="tab:blue", label="velocity (ours)")
    ax2.set(ylabel="velocity (m/s)", ylim=(0, 900))
    ax.legend(loc="lower center", fontsize=7)
    ax2.legend(loc="lower right", fontsize=7)
    return fig
