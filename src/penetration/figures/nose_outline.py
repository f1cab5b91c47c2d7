"""A user's noses drawn: the outline (mirrored about the axis) and the cumulative N* from the tip (Eq 5)."""
from __future__ import annotations

from .common import figure, save

COLORS = ("tab:red", "tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:gray", "tab:olive")


def draw_noses(curves: dict, path, title: str, dpi=150):
    """Write a PNG of noses (``curves``: label -> (x, y, cumulative N*) from the tip, m, as
    nose.nstar.cumulative_nstar gives them): outline in mm and cumulative N* against the distance from the tip."""
    fig, (ax, bx) = figure(2, 5.0, 3.8)
    for i, (label, (x, y, n)) in enumerate(curves.items()):
        c = COLORS[i % len(COLORS)]
        ax.plot(1e3 * x, 1e3 * y, color=c, label=label)
        ax.plot(1e3 * x, -1e3 * y, color=c)
        bx.plot(1e3 * x, n, color=c, label=f"{label}: N* = {n[-1]:.4g}")
    ax.axhline(0.0, color="black", lw=0.5, ls="-.")
    ax.set(xlabel="distance from the tip x (mm)", ylabel="radius y (mm)", title="outline", aspect="equal")
    bx.set(xlabel="distance from the tip x (mm)", ylabel="cumulative N* (Eq 5)", title="N* from the tip")
    ax.legend(fontsize=7, loc="upper left")
    bx.legend(fontsize=7, loc="upper left")
    fig.suptitle(title, fontsize=9)
    save(fig, path, dpi)
