"""A user's nose comparison drawn: per level, depth against velocity per nose (top) and each nose's contrast
against the reference nose with its combined uncertainty (bottom)."""
from __future__ import annotations

import numpy as np

from ..pipeline.io import write_csv
from .common import save
from .nose_outline import draw_noses

COLORS = ("tab:red", "tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:gray", "tab:olive",
          "tab:pink", "tab:cyan", "black", "gold")


def draw_comparison(table, path, title: str, dpi=150):
    """``table``: shots.compare.tabulate's rows (level, nose, velocity_ms, depth_m, contrast, u_combined)."""
    import matplotlib.pyplot as plt
    levels = list(dict.fromkeys(table.level))
    noses = list(dict.fromkeys(table.nose))
    fig, axes = plt.subplots(2, len(levels), figsize=(4.6 * len(levels), 7.0), squeeze=False, sharex=True)
    plt.rcParams.update({"font.size": 9})
    for j, lv in enumerate(levels):
        top, bottom = axes[0][j], axes[1][j]
        g = table[table.level == lv]
        for i, n in enumerate(noses):
            h = g[g.nose == n].sort_values("velocity_ms")
            c = COLORS[i % len(COLORS)]
            top.plot(h.velocity_ms, h.depth_m, "o-", color=c, ms=3, label=n)
            x, y = h.velocity_ms.to_numpy(), h.contrast.to_numpy()
            band = np.nan_to_num((h.u_combined * h.contrast).to_numpy())
            model = np.sqrt(np.nansum(np.square(h[["u_calibration", "u_chaos", "u_mesh"]].to_numpy()), axis=1)) * y
            if band.any():
                bottom.fill_between(x, y - band, y + band, color=c, alpha=0.08, lw=0)
            bottom.errorbar(x + 4.0 * (i - 0.5 * (len(noses) - 1)), y, yerr=model, fmt="o-", color=c, ms=3, capsize=2,
                            label=n)
        ref = g.reference.iloc[0]
        top.set(title=f"{lv}", ylabel="depth of penetration (m)")
        bottom.set(xlabel="striking velocity (m/s)", ylabel=f"depth / depth of {ref}")
        bottom.axhline(1.0, color="black", lw=0.6)
        for ax in (top, bottom):
            ax.grid(True, alpha=0.3)
        top.legend(fontsize=7)
    fig.suptitle(title + "\nbands: the contrast's combined uncertainty; bars: its model parts (calibration, chaos, "
                 "mesh) without the validated error (compare.csv names the parts)", fontsize=9)
    fig.tight_layout()
    save(fig, path, dpi)


def write_comparison(files: dict, table, noses, curves, title, dpi=150):
    """Write a comparison into ``files`` (shots.compare.output_files): the table, the noses' table, the figure
    and the noses' outlines, each atomically."""
    write_csv(table, files["compare.csv"])
    write_csv(noses, files["noses.csv"])
    draw_comparison(table, files["compare.png"], title, dpi)
    draw_noses(curves, files["noses.png"], title, dpi)
