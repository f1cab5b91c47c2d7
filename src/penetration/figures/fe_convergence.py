"""Drawing of the FE nose contrasts' regression on the element size (tasks.fe_studies) and of the erosion-free
target's grid convergence (tasks.fe_erosion_free)."""
from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt
import numpy as np

from .common import NOSE_COLORS, PAPER_STYLE, save

MM = 1e-3


def contrast_extrapolation_figure(cells, meshes, singles, path, dpi):
    """One panel per contrast (rows) and velocity (columns): the band meshes, the fitted line with its interval
    at h = 0, the single-mesh series (the coarsest drawn at the right edge, its size in the tick label) and the
    paper's simulated value."""
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3})
    names = list(dict.fromkeys(cells.contrast))
    vs = sorted(cells.velocity_ms.unique())
    fig, axes = plt.subplots(len(names), len(vs), figsize=(2.45 * len(vs), 2.35 * len(names)), sharex=True,
                             sharey="row", squeeze=False)
    hmax = 1.08 * meshes.element_size_m.max() / MM
    edge = hmax + 0.9  # where a single mesh coarser than the bands is drawn
    for i, name in enumerate(names):
        for j, v in enumerate(vs):
            ax = axes[i, j]
            c = cells[(cells.contrast == name) & (cells.velocity_ms == v)].iloc[0]
            g = meshes[(meshes.contrast == name) & (meshes.velocity_ms == v)]
            ax.plot(g.element_size_m / MM, 100 * (g.fe_ratio - 1), "o", ms=2.8, color="tab:blue", alpha=0.6,
                    label=f"one mesh of the bands ({c.meshes})")
            h = np.linspace(0, c.element_size_max_m / MM, 50)
            slope = c.slope_points_per_mm
            ax.plot(h, 100 * (c.ratio_at_zero_size - 1) + slope * h, color="tab:blue", lw=1,
                    label="least-squares line")
            ax.errorbar([0.25], [100 * (c.ratio_at_zero_size - 1)],
                        yerr=[[100 * (c.ratio_at_zero_size - c.interval_low)], [100 * (c.interval_high - c.ratio_at_zero_size)]],
                        fmt="s", ms=4, color="tab:blue", capsize=3,
                        label=f"at zero size, {100 * c.confidence:.0f} % interval")
            s = singles[(singles.contrast == name) & (singles.velocity_ms == v)].sort_values("element_size_m")
            x, y = (s.element_size_m / MM).to_numpy(), 100 * (s.fe_ratio.to_numpy() - 1)
            near = x <= hmax
            ax.plot(x[near], y[near], "D-", ms=3.5, lw=0.8, color="tab:orange",
                    label="single meshes, 12/10/8/3 across")
            if (~near).any():  # across the axis break: dotted
                k = np.flatnonzero(near)[-1]
                ax.plot([x[k], edge], [y[k], y[~near][0]], ":", lw=0.8, color="tab:orange")
                ax.plot([edge], [y[~near][0]], "D", ms=3.5, color="tab:orange")
            ax.plot([0.75], [100 * (c.paper_sim_ratio - 1)], **PAPER_STYLE, label="paper's simulation")
            ax.axhline(0, color="black", lw=0.5)
            if i == 0:
                ax.set_title(f"{v} m/s")
            if j == 0:
                ax.set_ylabel(f"{name}\ndepth gain (%)")
            if i == len(names) - 1:
                ax.set_xlabel("element size (mm)")
    coarse = singles.element_size_m.max() / MM
    ticks = [t for t in range(0, int(hmax) + 1, 2)]
    for ax in axes[-1]:
        ax.set_xticks([*ticks, edge], [*(f"{t}" for t in ticks), f"{coarse:.0f}"])
        ax.set_xlim(-0.3, edge + 0.6)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, bbox_to_anchor=(0.5, -0.01))
    fig.suptitle("Nose contrasts of Table 3 at the eroding FE level against the element size, each mesh calibrated "
                 "on DO1:\nthe line over the band meshes extrapolated to zero size (the rightmost tick: the 3-across "
                 "mesh, off scale)", fontsize=9)
    fig.subplots_adjust(bottom=0.15, top=0.88, wspace=0.08, hspace=0.12)
    save(fig, path, dpi)


