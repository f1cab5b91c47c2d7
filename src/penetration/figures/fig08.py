"""Fig 8: deceleration histories of the 450 kg projectiles (Fig 9 draws Pd/d with the same panels).

Solid lines use the inferred diameter; thin dashed lines the ends of its
inferred interval (the sensitivity of the figure to that inference).
"""
from __future__ import annotations

import pandas as pd

from ..pipeline.io import load_json, task, write_csv
from ..units import G0
from .common import color, ending_at_rest, figure, save

LABELS = {"crh3": "CRH 3", "double_ogive": "double ogive", "crh5": "CRH 5"}


def s_choice_note(diameter):
    """Footnote: the S the Section 2.2 scenes use, and the diameter each other S choice would infer."""
    lines = [f"S = {diameter['S']:.4g} (Eq 7's stated 72 fc^-0.5 at 35 MPa): d = {diameter['diameter'] * 1e3:.0f} mm "
             f"({diameter['interval'][0] * 1e3:.0f}-{diameter['interval'][1] * 1e3:.0f} mm) from Fig 9's axes"]
    for v in diameter["variants"]:
        where = (f"d = {v['diameter'] * 1e3:.0f} mm ({v['interval'][0] * 1e3:.0f}-{v['interval'][1] * 1e3:.0f} mm)"
                 if v["diameter"] else "no diameter fits both axes")
        lines.append(f"variant, {v['S_choice']}: S = {v['S']:.4g}, {where} (not drawn)")
    return "\n".join(lines)


def panels(hist, dop, quantity, outputs, params, ylabel, title, axis_refs=None, legend_loc="best", note=None):
    vel = sorted(hist.velocity.unique())
    fig, axes = figure(len(vel), 5.0, 3.8)
    for ax, v in zip(axes, vel):
        for (nose, case), g in hist[hist.velocity == v].groupby(["nose", "radius_case"], sort=False):
            main = case == "chosen"
            ax.plot(g.t * 1e3, g[quantity], color=color(nose), lw=1.6 if main else 0.6, ls="-" if main else "--",
                    label=LABELS[nose] if main else None)
        lo, hi = (2e3 * dop.loc[dop.radius_case == c, "radius"].iloc[0] for c in ("interval_low", "interval_high"))
        ax.plot([], [], "k--", lw=0.6, label=f"dashed: d = {lo:.0f} and {hi:.0f} mm (ends of the inferred interval)")
        if axis_refs:
            t_top, y_top = axis_refs[v]
            ax.axhline(y_top, color="k", ls=":", lw=1, label="paper axis limits")
            ax.axvline(t_top, color="k", ls=":", lw=1)
        d = 2 * dop.loc[dop.radius_case == "chosen", "radius"].iloc[0]
        ax.set(xlabel="t (ms)", ylabel=ylabel, title=f"{title}, vs = {v:.0f} m/s, d = {d * 1e3:.0f} mm (inferred)")
        ax.legend(fontsize=7, loc=legend_loc)
    if note:
        fig.text(0.01, -0.02, note, fontsize=7, va="top", ha="left")
    save(fig, outputs.png, params.dpi)


@task
def fig08(inputs, outputs, params):
    hist = pd.read_csv(inputs.histories)
    dop = pd.read_csv(inputs.dop)
    hist = ending_at_rest(hist, ["nose", "radius_case", "velocity"])
    hist["deceleration_g"] = hist.deceleration / G0
    write_csv(hist[["nose", "radius_case", "velocity", "t", "deceleration_g"]], outputs.csv)
    panels(hist, dop, "deceleration_g", outputs, params, "deceleration (g)", "Fig 8", legend_loc="lower center",
           note=s_choice_note(load_json(inputs.diameter)))
