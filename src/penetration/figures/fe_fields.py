"""The FE target's state at one time drawn on its deformed mesh: damage, plastic strain and pressure around the
projectile (elements that carry stress; eroded and ejected ones left out)."""
from __future__ import annotations

import numpy as np

from .common import figure, save

LIVE = 1   # fe.state.LIVE (figures import no physics: the code is the state file's)


def draw_snapshot(snap: dict, conn, radius: float, path, title: str, dpi=150):
    """``snap``: fe.shot.snapshot's dict (r, z of the nodes; damage, eps_p, pressure, state per element); ``conn``
    the elements' corner nodes; ``radius`` the shank radius (m) that sets the window drawn."""
    from matplotlib.collections import PolyCollection
    depth = snap["depth"]
    r, z = snap["r"], snap["z"]
    # the model's z is the depth below the struck face (ejecta above it: z < 0)
    keep = snap["state"] == LIVE
    rc, dc = r[conn].mean(axis=1), z[conn].mean(axis=1)
    keep &= (rc < 8 * radius) & (dc < depth + 6 * radius) & (dc > -2 * radius)
    polys = np.stack([1e3 * r[conn[keep]], 1e3 * z[conn[keep]]], axis=-1)
    fig, axes = figure(3, 3.6, 5.2)
    for ax, (name, values, label, cmap) in zip(axes, (
            ("damage", snap["damage"], "damage D", "magma_r"),
            ("eps_p", snap["eps_p"], "plastic strain", "viridis"),
            ("pressure", snap["pressure"] / 1e6, "pressure (MPa)", "coolwarm"))):
        pc = PolyCollection(polys, array=values[keep], cmap=cmap, edgecolors="none")
        if name == "pressure":
            lim = max(1.0, float(np.nanpercentile(np.abs(values[keep]), 99)) if keep.any() else 1.0)
            pc.set_clim(-lim, lim)
        ax.add_collection(pc)
        fig.colorbar(pc, ax=ax, label=label, shrink=0.8)
        ax.set(xlim=(0, 8e3 * radius), ylim=(1e3 * (depth + 6 * radius), -2e3 * radius), aspect="equal",
               xlabel="radius r (mm)", ylabel="depth below the struck face (mm)")
        ax.axhline(1e3 * depth, color="black", lw=0.6, ls="--")
        ax.grid(False)
    fig.suptitle(f"{title}\nt = {1e3 * snap['t']:.3f} ms, tip at {depth:.3f} m (dashed)", fontsize=9)
    save(fig, path, dpi)
