"""The HJC scaling rule against material data: the scaled set's G, T and pc against fc beside published HJC sets,
and its normalised strength at a few pressures beside triaxial criteria with an fc dependence (the task computes
every curve: tasks.levels.hjc_scaling)."""
from __future__ import annotations

import pandas as pd

from .common import figure, save


def hjc_scaling_figure(curves: pd.DataFrame, sets: pd.DataFrame, criteria: pd.DataFrame, path, dpi):
    """curves: fc_MPa and, per quantity G (GPa), T and pc (MPa), the rule's value and the former rule's (G_former,
    T_former); sets: workflow/data/hjc_sets.csv, with q_star_p1/p2/p5 (their own surfaces at p* = 1, 2, 5);
    criteria: hjc_scaling_criteria.csv."""
    fig, axes = figure(4, 3.5, 4.6)
    x = curves.fc_MPa
    ref = sets.refitted_strength_surface == "yes"
    for ax, key, unit in ((axes[0], "G", "G (GPa)"), (axes[1], "T", "T (MPa)"), (axes[2], "pc", "pc (MPa)")):
        ax.plot(x, curves[key], "k-", label="rule (fib MC2010; pc = fc/3)")
        if f"{key}_former" in curves:
            ax.plot(x, curves[f"{key}_former"], "k:", label="former rule (ACI 318 E; T as fc^(2/3))")
        col = {"G": "G_MPa", "T": "T_MPa", "pc": "pc_MPa"}[key]
        k = 1e-3 if key == "G" else 1.0
        ax.plot(sets.fc_MPa[ref], sets[col][ref] * k, "o", color="tab:red", label="published set (own A, B, N)")
        ax.plot(sets.fc_MPa[~ref], sets[col][~ref] * k, "s", mfc="none", color="tab:blue",
                label="published set (1993 A, B, N)")
        ax.set_xlabel("fc (MPa)")
        ax.set_ylabel(unit)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, loc="upper left")
    ax = axes[3]
    colors = {1.0: "tab:blue", 2.0: "tab:orange", 5.0: "tab:green"}
    for p, c in colors.items():
        sub = criteria[criteria.p_star == p]
        ax.plot(sub.fc_MPa, sub.q_star_rule, "-", color=c, label=f"rule, p* = {p:g}")
        ax.plot(sub.fc_MPa, sub.q_star_ottosen_mc90, "--", color=c, label=f"Ottosen MC90, p* = {p:g}")
        inside = ~sub.attard_setunge_extrapolated.astype(bool)
        ax.plot(sub.fc_MPa[inside], sub.q_star_attard_setunge[inside], "^", color=c,
                label=f"Attard-Setunge (tested confinement), p* = {p:g}")
        for s in sets[ref].itertuples():
            ax.plot(min(s.fc_MPa, 110.0), getattr(s, f"q_star_p{p:g}"), "o", color=c, mfc="none", ms=7)
    ax.set_xlabel("fc (MPa)")
    ax.set_ylabel("q* = (sigma1 - sigma3)/fc")
    ax.set_title("normalised strength (circles: refitted sets; 200 MPa drawn at 110)", fontsize=8)
    ax.legend(fontsize=6, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    ax.grid(alpha=0.3)
    fig.suptitle("HJC scaling rule against published HJC sets and triaxial criteria", fontsize=10)
    save(fig, path, dpi)
