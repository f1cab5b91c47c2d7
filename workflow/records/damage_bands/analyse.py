"""The damage bands of the runs of workflow/records/damage_bands: their spacing in depth and in the time of the
tip's passage, per run, and a figure of the damage fields side by side (bands.png).

Usage (from the repository root, after run.py): python workflow/records/damage_bands/analyse.py NAME [NAME ...]
"""
import json
import sys
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = Path(__file__).parent
D = 0.14


def bands(name, r_over_d=2.0, level=0.9):
    """Depths (m) where the damage in the column nearest r0 = r_over_d d rises through `level` into a band at least
    two elements deep, and the tip's passage times there (s)."""
    f = pd.read_csv(HERE / f"{name}_fields.csv.gz")
    h = pd.read_csv(HERE / f"{name}_histories.csv.gz")
    r0 = min(f.r0.unique(), key=lambda x: abs(x - r_over_d * D))
    c = f[f.r0 == r0].sort_values("z0")
    z, hi = c.z0.to_numpy(), c.damage.to_numpy() > level
    starts = [k for k in range(1, len(z) - 2) if hi[k] and hi[k + 1] and not hi[k - 1]]
    zs = z[starts]
    ts = np.interp(zs, h.depth, h.t)
    return zs, ts, float(h.depth.iloc[-1])


if __name__ == "__main__":
    names = sys.argv[1:]
    fig, axes = plt.subplots(1, len(names), figsize=(3.0 * len(names), 5.5), sharey=True, squeeze=False)
    for ax, name in zip(axes[0], names):
        zs, ts, depth = bands(name)
        main = np.diff(ts)[np.diff(ts) > 3e-4]  # gaps between bands, the sub-bands of one band (< 0.3 ms) aside
        print(json.dumps({"name": name, "bands": len(zs), "depth_m": round(depth, 4),
                          "band_depths_over_d": [round(x / D, 2) for x in zs],
                          "passage_times_ms": [round(1e3 * x, 3) for x in ts],
                          "median_gap_ms": round(1e3 * float(np.median(main)), 3) if len(main) else None}))
        f = pd.read_csv(HERE / f"{name}_fields.csv.gz")
        live = f[f.state.isin((1, 4))]
        ax.scatter(live.r0 / D, live.z0 / D, c=live.damage, s=1.0, cmap="viridis", vmin=0, vmax=1, rasterized=True)
        ax.set(xlim=(0, 4), xlabel="r0/d", title=name)
    axes[0][0].set_ylabel("z0/d")
    axes[0][0].invert_yaxis()
    fig.savefig(HERE / "bands.png", dpi=110, bbox_inches="tight")
