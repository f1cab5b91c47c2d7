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
    """X/d against calibre (log-log): each level and variant (its factor calibrated on the laboratory shots), and
    the empirical formulas (their own constants) as the size laws they carry."""
    fig, (ax,) = figure(1, 7.2, 4.8)
    for (kind, level, variant), g in table.groupby(["kind", "level", "variant"], sort=False, dropna=False):
        x, y = g.calibre_m * 1e3, g.depth_over_calibre
        if kind == "empirical":
            ax.plot(x, y, color="darkgoldenrod", ls=EMPIRICAL_STYLE.get(level, "--"), lw=1.2,
                    label=f"{level.upper()} formula (its own constants)")
        else:
            c, ls = VARIANT_STYLE.get(variant, ("tab:green", "-"))
            ax.plot(x, y, color=c, ls=ls, marker=LEVEL_MARKER.get(level, "o"), ms=3.5, lw=1.2,
                    label=f"{level}, {variant} ({FACTOR_LABEL.get(g.parameter.iloc[0], g.parameter.iloc[0])} "
                          f"{g.value.iloc[0]:.3g})")
    for name, d in CALIBRES.items():
        ax.axvline(d * 1e3, color="0.6", lw=0.8, ls="--")
        ax.text(d * 1e3, 0.02, name, rotation=90, transform=ax.get_xaxis_transform(), fontsize=6.5, color="0.35",
                ha="right", va="bottom")
    ax.set(xscale="log", yscale="log", xlabel="calibre d (mm)", ylabel="depth over calibre X/d",
           title=f"Geometric similarity: CRH {spec['crh']:g} ogive at {spec['velocity']:g} m/s into "
                 f"{spec['fc'] / 1e6:g} MPa concrete, M/d^3 of DO1")
    ax.legend(fontsize=6.5, loc="upper left", ncol=2)
    save(fig, path, dpi)
