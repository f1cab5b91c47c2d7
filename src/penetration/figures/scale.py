"""The scale effect's figures: depth over calibre under geometric similarity (rule scale_similarity)."""
from __future__ import annotations

from .common import figure, save

VARIANT_STYLE = {"none": ("black", "-"), "rate_cap": ("gray", ":"), "rate": ("tab:red", "-"),
                 "fracture": ("tab:blue", "-"), "fracture_a8": ("tab:blue", "--"), "fracture_a32": ("tab:blue", ":"),
                 "rate_fracture": ("tab:purple", "-")}
LEVEL_MARKER = {"analytic": "o", "trajectory": "s", "cavity": "^", "fe": "D"}
EMPIRICAL_STYLE = {"ndrc": "--", "ace": "-.", "brl": ":"}
# the factor each level was fitted with on the laboratory shots
FACTOR_LABEL = {"s_scale": "S x", "strength_scale": "strength x", "fs": "fs"}
CALIBRES = {"laboratory 2003 (26.9 mm)": 0.0269, "laboratory 1994 (76.2 mm)": 0.0762, "DO1 (140 mm)": 0.14}


def similarity_figure(table, spec, path, dpi):
    """X/d against calibre (log-log), one panel per level: its variants (each with its factor calibrated on the
    laboratory shots) beside the empirical formulas (their own constants) as the size laws they carry."""
    levels = [lv for lv in LEVEL_MARKER if lv in set(table.level[table.kind == "level"])]
    fig, axes = figure(len(levels), 4.6, 4.6)
    empirical = table[table.kind == "empirical"]
    y = table.depth_over_calibre
    for ax, level in zip(axes, levels):
        rows = table[(table.kind == "level") & (table.level == level)]
        for variant, g in rows.groupby("variant", sort=False, dropna=False):
            c, ls = VARIANT_STYLE.get(variant, ("tab:green", "-"))
            ax.plot(g.calibre_m * 1e3, g.depth_over_calibre, color=c, ls=ls, marker=LEVEL_MARKER[level], ms=3.5,
                    lw=1.2, label=f"{variant} ({FACTOR_LABEL.get(g.parameter.iloc[0], g.parameter.iloc[0])} "
                                  f"{g.value.iloc[0]:.3g})")
        for name, g in empirical.groupby("level", sort=False):
            ax.plot(g.calibre_m * 1e3, g.depth_over_calibre, color="darkgoldenrod", ls=EMPIRICAL_STYLE.get(name, "--"),
                    lw=1.0, label=f"{name.upper()} formula")
        for name, d in CALIBRES.items():
            ax.axvline(d * 1e3, color="0.6", lw=0.8, ls="--")
            ax.text(d * 1e3, 0.02, name, rotation=90, transform=ax.get_xaxis_transform(), fontsize=6.5, color="0.35",
                    ha="right", va="bottom")
        ax.set(xscale="log", yscale="log", xlabel="calibre d (mm)", ylim=(0.9 * y.min(), 1.1 * y.max()),
               title=f"{level} level")
        ax.legend(fontsize=6.5, loc="upper left", title="variant (factor fitted on the laboratory shots)",
                  title_fontsize=6.5)
    axes[0].set_ylabel("depth over calibre X/d")
    fig.suptitle(f"Geometric similarity: CRH {spec['crh']:g} ogive at {spec['velocity']:g} m/s into "
                 f"{spec['fc'] / 1e6:g} MPa concrete, M/d^3 and L/d of DO1")
    save(fig, path, dpi)
