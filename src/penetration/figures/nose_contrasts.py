"""Nose-shape contrasts: DO/CRH 4.5, DO/CRH 3 and CRH 4.5/CRH 3 depth ratios and gains at every level."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import committed_studies, committed_study, task, write_csv
from .common import PAPER_STYLE, figure, save

PANELS = ("DO/CRH 4.5", "DO/CRH 3", "CRH 4.5/CRH 3")
# the text's claims drawn on the ratio panels: contrast -> reference id of "+x % at the same velocity"
CLAIMS = {"DO/CRH 4.5": "text.gain_pct_crh45", "DO/CRH 3": "text.gain_pct_crh3"}
GAINS_1200 = {"DO/CRH 4.5": "text.gain_1200_crh45", "DO/CRH 3": "text.gain_1200_crh3"}
LINES = {("analytic", "Eq 9, S calibrated on DO1"): dict(color="tab:blue", ls="-", lw=1.4),
         ("trajectory", "Eq 7/8 integrated, S calibrated on DO1"): dict(color="tab:cyan", ls=":", lw=2.0),
         ("cavity", "strength scale calibrated on DO1"): dict(color="tab:green", ls="-", lw=1.4)}


def wide_table(data):
    """One row per (contrast, velocity) at Table 3's velocities: each source's ratio and gain."""
    t3 = data[data.source == "table3"]
    out = t3[["contrast", "velocity"]].drop_duplicates().reset_index(drop=True)
    idx = pd.MultiIndex.from_frame(out[["contrast", "velocity"]])
    sources = [(name, t3[(t3.level == level) & (t3.variant == variant)])
               for name, level, variant in (("paper_sim", "paper", "simulation (LS-DYNA, fs calibrated on DO1)"),
                                            ("paper_calc", "paper", "calculation (Eq 9)"),
                                            ("analytic", "analytic", "Eq 9, S calibrated on DO1"),
                                            ("analytic_stated_S", "analytic", "Eq 9, S = 72 fc^-0.5"),
                                            ("cavity", "cavity", "strength scale calibrated on DO1"))]
    sources.append(("trajectory", data[(data.source == "fig15") & (data.level == "trajectory")]))
    for name, rows in sources:
        g = rows.set_index(["contrast", "velocity"])
        out[f"{name}_ratio"] = g.ratio.reindex(idx).to_numpy()
        out[f"{name}_gain_m"] = g.gain_m.reindex(idx).to_numpy()
    return out


FE_COLOR = "tab:red"
FREE_COLOR = "tab:purple"


def _fe(ax, name, band, limit):
    """The FE level on a ratio panel (studies, the same whichever mesh profile a build uses; one mesh's contrasts are
    figures/fe/{profile}/contrasts.png): the bands' means, a scatter measure, and the line through the band meshes
    at zero element size with its interval."""
    b = band[band.contrast == name]
    ax.plot(b.velocity_ms - 15, b.mean_ratio, ".", ms=5, color=FE_COLOR, alpha=0.6,
            label="fe: mean over a band of meshes (8, 10, 12 across; a study)")
    z = limit[limit.contrast == name]
    ax.errorbar(z.velocity_ms + 15, z.ratio_at_zero_size,
                yerr=[z.ratio_at_zero_size - z.interval_low, z.interval_high - z.ratio_at_zero_size], fmt="s", ms=4,
                color=FE_COLOR, capsize=2, lw=1,
                label=f"fe: at zero element size, {100 * z.confidence.iloc[0]:.0f} % interval (21 meshes; a study)")


def _free(ax, name, free):
    """The erosion-free FE target on a ratio panel (a study, figures/fe/erosion_free/chaos_v*.csv): the contrast at
    zero element size +- U, filled where the study's line holds the means within their chaos, open where it does not
    (no limit: not an interval)."""
    if free is None:
        return
    z = free[(free.kind == "contrast") & (free.quantity == name) & free.estimate.notna()]
    holds = z.fit_holds.astype(str) == "True"
    for pick, style, label in ((holds, {}, "at zero element size +- U (realisations on several meshes; a study)"),
                               (~holds, {"mfc": "white"}, "no limit: the line at zero size +- U does not hold the "
                                                          "means (a study)")):
        if pick.any():
            ax.errorbar(z.velocity_ms[pick] - 30, z.estimate[pick], yerr=z.uncertainty[pick], fmt="D", ms=4,
                        color=FREE_COLOR, capsize=2, lw=1, label=f"fe, erosion-free target: {label}", **style)


@task
def nose_contrasts(inputs, outputs, params):
    data = pd.read_csv(inputs.csv)
    refs = load_reference(inputs.reference)
    write_csv(data, outputs.csv)
    write_csv(wide_table(data), outputs.table)
    fig, axes = figure(4, 4.0, 4.0)
    fig.subplots_adjust(wspace=0.3)
    t3 = data[data.source == "table3"]
    band, limit, free = committed_study(params.band), committed_study(params.limit), committed_studies(params.free)
    for ax, name in zip(axes, PANELS):
        d = data[data.contrast == name]
        for (level, variant), style in LINES.items():
            g = d[(d.source == "fig15") & (d.level == level) & (d.variant == variant)]
            ax.plot(g.velocity, g.ratio, label=f"{level}: {variant}", **style)
        st = t3[(t3.contrast == name) & (t3.variant == "Eq 9, S = 72 fc^-0.5")]
        ax.plot(st.velocity, st.ratio, "s", mfc="none", color="tab:blue", label="Eq 9, S = 72 fc^-0.5 (Table 3 cells)")
        for variant, style in (("simulation (LS-DYNA, fs calibrated on DO1)", PAPER_STYLE),
                               ("calculation (Eq 9)", dict(PAPER_STYLE, marker="+", color="tab:gray"))):
            g = t3[(t3.contrast == name) & (t3.level == "paper") & (t3.variant == variant)]
            ax.plot(g.velocity, g.ratio, label=f"paper, Table 3 {variant}", **style)
        if name in CLAIMS:
            claim = refs[CLAIMS[name]]
            ax.axhline(1 + claim.value / 100, color="k", ls="--", lw=0.8,
                       label="paper's text: the gain 'at the same velocity' (+5 % over CRH 4.5, +10 % over CRH 3)")
            ax.annotate(f"text: +{claim.value:g} %", (1400, 1 + claim.value / 100), fontsize=7, ha="right",
                        va="bottom")
        _fe(ax, name, band, limit)
        _free(ax, name, free)
        ax.axhline(1.0, color="k", lw=0.6)
        ax.set(xlabel="striking velocity (m/s)", ylabel="depth ratio", title=f"{name} depth ratio")
    gains = data[(data.source == "fig15") & (data.contrast.isin(GAINS_1200))]
    ax = axes[3]
    for (level, variant), style in LINES.items():
        for contrast, marker in zip(GAINS_1200, ("o", "^")):
            g = gains[(gains.level == level) & (gains.variant == variant) & (gains.contrast == contrast)]
            ax.plot(g.velocity, g.gain_m, marker=marker, markevery=8, ms=4, label=f"{contrast}: {level}", **style)
    for contrast, marker in zip(GAINS_1200, ("o", "^")):
        ref = refs[GAINS_1200[contrast]]
        ax.plot([1200.0], [ref.value], **dict(PAPER_STYLE, marker=marker, mfc="none"),
                label=f"paper's text at 1200 m/s: {contrast} +{ref.value:g} m")
        g = t3[(t3.contrast == contrast) & (t3.level == "paper") & (t3.variant.str.startswith("simulation"))]
        ax.plot(g.velocity, g.gain_m, **dict(PAPER_STYLE, marker=marker, color="tab:gray", markersize=5),
                label=f"paper, Table 3 simulation: {contrast}")
    ax.set(xlabel="striking velocity (m/s)", ylabel="depth gain of the double ogive (m)", title="gains in metres")
    legend = {}   # every ratio panel's entries, once each (a marker may appear on one panel only)
    for ax in axes[:3]:
        for h, label in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(label, h)
    handles, labels = list(legend.values()), list(legend)
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3, fontsize=7)
    axes[3].legend(fontsize=6, loc="upper left")
    fig.suptitle("Nose-shape contrasts: the paper's conclusions at every model level (solid lines: Fig 15 sweep)")
    save(fig, outputs.png, params.dpi)
