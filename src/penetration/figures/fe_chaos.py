"""Drawing of the erosion-free target's grid study with the chaos in its error model (tasks.fe_chaos)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .common import PAPER_STYLE, save

MM = 1e-3
CONTRAST_COLORS = {"DO/CRH 4.5": "tab:green", "DO/CRH 3": "tab:purple", "CRH 4.5/CRH 3": "tab:blue"}


def chaos_figure(cells, rows, path, dpi, where=""):
    """One panel per velocity: each contrast's realisations' mean +- 2 s.e. on every mesh (ratio - 1 in points
    against the element size; the standard errors of the chaos pooled over the meshes, as the fit's), its weighted
    first-order line, the estimate at zero size +- U and the paper's simulated value (a cross at zero size).
    ``where``: the scene's words for the title."""
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3})
    con = cells[cells.kind == "contrast"]
    vs = sorted(con.velocity_ms.unique())
    fig, axes = plt.subplots(1, len(vs), figsize=(4.4 * len(vs), 3.9), squeeze=False)
    for j, v in enumerate(vs):
        ax = axes[0, j]
        for k, (name, color) in enumerate(CONTRAST_COLORS.items()):
            g = con[(con.quantity == name) & (con.velocity_ms == v)].sort_values("element_size_m")
            if g.empty:
                continue
            dx = (k - 1) * 0.06
            r = rows[(rows.quantity == name) & (rows.velocity_ms == v)]
            pooled = float(r.iloc[0].get("sd_pooled", np.nan)) if len(r) else np.nan
            se = pooled / np.sqrt(g.realisations) if np.isfinite(pooled) else g.se   # the fit's errors
            ax.errorbar(g.element_size_m / MM + dx, 100 * (g["mean"] - 1), yerr=200 * se, fmt="o", ms=3.5,
                        color=color, capsize=2, label=f"{name}: mean of {int(g.realisations.min())}+ realisations +- 2 s.e.")
            if r.empty or not np.isfinite(r.iloc[0].get("zero_size", np.nan)):
                continue
            r = r.iloc[0]
            h = np.linspace(0, g.element_size_m.max() / MM, 40)
            ax.plot(h, 100 * (r.zero_size - 1) + 100 * r.slope_per_m * h * MM, color=color, lw=0.9, ls="--")
            ax.errorbar([-0.35 + dx], [100 * (r.estimate - 1)], yerr=[100 * r.uncertainty], fmt="s", ms=4,
                        color=color, capsize=3)
            if np.isfinite(r.paper):
                ax.plot([-0.7 + dx], [100 * (r.paper - 1)], **{**PAPER_STYLE, "color": color, "markersize": 6})
        ax.axhline(0, color="0.3", lw=0.7)
        ax.set_xlim(-1.0, None)
        ax.set_xlabel("element size (mm); squares at 0: zero-size estimate +- U, crosses: paper")
        ax.set_ylabel("depth ratio - 1 (points)")
        ax.set_title(f"{v:g} m/s, erosion-free target{where}")
    axes[0, 0].legend(fontsize=6.5, loc="best")
    fig.tight_layout()
    save(fig, path, dpi)