CONTRAST_COLORS = {"DO/CRH 4.5": "tab:green", "CRH 4.5/CRH 3": "tab:blue", "DO/CRH 3": "tab:purple"}
HOLE_STYLES = ("-", "--", ":", "-.")


def grid_convergence_figure(conv, holes, path, dpi):
    """The erosion-free target's grid convergence, one column per velocity: depths (top row) and nose contrasts as
    depth gains (middle row) against the element size, one line per pilot hole, with each hole's Richardson
    extrapolation at zero size and the finest mesh's GCI as its bar (hollow: not in the asymptotic range), and the
    finest value's least-squares (Eça-Hoekstra) interval as a bar between them (one per hole); the
    zero-size values against the pilot hole (bottom row: depths scaled by their zero-hole value, and the gains),
    extrapolated to zero hole with the larger of the hole's and the meshes' GCI as the bar; the paper's simulated
    values as crosses."""
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3})
    cols = [c for c in conv.columns if c.startswith("value_at_")]
    across = np.array([float(c.split("_")[2]) for c in cols])
    h = 70.0 / across   # mm: the 70 mm shank radius over the elements across
    vs = sorted(conv.velocity_ms.unique())
    hole_sizes = sorted(conv.pilot_hole.unique(), reverse=True)
    fig, axes = plt.subplots(3, len(vs), figsize=(5.2 * len(vs), 11.0), squeeze=False)
    kinds = (("depth_m", NOSE_COLORS, 1.0, 0.0, "depth (m)"),
             ("depth_ratio", CONTRAST_COLORS, 100.0, 1.0, "depth gain of the contrast (%)"))
    for j, v in enumerate(vs):
        for i, (quantity, colors, scale, offset, label) in enumerate(kinds):
            ax = axes[i, j]
            rows = conv[(conv.quantity == quantity) & (conv.velocity_ms == v)].to_dict("records")
            for r in rows:
                k = hole_sizes.index(r["pilot_hole"])
                color = colors.get(r["case"], "gray")
                y = scale * (np.array([r[c] for c in cols]) - offset)
                ax.plot(h, y, "o", ls=HOLE_STYLES[k % 4], ms=2.5, lw=0.9, color=color,
                        label=r["case"] if k == 0 else None)
                if r["status"] == "asymptotic":   # an estimate: the axes hold it
                    ax.plot([-0.3 - 0.25 * k], [scale * (r["extrapolated"] - offset)], alpha=0)
            for r in rows[:len(rows) // len(hole_sizes)]:
                if np.isfinite(r["paper_simulated"]):
                    ax.plot([h.max() + 0.7], [scale * (r["paper_simulated"] - offset)],
                            **{**PAPER_STYLE, "color": colors.get(r["case"], "gray")})
            # the limits are set by the meshes' values, the paper's and the extrapolations in the asymptotic range; a
            # Richardson value outside the asymptotic range (not an estimate) that falls beyond them is a hollow
            # triangle at the edge, and every bar is cut at the axes
            ax.autoscale_view()
            lim = ax.get_ylim()
            for r in rows:
                k = hole_sizes.index(r["pilot_hole"])
                color, x = colors.get(r["case"], "gray"), -0.3 - 0.25 * k
                y = scale * (r["extrapolated"] - offset)
                if lim[0] <= y <= lim[1]:
                    ax.errorbar([x], [y], yerr=[scale * r["gci_fine"]], fmt="s", ms=3.5, color=color,
                                mfc=color if r["status"] == "asymptotic" else "white", capsize=2)
                elif np.isfinite(y):
                    edge = lim[1] if y > lim[1] else lim[0]
                    ax.plot([x], [edge], "^" if y > lim[1] else "v", ms=4.5, color=color, mfc="white", clip_on=False)
            # each hole's least-squares interval of its finest value (thin bars right of the finest mesh)
            for r in rows:
                u = r.get("ls_uncertainty", np.nan)
                if np.isfinite(u):
                    k = hole_sizes.index(r["pilot_hole"])
                    ax.errorbar([1.6 + 0.5 * k], [scale * (r["ls_value"] - offset)], yerr=[scale * u],
                                fmt="_", ms=5, elinewidth=0.9, capsize=0, color=colors.get(r["case"], "gray"))
            ax.set_ylim(lim)
            if i == 0:
                ax.set_title(f"{v:g} m/s")
            if i == 1:
                ax.axhline(0, color="black", lw=0.5)
            ax.set_xlabel("element size (mm)")
            ax.set_xlim(-1.3, h.max() + 1.2)
            if j == 0:
                ax.set_ylabel(label)
        ax = axes[2, j]
        t = holes[holes.velocity_ms == v].to_dict("records")
        for r in t:
            x = np.array(hole_sizes)
            if str(r.get("limit_found", True)) != "True":
                # no limit under refinement: each hole's values over its meshes (median, range), nothing at zero
                g = conv[(conv.quantity == r["quantity"]) & (conv.case == r["case"]) & (conv.velocity_ms == v)]
                g = g.set_index("pilot_hole").loc[hole_sizes, cols].to_numpy()
                ref = r["values_median"] if r["quantity"] == "depth_m" else 1.0
                vals = 100 * (g / ref - 1)
                med, lo, hi = np.nanmedian(vals, axis=1), np.nanmin(vals, axis=1), np.nanmax(vals, axis=1)
                if r["quantity"] == "depth_m":
                    color, name = NOSE_COLORS.get(r["case"], "gray"), f"{r['case']} depth, % of its median"
                else:
                    color, name = CONTRAST_COLORS.get(r["case"], "gray"), f"{r['case']} gain (%)"
                    if np.isfinite(r["paper_simulated"]):
                        ax.plot([0.56], [100 * (r["paper_simulated"] - 1)], **{**PAPER_STYLE, "color": color})
                ax.errorbar(x, med, yerr=[med - lo, hi - med], fmt="o-" if r["quantity"] == "depth_ratio" else "o:",
                            ms=3, lw=0.9, capsize=2, color=color, label=name)
                continue
            f = np.array([r[f"zero_size_at_hole_{x_:g}"] for x_ in hole_sizes])
            if r["quantity"] == "depth_m":
                y, y0, err = 100 * (f / r["at_zero_hole"] - 1), 0.0, 100 * r["uncertainty"] / r["at_zero_hole"]
                color, name = NOSE_COLORS.get(r["case"], "gray"), f"{r['case']} depth, % of its zero-hole value"
            else:
                y, y0, err = 100 * (f - 1), 100 * (r["at_zero_hole"] - 1), 100 * r["uncertainty"]
                color, name = CONTRAST_COLORS.get(r["case"], "gray"), f"{r['case']} gain (%)"
                if np.isfinite(r["paper_simulated"]):
                    ax.plot([0.56], [100 * (r["paper_simulated"] - 1)], **{**PAPER_STYLE, "color": color})
            ax.plot(x, y, "o-" if r["quantity"] == "depth_ratio" else "o:", ms=3, lw=0.9, color=color, label=name)
            ax.errorbar([0.0], [y0], yerr=[err], fmt="s", ms=3.5, color=color, capsize=2,
                        mfc=color if r["hole_status"] == "asymptotic" else "white")
        ax.set_xlabel("pilot hole / shank radius")
        ax.set_xlim(-0.04, 0.6)
        if j == 0:
            ax.set_ylabel("over the holes (%)")
    axes[0, -1].legend(fontsize=7, loc="best")
    axes[1, -1].legend(fontsize=7, loc="best")
    axes[2, -1].legend(fontsize=6, loc="best")
    title = ("Erosion-free target (Table 1's HJC as stated): Table 3 rows on meshes refined by "
             f"{across[1] / across[0]:.3g} ({', '.join(f'{n:g}' for n in across)} elements across the shank radius) "
             f"at pilot holes of {', '.join(f'{x:g}' for x in hole_sizes)} of it (solid, dashed, dotted). "
             "Squares: Richardson extrapolation with its GCI (hollow: not in the asymptotic range, not an estimate; a hollow "
             "triangle at the edge: such a value beyond the axes); "
             "crosses: the paper's simulation (LS-DYNA with erosion); bars at 1.6-2.6 mm: each hole's finest value "
             f"with its least-squares uncertainty (Eça & Hoekstra 2014, over the {len(cols)} meshes; cut at the axes). "
             "Bottom: the zero-size values against the pilot hole, extrapolated to zero hole; where the refinement "
             "finds no limit, each hole's median and range over its meshes instead.")
    fig.suptitle("\n".join(textwrap.wrap(title, 70 * len(vs))), fontsize=9)
    fig.subplots_adjust(top=0.86, wspace=0.2, hspace=0.28)
    save(fig, path, dpi)
