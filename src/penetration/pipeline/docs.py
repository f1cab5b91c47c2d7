"""The numbers the README and docs/ quote, generated from the committed outputs they cite.

A generated block in a markdown file is the text between ``<!-- generated: NAME -->`` and
``<!-- end generated -->``; ``python -m penetration.pipeline.docs README.md docs/*.md`` rewrites every block from the
files under figures/ (``--check``: exit 1, naming the blocks, where a file differs from what the outputs give).
tests/test_docs.py renders each block from the outputs committed at git HEAD and compares, so that no quoted
number can drift from its output, and no quantity is stated in two places with two values: each lives in one
block, built from one file.
"""
from __future__ import annotations

import argparse
import collections
import json
import math
import re
import statistics
import sys
from fractions import Fraction
from pathlib import Path

from ..studies.stats import power_law_exponent
from .docs_read import number as _num, rows as _rows, rows_if_any as _rows_if_any
from .docs_scale import BLOCKS as SCALE_BLOCKS
from .docs_unstated import BLOCKS as UNSTATED_BLOCKS

BLOCK = re.compile(r"(<!-- generated: (?P<name>[a-z0-9_]+) -->\n)(?P<body>.*?)(<!-- end generated -->)", re.S)


def _pct(x) -> str:
    return f"{100 * float(x):.0f} %"


def _span(seconds) -> str:
    s = float(seconds)
    if s < 1e-6:
        return f"{s * 1e9:.0f} ns"
    if s < 1e-3:
        return f"{s * 1e6:.0f} us"
    if s < 1:
        return f"{s * 1e3:.0f} ms"
    return f"{s:.1f} s" if s < 90 else f"{s / 60:.1f} min"


def _ci(r, key) -> str:
    """A slope with its 90 % interval from a validation summary row."""
    return f"{float(r[key]):+.2f} ({float(r[key + '_low']):+.2f} to {float(r[key + '_high']):+.2f})"


def _scope(read) -> str:
    """The calibres, strengths, velocities and noses of the development shots (the validated range)."""
    shots = _rows(read, "workflow/data/experiments-dev.csv")
    col = lambda k: [float(r[k]) for r in shots]
    d, fc, v, crh = col("diameter_m"), col("fc_MPa"), col("velocity_ms"), col("crh")
    return (f"{len(shots)} shots: calibres {1e3 * min(d):.1f}-{1e3 * max(d):.1f} mm, fc {min(fc):g}-{max(fc):g} MPa, "
            f"{min(v):g}-{max(v):g} m/s, ogive noses of CRH {min(crh):g}-{max(crh):g}")


def levels(read) -> str:
    """One row per level and calibration: its cost, its out-of-sample accuracy on the development shots and the
    residual's slope with fc, and the scope they hold for."""
    summary = [r for r in _rows(read, "figures/fe/full/validation_levels_summary.csv") if r["primary"] == "True"]
    walls = {r["level"]: r for r in _rows(read, "figures/timing/validation_levels_full.csv")}
    eq9 = next(r for r in _rows(read, "figures/timing/accuracy_cost.csv") if r["level"] == "analytic")
    pairs = {(r["level"], r["calibration"]): r for r in _rows(read, "figures/fe/full/validation_nose_pairs_summary.csv")}
    lines = ["| `--model` | calibration | cost per shot | depth error (scored on): median, 90th percentile, mean | "
             "nose-pair contrast error: median, 90th percentile, mean | "
             "slope of ln(predicted/measured) with ln fc, inside each series (90 %) |", "|---|---|---|---|---|---|"]
    for a in summary:
        level = a["level"]
        if level == "analytic":
            cost = f"{_span(eq9['wall_time_per_shot_s'])} (vectorised)"
        else:
            w = walls[level]
            cost = f"{_span(w['median_wall_time_per_shot_s'])} (up to {_span(w['max_wall_time_per_shot_s'])})"
        default = " (default)" if a["calibration"] == "laboratory" else ""
        p = pairs.get((level, a["calibration"]), {k: "nan" for k in ("median_abs_contrast_error",
                                                                     "p90_abs_contrast_error", "mean_contrast_error")})
        lines.append(f"| `{level}` | {a['calibration']}{default} | {cost} | {_pct(a['median_abs_rel_err'])}, "
                     f"{_pct(a['p90_abs_rel_err'])}, {float(a['mean_rel_err']) * 100:+.0f} % ({a['scoring']}, "
                     f"{a['shots']} shots) | {_pct(p['median_abs_contrast_error'])}, {_pct(p['p90_abs_contrast_error'])}, "
                     f"{float(p['mean_contrast_error']) * 100:+.0f} % | {_ci(a, 'slope_ln_fc_within_series')} |")
    lines += ["", f"Scope: the development shots, {_scope(read)}; the command line warns about every quantity of a "
              "shot outside these ranges. Costs: median (largest) wall time per development shot in the committed build "
              "(`figures/timing/validation_levels_full.csv`; Eq 9: `figures/timing/accuracy_cost.csv`); errors: "
              "`figures/fe/full/validation_levels_summary.csv` (fe at the default mesh). A positive mean is too deep; "
              "a negative slope means the level goes too deep in weak concrete and too shallow in strong. The nose-pair "
              "contrast error is (predicted/measured depth of the sharper nose) / (that of the blunter) - 1 over the "
              f"development shots' pairs of different noses in one series ({_pair_scope(pairs)}; "
              "`figures/fe/full/validation_nose_pairs_summary.csv`): the series' own bias cancels, what is left is "
              "the level's error on the contrast a user compares; negative: the level understates the sharper nose's "
              "gain."]
    return "\n".join(lines) + "\n"


def _pair_scope(pairs) -> str:
    r = next(iter(pairs.values()))
    return f"{r['pairs']} pairs of {r['shots']} shots in {r['series']} series, {r['noses']}"


# the laboratory validation's goal for the 90th percentile of |error| out of sample (its median's goal is the
# analytic level's median on the same shots)
P90_GOAL = 0.20


def laboratory(read) -> str:
    """The laboratory calibrations (the cavity level's strength scale; the fe level's failure strain at each mesh
    profile whose grid has run): each fold's fitted value and its held-out errors, the residual's slopes, and DO1
    predicted with them."""
    fits = [("cavity", "strength scale", _rows(read, "figures/calibration_cavity_laboratory.csv"), "full")]
    for profile in ("full", "ci"):
        rows = _rows_if_any(read, f"figures/fe/{profile}/calibration_fe_laboratory.csv")
        if rows:
            fits.append((f"fe ({profile} mesh, {float(rows[0]['elements_across_radius']):g} across)", "failure strain",
                         rows, profile))
    lines = ["| level | fold | fitted on | fitted value | fit rms of ln(pred/meas) | held out | held-out median, 90th "
             "percentile, mean |", "|---|---|---|---|---|---|---|"]
    for level, name, rows, _ in fits:
        for f in rows:
            held = (f"{_pct(f['held_out_median_abs_rel_err'])}, {_pct(f['held_out_p90_abs_rel_err'])}, "
                    f"{float(f['held_out_mean_rel_err']) * 100:+.0f} %" if int(f["held_out_shots"]) else "-")
            lines.append(f"| {level} | {f['fold']} | {f['fit_series']} ({f['fit_shots']} shots) | {name} "
                         f"{float(f['value']):.3f} | {float(f['fit_rms_log_error']):.3f} | {f['held_out_shots']} | {held} |")
    summary = {(r["level"], r["calibration"], r["scoring"]): r for r in
               _rows(read, "figures/fe/full/validation_levels_summary.csv")}
    lab = next(r for k, r in summary.items() if k[:2] == ("cavity", "laboratory") and r["primary"] == "True")
    eq9 = next(r for k, r in summary.items() if k[0] == "analytic")
    do1 = {r["level"]: r for r in _rows(read, "figures/do1_test.csv")}
    lines += ["", f"Out of sample (leave one series out, all {lab['shots']} shots) the laboratory-calibrated cavity "
              f"level errs by a median {_pct(lab['median_abs_rel_err'])} and a 90th percentile "
              f"{_pct(lab['p90_abs_rel_err'])}, against the goals of the analytic level's "
              f"{_pct(eq9['median_abs_rel_err'])} and {_pct(P90_GOAL)} (`figures/fe/full/validation_levels_summary.csv`). "
              f"Its residual's slope with ln calibre is {_ci(lab, 'slope_ln_calibre')} and with ln fc inside each "
              f"series {_ci(lab, 'slope_ln_fc_within_series')}; the analytic level's are "
              f"{_ci(eq9, 'slope_ln_calibre')} and {_ci(eq9, 'slope_ln_fc_within_series')}. "
              "The two calibres are the two series, so the calibre slope is the series' offset as much as a size "
              "effect."]
    for _, _, rows, profile in fits[1:]:
        level = f"fe level at the {profile} mesh ({float(rows[0]['elements_across_radius']):g} across)"
        path = f"figures/fe/{profile}/validation_levels_summary.csv"
        fe = [r for r in _rows(read, path) if r["level"] == "fe" and r["calibration"] == "laboratory"]
        if not fe:
            lines += ["", f"The {level}: its laboratory calibration is not scored in `{path}` yet."]
            continue
        scored = "; ".join(f"{r['scoring']} ({r['shots']} shots): median {_pct(r['median_abs_rel_err'])}, 90th "
                           f"percentile {_pct(r['p90_abs_rel_err'])}, mean {float(r['mean_rel_err']) * 100:+.0f} %"
                           for r in fe)
        main = next((r for r in fe if r["primary"] == "True"), fe[0])
        met = [float(main["median_abs_rel_err"]) <= float(eq9["median_abs_rel_err"]),
               float(main["p90_abs_rel_err"]) <= P90_GOAL]
        lines += ["", f"The {level}, out of sample (`{path}`): {scored}. Against the same goals (median "
                  f"{_pct(eq9['median_abs_rel_err'])}, 90th percentile {_pct(P90_GOAL)}, leaving one series out) it meets "
                  f"{sum(met)} of 2. Its residual's slope with ln calibre is "
                  f"{_ci(main, 'slope_ln_calibre')} and with ln fc inside each series "
                  f"{_ci(main, 'slope_ln_fc_within_series')}."]
    measured = {float(r["dop_m"]) for r in do1.values()}
    lines += ["", f"DO1 ({' and '.join(f'{m:g} m' for m in sorted(measured))}) predicted with the laboratory calibrations "
              "(`figures/do1_test.csv`): "
              + "; ".join(f"{k} {float(r['dop_pred_m']):.2f} m (DO1 {float(r['excess']) * 100:+.0f} % deeper)"
                          for k, r in do1.items()) + "."]
    return "\n".join(lines) + "\n"


def _range(values, fmt=".3f"):
    v = sorted(float(x) for x in values)
    return f"{v[0]:{fmt}}-{v[-1]:{fmt}}"


def answer(read) -> str:
    """The paper's central contrast at each level, over Table 3's velocities."""
    t = [r for r in _rows(read, "figures/nose_contrasts_table.csv") if r["contrast"] == "DO/CRH 4.5"]
    fe = [r for r in _rows(read, "figures/fe/full/table3_ratios.csv") if r["contrast"] == "DO/CRH 4.5"]
    lim = [r for r in _rows(read, "figures/fe/contrast_extrapolation.csv") if r["contrast"] == "DO/CRH 4.5"]
    inside = sum(r["paper_inside_interval"] == "True" for r in lim)
    hw = [float(r["interval_half_width_points"]) for r in lim]
    vel = ", ".join(f"{float(r['velocity']):.0f}" for r in t)
    return (f"Depth ratio of the double ogive to the CRH 4.5 ogive (DO/CRH 4.5) at {vel} m/s: the paper's simulation "
            f"{_range(r['paper_sim_ratio'] for r in t)}, its Eq 9 calculation {_range(r['paper_calc_ratio'] for r in t)}; "
            f"here Eq 9 with the stated S {_range(r['analytic_stated_S_ratio'] for r in t)}, the trajectory level "
            f"{_range(r['trajectory_ratio'] for r in t)}, the cavity level {_range(r['cavity_ratio'] for r in t)} "
            f"(`figures/nose_contrasts_table.csv`), the finite-element level at its default mesh "
            f"{_range(r['fe_ratio'] for r in fe)} (`figures/fe/full/table3_ratios.csv`) and, extrapolated to zero "
            f"element size over {lim[0]['meshes']} meshes, {_range(r['ratio_at_zero_size'] for r in lim)} with "
            f"{100 * float(lim[0]['confidence']):.0f} % intervals of +-{min(hw):.0f} to +-{max(hw):.0f} points that hold the paper's value at {inside} of {len(lim)} velocities "
            f"(a study: `figures/fe/contrast_extrapolation.csv`).\n")


def fe_limit(read) -> str:
    """The eroding FE level's nose contrasts at zero element size, with their intervals."""
    rows = _rows(read, "figures/fe/contrast_extrapolation.csv")
    lines = ["| contrast | velocity (m/s) | paper's simulation | at zero size | interval | scatter (points) | "
             "paper inside |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['contrast']} | {r['velocity_ms']} | {float(r['paper_sim_ratio']):.3f} | "
                     f"{float(r['ratio_at_zero_size']):.3f} | {float(r['interval_low']):.3f}-{float(r['interval_high']):.3f} | "
                     f"{float(r['scatter_points']):.1f} | {'yes' if r['paper_inside_interval'] == 'True' else 'no'} |")
    inside = sum(r["paper_inside_interval"] == "True" for r in rows)
    mono = sum(r["single_meshes_monotone"] == "True" for r in rows)
    lines += ["", f"{len(rows)} cells over {rows[0]['meshes']} meshes of "
              f"{1e3 * float(rows[0]['element_size_min_m']):.1f}-{1e3 * float(rows[0]['element_size_max_m']):.1f} mm; "
              f"half-widths {_range((r['interval_half_width_points'] for r in rows), '.1f')} points "
              f"({100 * float(rows[0]['confidence']):.0f} %, Student's t); the paper's value inside {inside} of {len(rows)}; "
              f"the single meshes of 3, 8, 10 and 12 across monotone in {mono} of {len(rows)} cells "
              "(`figures/fe/contrast_extrapolation.csv`)."]
    return "\n".join(lines) + "\n"


def _by_band(rows):
    """contrast_band.csv's rows by band: (band, elements across its centre) -> its rows, in the file's order."""
    out = {}
    for r in rows:
        out.setdefault((r["band"], r["centre_elements_across"]), []).append(r)
    return out


def fe_band_means(read) -> str:
    """The eroding FE level's band means minus the paper's simulated ratios (points), over Table 3's velocities."""
    rows = _rows(read, "figures/fe/contrast_band.csv")
    sizes = _by_band(rows)
    bands = list(sizes)
    lines = ["| contrast | paper | " + " | ".join(f"{c} across ({b})" for b, c in bands) + " |",
             "|---|---|" + "---|" * len(bands)]
    for contrast in dict.fromkeys(r["contrast"] for r in rows):
        mine = [r for r in rows if r["contrast"] == contrast]
        cells = []
        for b in bands:
            pts = [float(r["mean_minus_paper_points"]) for r in sizes[b] if r["contrast"] == contrast]
            cells.append(f"{min(pts):+.1f} to {max(pts):+.1f}")
        lines.append(f"| {contrast} | {_range((r['paper_sim_ratio'] for r in mine), '.3f')} | " + " | ".join(cells) + " |")
    meshes = "; ".join(f"{b[1]} across: {sizes[b][0]['meshes']} meshes, failure strain "
                       f"{float(sizes[b][0]['failure_strain_min']):.3f}-{float(sizes[b][0]['failure_strain_max']):.3f}"
                       for b in bands)
    return "\n".join(lines) + f"\n\n({meshes}; `figures/fe/contrast_band.csv`)\n"


def fe_single_meshes(read) -> str:
    """The eroding FE level's contrasts on the single meshes (ci, full, fine, finer), in points from the paper's
    simulated ratio: how many cells are monotone over the series, and the widest swing."""
    rows = _rows(read, "figures/fe/contrast_convergence.csv")
    across = sorted({float(r["elements_across_radius"]) for r in rows})
    cells = {}
    for r in rows:
        cells.setdefault((r["contrast"], r["velocity_ms"]), {})[float(r["elements_across_radius"])] = \
            float(r["difference_points"])
    mono, widest = 0, None
    for key, by in cells.items():
        seq = [by[n] for n in across if n in by]
        steps = [b - a for a, b in zip(seq, seq[1:])]
        mono += all(d >= 0 for d in steps) or all(d <= 0 for d in steps)
        swing = max(seq) - min(seq)
        if widest is None or swing > widest[0]:
            widest = (swing, key, seq)
    swing, (contrast, v), seq = widest
    return (f"Over the single meshes of {', '.join(f'{n:g}' for n in across)} elements across, each calibrated on DO1, "
            f"the contrasts are monotone in {mono} of {len(cells)} cells; the widest swing is {contrast} at {v} m/s, "
            f"{', '.join(f'{d:+.1f}' for d in seq)} points from the paper's value "
            "(`figures/fe/contrast_convergence.csv`).\n")


TEXT_CLAIM = {"DO/CRH 3": 1.10, "DO/CRH 4.5": 1.05}   # the text's "+10 % over CRH 3 and +5 % over the equivalent nose"


def _claim_velocities(rows, key):
    """The velocities (m/s, as written) at which both of the text's margins hold on ``rows`` (contrast, velocity_ms
    and the ratio in column ``key``)."""
    held = {}
    for r in rows:
        if r["contrast"] in TEXT_CLAIM:
            held.setdefault(r["velocity_ms"], []).append(float(r[key]) >= TEXT_CLAIM[r["contrast"]])
    return [v for v, ok in held.items() if len(ok) == len(TEXT_CLAIM) and all(ok)], len(held)


def fe_text_claim(read) -> str:
    """Where the text's "+10 % / +5 %" (the double ogive over CRH 3 and over CRH 4.5 at the same velocity) holds at the
    eroding FE level: on each band's means, on each single mesh, and at zero size (the interval's sides)."""
    def say(vs, n):
        return "at every velocity" if len(vs) == n else ("at none" if not vs else "at " + ", ".join(vs) + " m/s")

    parts = []
    for (_, centre), rows in _by_band(_rows(read, "figures/fe/contrast_band.csv")).items():
        vs, n = _claim_velocities(rows, "mean_ratio")
        parts.append(f"the band around {centre} across {say(vs, n)}")
    order = []
    single = _rows(read, "figures/fe/contrast_convergence.csv")
    for across in sorted({float(r["elements_across_radius"]) for r in single}):
        rows = [r for r in single if float(r["elements_across_radius"]) == across]
        vs, n = _claim_velocities(rows, "fe_ratio")
        parts.append(f"the single mesh of {across:g} across {say(vs, n)}")
        ordered = {r["velocity_ms"] for r in rows} - {r["velocity_ms"] for r in rows if r["contrast"] in
                                                     ("DO/CRH 4.5", "CRH 4.5/CRH 3") and float(r["fe_ratio"]) <= 1}
        order.append(f"{across:g} across {say(sorted(ordered, key=float), n)}")
    text = "The text's \"+10 % / +5 %\" (DO/CRH 3 >= 1.10 and DO/CRH 4.5 >= 1.05) holds on " + "; ".join(parts)
    zero = [r for r in _rows(read, "figures/fe/contrast_extrapolation.csv") if r["contrast"] in TEXT_CLAIM]
    both = [f"{r['contrast']} at {r['velocity_ms']} m/s" for r in zero
            if float(r["interval_low"]) < TEXT_CLAIM[r["contrast"]] <= float(r["interval_high"])]
    if zero:
        text += ("; at zero size the intervals of " + ", ".join(both) + " hold values on both sides of the margin"
                 if both else "; at zero size every interval lies on one side of the margin")
    if order:
        text += "; the ordering (DO deeper than CRH 4.5, deeper than CRH 3) holds on the single mesh of " + "; ".join(order)
    return text + (" (`figures/fe/contrast_band.csv`, `figures/fe/contrast_convergence.csv`, "
                   "`figures/fe/contrast_extrapolation.csv`).\n")


def fe_table3(read) -> str:
    """The FE Table 3 cells within 5 % of the paper's simulation, split by their distance from the DO1 calibration."""
    rows = _rows(read, "figures/fe/full/table3.csv")
    names = {"double_ogive": "the double ogive", "crh45": "CRH 4.5", "crh3": "CRH 3"}
    parts = []
    for nose in dict.fromkeys(r["nose"] for r in sorted(rows, key=lambda r: r["calibration_nose"] != "True")):
        g = [r for r in rows if r["nose"] == nose]
        within = sum(r["within_5pct_goal"] == "True" for r in g)
        worst = max(abs(float(r["rel_dev_fe_vs_paper_sim_pct"])) for r in g)
        what = " (the calibrated nose)" if g[0]["calibration_nose"] == "True" else ""
        parts.append(f"{names.get(nose, nose)}{what} {within} of {len(g)} (largest |deviation| {worst:.1f} %)")
    gaps = sorted({float(r["velocity_minus_calibration_ms"]) for r in rows})
    return (f"Cells within 5 % of the paper's simulated depth at 8 elements across: {'; '.join(parts)}; the cells "
            f"lie {gaps[0]:+.0f} to {gaps[-1]:+.0f} m/s from the 835 m/s calibration shot "
            "(`figures/fe/full/table3.csv`, `calibration_nose`, `velocity_minus_calibration_ms`).\n")


def wall_times(read) -> str:
    """The wall times the committed timing files hold, level by level (docs/benchmarks.md)."""
    cost = _rows(read, "figures/timing/accuracy_cost.csv")
    by = lambda level: [r for r in cost if r["level"] == level]
    traj = {r["setting"]: float(r["wall_time_per_shot_s"]) for r in by("trajectory")}
    cav = {r["setting"]: float(r["wall_time_per_shot_s"]) for r in by("cavity")}
    fe = [(r["setting"].split(" elements")[0], float(r["wall_time_per_shot_s"])) for r in by("fe")]
    do1 = {p: json.loads(read(f"figures/timing/fe_do1_{p}.json")) for p in ("full", "ci")}
    val = {p: {r["level"]: r for r in _rows(read, f"figures/timing/validation_levels_{p}.csv")} for p in ("full", "ci")}
    mesh = _rows(read, "figures/timing/fe_mesh_study_full.csv")
    win = _rows(read, "figures/timing/fe_window_full.csv")[0]
    across = ", ".join(f"{float(r['elements_across_radius']):.0f}" for r in mesh)
    vf = val["full"]
    lines = ["| level | wall time per shot | what is timed |", "|---|---|---|",
             f"| analytic (Eq 9) | {_span(by('analytic')[0]['wall_time_per_shot_s'])} | {by('analytic')[0]['timer']} |",
             f"| trajectory | {_span(min(traj.values()))}-{_span(max(traj.values()))} over {len(traj)} tolerances "
             f"({_span(traj['DOP853 rtol 1e-08'])} at the pipeline's 1e-8) | in-process, DOP853, the trajectory tolerance sweep |",
             f"| cavity | {_span(cav['100 zones'])} at 100 zones | one sigma_n table of 15 expansions and one trajectory: a "
             "shot on a new concrete |",
             f"| fe | {', '.join(_span(t) for _, t in fe)} at {', '.join(a for a, _ in fe)} elements across the shank radius "
             f"| {by('fe')[0]['timer']} |",
             "", "(`figures/timing/accuracy_cost.csv`, machine: "
             f"{cost[0]['machine']}.)", "",
             f"- The DO1 shot at the FE level, in the pipeline's run: {_span(do1['full']['do1_wall_time_s'])} at 8 elements "
             f"across ({do1['full'].get('do1_mesh_elements', '?')} mesh elements, {do1['full'].get('do1_steps', '?')} steps; "
             f"`figures/timing/fe_do1_full.json`), {_span(do1['ci']['do1_wall_time_s'])} at the CI's 3 across "
             "(`figures/timing/fe_do1_ci.json`).",
             f"- The 25 development shots (`figures/timing/validation_levels_full.csv`): "
             f"{_span(vf['trajectory']['total_wall_time_s'])} at the trajectory level; {_span(vf['cavity']['total_wall_time_s'])} "
             f"at the cavity level, its tables included (median {_span(vf['cavity']['median_wall_time_per_shot_s'])} per shot); "
             f"{_span(vf['fe']['total_wall_time_s'])} at the fe level (median {_span(vf['fe']['median_wall_time_per_shot_s'])}, "
             f"largest {_span(vf['fe']['max_wall_time_per_shot_s'])} per shot); at the CI's mesh the fe level took "
             f"{_span(val['ci']['fe']['total_wall_time_s'])} (`figures/timing/validation_levels_ci.csv`).",
             "- The FE mesh study (`figures/timing/fe_mesh_study_full.csv`): one DO1 run takes "
             f"{', '.join(_span(r['wall_time_per_run_s']) for r in mesh)} at "
             f"{across} elements across, and its "
             f"failure-strain calibration {', '.join(_span(r['calibration_wall_time_s']) for r in mesh)}.",
             f"- The moving window (`figures/timing/fe_window_full.csv`): the {win['realisations']} windowed DO1 runs took "
             f"{_span(win['wall_window_s'])}, the {win['realisations']} on the whole domain {_span(win['wall_whole_s'])}, a "
             f"ratio of {float(win['wall_ratio']):.2f}."]
    return "\n".join(lines) + "\n"


def accuracy(read) -> str:
    """Every level's prediction errors beside its cost (figures/accuracy_prediction.csv)."""
    cost = {(r["level"], r["setting"]): float(r["wall_time_per_shot_s"])
            for r in _rows(read, "figures/timing/accuracy_cost.csv")}
    fmt = lambda x, scale, unit: "" if x == "" else f"{scale * float(x):.1f}{unit}"
    lines = ["| level | setting | wall time per shot | Table 3, other noses: mean abs. deviation | contrasts: mean "
             "abs. difference | development shots: median abs. error |", "|---|---|---|---|---|---|"]
    for r in _rows(read, "figures/accuracy_prediction.csv"):
        t = cost.get((r["level"], r["setting"]))
        lines.append(f"| {r['level']} | {r['setting']} | {_span(t) if t is not None else ''} | "
                     f"{fmt(r['table3_other_noses_mean_abs_rel_dev'], 100, ' %')} | "
                     f"{fmt(r['contrast_mean_abs_points'], 1, ' points')} | "
                     f"{fmt(r['validation_median_abs_rel_err'], 100, ' %')} |")
    lines += ["", "(`figures/accuracy_prediction.csv`; wall times `figures/timing/accuracy_cost.csv`; an empty cell: "
              "not computed at that setting.)"]
    return "\n".join(lines) + "\n"


def erosion(read) -> str:
    """How the FE level's tunnel forms: the eroded share of its volume in the Table 3 shots and DO1."""
    t = _rows(read, "figures/fe/full/table3.csv")
    share = [float(r["tunnel_eroded_share"]) for r in t]
    do1 = json.loads(read("figures/fe/full/summary.json"))
    return (f"At the FE level (8 elements across) erosion deletes {100 * min(share):.0f}-{100 * max(share):.0f} % of the "
            f"tunnel's volume in the twelve Table 3 shots and {100 * do1['do1_tunnel_eroded_share']:.0f} % in DO1 "
            f"({do1['do1_eroded_mass_kg']:.0f} kg; `figures/fe/full/table3.csv`, `tunnel_eroded_share`; "
            "`figures/fe/full/summary.json`).\n")


def _sequences(conv):
    """The erosion-free study's per-hole sequences (rows of convergence.csv): the count of each refinement status,
    and per quantity (depth_m, depth_ratio) the GCI goals met and the sequences."""
    status = dict(sorted(collections.Counter(r["status"] for r in conv).items()))
    met = {q: (sum(r["goal_met"] == "True" for r in conv if r["quantity"] == q), sum(r["quantity"] == q for r in conv))
           for q in ("depth_m", "depth_ratio")}
    return status, met


def _mesh_columns(conv) -> list:
    """The erosion-free study's value_at_* columns of convergence.csv: one per mesh, coarsest first."""
    return [k for k in conv[0] if k.startswith("value_at_")]


def _meshes(conv) -> int:
    """The number of meshes of the erosion-free study."""
    return len(_mesh_columns(conv))


def erosion_free(read) -> str:
    """The erosion-free FE target's nose contrasts at zero element size and zero pilot hole (a study), with the
    meshes' and the holes' statuses, the GCI goals met and the study's cost."""
    base = "figures/fe/erosion_free/"
    holes = [r for r in _rows(read, base + "convergence_holes.csv") if r["quantity"] == "depth_ratio"]
    conv = _rows(read, base + "convergence.csv")
    timing = _rows(read, "figures/timing/fe_erosion_free_convergence.csv")
    cost = [r for r in timing if r["formulation"] == "erosion_free"]
    eroding = [r for r in timing if r["formulation"] == "eroding"]
    n_holes = len({r["pilot_hole"] for r in conv})
    lines = ["| contrast | velocity (m/s) | paper's simulation | erosion-free: at zero size and hole, or the range of "
             f"{_meshes(conv)} meshes x {n_holes} holes | meshes | holes | ranking (ratio > 1) |", "|---|---|---|---|---|---|---|"]
    for r in holes:
        ratio, band = float(r["at_zero_hole"]), float(r["uncertainty"])
        lo, med, hi = (float(r[k]) for k in ("values_min", "values_median", "values_max"))
        if r["limit_found"] == "True":
            value = f"{ratio:.3f} +- {band:.3f}"
        else:
            value = f"no limit: {lo:.3f}-{hi:.3f}, median {med:.3f}"
            if r.get("ls_low"):
                value += f"; least squares {float(r['ls_low']):.3f} to {float(r['ls_high']):.3f}"
        rank = {"limit": r["verdict"], "least squares": f"{r['verdict']} at every hole (least squares)"}.get(
            r["verdict_basis"], f"{r['verdict']}: {r['verdict_basis']}")
        meshes = "asymptotic" if r["mesh_status_all_asymptotic"] == "True" else "not all asymptotic"
        if r["meshes_stopped"] == "True":
            meshes += "; a shot stopped"
        lines.append(f"| {r['case']} | {float(r['velocity_ms']):.0f} | {float(r['paper_simulated']):.3f} | "
                     f"{value} | {meshes} | {r['hole_status']} | {rank} |")
    side = {"above": [], "below": [], "inside": []}
    for r in holes:
        if r["limit_found"] == "True":
            continue
        paper, lo, hi = (float(r[k]) for k in ("paper_simulated", "values_min", "values_max"))
        where = "above" if paper > hi else "below" if paper < lo else "inside"
        side[where].append(f"{r['case']} at {float(r['velocity_ms']):.0f} m/s")
    status, met = _sequences(conv)
    across = sorted(float(r["elements_across"]) for r in cost)
    shots = sum(int(r["shots"]) for r in cost)
    hours = sum(float(r["wall_time_sum_s"]) for r in cost) / 3600
    per = "; ".join(f"{float(r['elements_across']):g} across {_span(r['wall_time_mean_s'])}"
                    for r in sorted(cost, key=lambda r: float(r["elements_across"])))
    ranges = [f"{k} every mesh's and hole's value: {'; '.join(v)}" for k, v in
              (("above", side["above"]), ("below", side["below"]), ("inside the range of", side["inside"])) if v]
    lines += ["", ("Where no limit is found, the paper's simulated ratio lies " + "; ".join(ranges) + ". ")
              if ranges else ""]
    lines[-1] += (f"The band is the larger of the holes' GCI and the meshes' largest. Without a limit, the least-squares "
              f"range is the hull of each hole's finest value +- its Eça-Hoekstra uncertainty (over the {_meshes(conv)} meshes; a "
              f"bound at the holes run, not at zero hole). Per hole, the GCI goals "
              f"(depth {100 * float(next(r['gci_goal'] for r in conv if r['quantity'] == 'depth_m')):g} %, contrast "
              f"{100 * float(next(r['gci_goal'] for r in conv if r['quantity'] == 'depth_ratio')):g} point) are met "
              f"by {met['depth_m'][0]} of {met['depth_m'][1]} depths and {met['depth_ratio'][0]} of {met['depth_ratio'][1]} "
              f"contrasts; statuses {', '.join(f'{k} {v}' for k, v in status.items())} "
              f"(`{base}convergence.csv`, `{base}convergence_holes.csv`). {shots} shots on meshes of "
              f"{across[0]:g}-{across[-1]:g} elements across, {hours:.1f} h of job time; mean per shot: {per}"
              + "".join(f"; the eroding level's same {r['shots']} shots at {float(r['elements_across']):g} across "
                        f"{_span(r['wall_time_mean_s'])}" for r in eroding)
              + " (`figures/timing/fe_erosion_free_convergence.csv`).")
    return "\n".join(lines) + "\n"


def next_mesh_cost(shots) -> tuple:
    """The grid study's next mesh and its cost from its shots (rows with elements_across and wall_time_s, >= 2
    meshes): the next mesh refined by the finest step's ratio again, the power p of a least-squares fit of the
    meshes' mean shot time against the elements across on log-log axes, and the finest mesh's summed job time
    scaled by ratio ** p (s)."""
    across = sorted({float(r["elements_across"]) for r in shots})
    if len(across) < 2:
        raise ValueError(f"elements_across: the cost fit needs shots on at least 2 meshes, got {len(across)}")
    means = [statistics.fmean(float(r["wall_time_s"]) for r in shots if float(r["elements_across"]) == a) for a in across]
    power = power_law_exponent(across, means)
    ratio = across[-1] / across[-2]
    finest = sum(float(r["wall_time_s"]) for r in shots if float(r["elements_across"]) == across[-1])
    return across[-1] * ratio, power, finest * ratio ** power


def erosion_free_status(read) -> str:
    """The erosion-free grid study's state: its shots (at rest or stopped, eroded mass, energy audit, job time), the
    per-hole sequences' refinement statuses and GCI goals, and the limits found at zero hole."""
    base = "figures/fe/erosion_free/"
    shots = _rows(read, base + "convergence_shots.csv")
    conv = _rows(read, base + "convergence.csv")
    holes = _rows(read, base + "convergence_holes.csv")
    across = sorted({float(r["elements_across"]) for r in shots})
    finest = [r for r in shots if float(r["elements_across"]) == across[-1]]
    stopped = [r for r in shots if r["status"] != "rest"]
    hours = sum(float(r["wall_time_s"]) for r in shots) / 3600
    times = [float(r["wall_time_s"]) for r in finest]
    text = (f"*Status* ({len(shots)} shots on meshes of {', '.join(f'{a:g}' for a in across)} elements across, "
            f"domain {', '.join(sorted({r['domain'] for r in shots}))}, {hours:.1f} h of job time): "
            f"{len(shots) - len(stopped)} at rest and {len(stopped)} stopped")
    if stopped:
        text += " (" + "; ".join(f"{r['nose']} at {float(r['velocity_ms']):.0f} m/s, {float(r['elements_across']):g} "
                                 f"across, hole {float(r['pilot_hole']):g}" for r in stopped) + ")"
    rest = [r for r in shots if r["status"] == "rest"]
    walled = [r for r in rest if float(r["wall_debris_mass_kg"]) > 0.0]
    ejected = sorted(float(r["ejected_mass_kg"]) for r in rest)
    text += (f"; eroded mass at most {max(float(r['eroded_mass_kg']) for r in shots):g} kg; ejected (stress-free from "
             f"then on) {ejected[0]:.1f}-{ejected[-1]:.1f} kg a shot (median {ejected[len(ejected) // 2]:.1f} kg); of the ejected, at most "
             f"{max((float(r['crater_debris_mass_kg']) for r in rest), default=0.0):.2f} kg of crater debris in a shot, and wall debris "
             f"behind the tail in {len(walled)} shots"
             + (f" (at most {max(float(r['wall_debris_mass_kg']) for r in walled) * 1000:.1f} g)" if walled else "")
             + f"; energy error at most "
             f"{max(abs(float(r['energy_error_max'])) for r in shots if r['energy_error_max']):.1e} over the shots at rest and "
             f"{max(abs(float(r['energy_error_max'])) for r in finest if r['energy_error_max']):.1e} at {across[-1]:g} across, where a shot "
             f"takes {_span(min(times))} to {_span(max(times))}. ")
    status, met = _sequences(conv)
    cols = _mesh_columns(conv)
    steps = {}
    for q, scale in (("depth_m", None), ("depth_ratio", 100.0)):
        # each step's median over the sequences that have both meshes (a stopped shot leaves its mesh empty)
        per_step = [[abs(float(r[b]) - float(r[a])) * (scale or 100.0 / float(r[a]))
                     for r in conv if r["quantity"] == q and r[a] and r[b]] for a, b in zip(cols, cols[1:])]
        steps[q] = ", ".join(f"{statistics.median(c):.2f}" for c in per_step)
    text += (f"The median change from one mesh to the next is {steps['depth_m']} % for the depths and "
             f"{steps['depth_ratio']} points for the contrasts (from the coarsest step to the finest). ")
    text += (f"Of the {len(conv)} per-hole sequences (each depth and contrast at each hole), "
             + ", ".join(f"{v} {k}" for k, v in status.items())
             + f"; the GCI goal is met by {met['depth_m'][0]} of {met['depth_m'][1]} depths and {met['depth_ratio'][0]} "
             f"of {met['depth_ratio'][1]} contrasts. ")
    if any(v for k, v in status.items() if k != "asymptotic") and len(across) >= 3:
        following, power, seconds = next_mesh_cost(shots)
        text += (f"Not every sequence is in the asymptotic range, so the study's next mesh would be "
                 f"{following:g} across (refined by {following / across[-1]:g} again): with a shot's mean job time "
                 f"growing as the {power:.1f} power of the elements across (fitted over the {len(across)} meshes), its "
                 f"{len(finest)} shots would take about {seconds / 3600:.0f} h of job time, against "
                 f"{sum(times) / 3600:.1f} h at {across[-1]:g} across. ")
    found = {q: (sum(r["limit_found"] == "True" for r in holes if r["quantity"] == q), sum(r["quantity"] == q for r in holes))
             for q in ("depth_m", "depth_ratio")}
    shown = sum(r["limit_found"] == "True" and r["mesh_status_all_asymptotic"] == "True" and r["hole_status"] == "asymptotic"
                for r in holes)
    text += (f"To zero hole a limit with a GCI band is found for {found['depth_m'][0]} of {found['depth_m'][1]} depths "
             f"and {found['depth_ratio'][0]} of {found['depth_ratio'][1]} contrasts, {shown} of them from sequences "
             f"all in the asymptotic range (`{base}convergence_shots.csv`, `convergence.csv`, "
             f"`convergence_holes.csv`).\n")
    return text


def erosion_free_depths(read) -> str:
    """The erosion-free target's absolute depths: with Table 1's HJC as stated at zero element size and hole (a
    study), and with one strength scale calibrated on DO1 at one mesh (a calibration), against the paper's Table 3."""
    base = "figures/fe/erosion_free/"
    holes = [r for r in _rows(read, base + "convergence_holes.csv") if r["quantity"] == "depth_m"]
    limit = [r for r in holes if r["limit_found"] == "True"]
    ratios = [float(r["at_zero_hole"]) / float(r["paper_simulated"]) for r in limit]
    spread = [float(r[k]) / float(r["paper_simulated"]) for r in holes if r["limit_found"] != "True"
              for k in ("values_min", "values_max")]
    stated = "With Table 1's HJC as stated, "
    if ratios:
        span = f"{min(ratios):.2f}" if f"{min(ratios):.2f}" == f"{max(ratios):.2f}" else f"{min(ratios):.2f}-{max(ratios):.2f}"
        stated += (f"the erosion-free depth{'s' if len(limit) > 1 else ''} at zero element size and hole "
                   f"{'are' if len(limit) > 1 else 'is'} {span} of the paper's simulated one"
                   f"{'s' if len(limit) > 1 else ''} ({len(limit)} of {len(holes)} shots of Table 3: "
                   + ", ".join(f"{r['case']} at {float(r['velocity_ms']):.0f} m/s" for r in limit) + ")")
    if spread:
        stated += (("; " if ratios else "") + f"{len(holes) - len(limit)} of the {len(holes)} Table 3 depths have no "
                   f"limit under refinement, and their values on every mesh and hole are {min(spread):.2f}-"
                   f"{max(spread):.2f} of the paper's simulated ones")
        hulls = [r for r in holes if r["limit_found"] != "True" and r.get("ls_high")]
        below = sum(float(r["ls_high"]) < float(r["paper_simulated"]) for r in hulls)
        if hulls:
            meshes = _meshes(_rows(read, base + "convergence.csv"))
            stated += (f"; for {len(hulls)} of them every hole has a least-squares interval (Eça-Hoekstra, over the "
                       f"{meshes} meshes), and in {below} the whole hull of those intervals lies below the paper's depth")
    stated += f" (`{base}convergence_holes.csv`)."
    try:
        cal = _rows(read, base + "calibration.csv")[0]
        depths = _rows(read, base + "calibrated.csv")
    except FileNotFoundError:   # the calibration study not yet run: the stated depths alone
        return stated + " The DO1 strength-scale calibration of this target is not yet run (rule calibrate_fe_strength_do1).\n"
    over = [float(r["calibrated_over_paper"]) for r in depths]
    plain = [float(r["stated_over_paper"]) for r in depths]
    return (stated + " One strength scale calibrated on DO1 (a calibration: "
            f"{float(cal['value']):.3f} on the whole HJC strength surface, residual {float(cal['residual_m']) * 100:+.1f} cm "
            f"on the measured {float(cal['measured_depth_m']):g} m after {cal['trials']} trials, at "
            f"{float(cal['elements_across_radius']):g} elements across and hole {float(cal['pilot_hole']):g}) brings "
            f"the {len(depths)} shots to {min(over):.2f}-{max(over):.2f} of the paper's on that mesh, against "
            f"{min(plain):.2f}-{max(plain):.2f} with the stated HJC there (`{base}calibrated.csv`, "
            f"`{base}calibration.csv`).\n")


def erosion_free_window(read) -> str:
    """The moving window on the erosion-free target: each shot's mean depth with the window against the whole
    domain's, with the equivalence test's interval."""
    import yaml
    base = "figures/fe/erosion_free/"
    parts, spread = [], []
    for shot in yaml.safe_load(read("workflow/config.yaml"))["fe_erosion_free"]["window"]["shots"]:
        r = _rows(read, f"{base}window_{shot}_summary.csv")[0]
        spread += [100 * float(r[f"std_{d}_m"]) / float(r[f"mean_{d}_m"]) for d in ("window", "whole")]
        parts.append(f"{shot.replace('_', ' at ')} m/s {float(r['difference_pct']):+.2f} % ({100 * float(r['confidence']):.0f} % "
                     f"interval {float(r['interval_low_pct']):+.2f} to {float(r['interval_high_pct']):+.2f} %, "
                     f"{'within' if r['within_goal'] == 'True' else 'not within'} +-{float(r['goal_pct']):g} %; "
                     f"{r['realisations']} realisations each)")
    return ("The moving window against the whole domain on the erosion-free target (mean depths): " + "; ".join(parts)
            + f". The realisations of one shot spread by {min(spread):.1f}-{max(spread):.1f} % (the standard deviation "
            f"over its members over their mean depth; `{base}window_*_summary.csv`).\n")


def fe_speed(read) -> str:
    """Every run of workflow/benchmarks/fe_speed.py, per machine: time per element-step against the floor."""
    rows = _rows(read, "figures/timing/fe_speed.csv")
    out = []
    for machine in dict.fromkeys(r["machine"] for r in rows):
        mine = [r for r in rows if r["machine"] == machine]
        runs = list(dict.fromkeys(r["date"] for r in mine))
        first = mine[0]
        stream = ", ".join(f"{float(r['stream_before_GBs']):.1f}/{float(r['stream_after_GBs']):.1f}"
                           for r in (next(x for x in mine if x["date"] == d) for d in runs))
        floors = ", ".join(f"{float(next(x for x in mine if x['date'] == d)['floor_ns']):.1f}" for d in runs)
        out += [f"{machine} ({first['isa']}, {first['threads']} threads): {len(runs)} runs, {runs[0][:10]} to "
                f"{runs[-1][:10]}; STREAM triad before/after {stream} GB/s; {first['bytes_per_element_step']} bytes per "
                f"element-step, floor {floors} ns.", "",
                "| state | ns per element-step, run by run | times the floor | runs meeting 30 ns | runs meeting 2 x the floor |",
                "|---|---|---|---|---|"]
        for state in dict.fromkeys(r["state"] for r in mine):
            g = [r for r in mine if r["state"] == state]
            ns = [float(r["ns_per_element_step"]) for r in g]
            ratio = [float(r["times_floor"]) for r in g]
            # a part of a state's step (the strength surface alone) has no target of its own
            met = (["(a part of the plastic state's step)"] * 2 if state.startswith("strength surface") else
                   [f"{sum(x <= 30 for x in ns)} of {len(g)}", f"{sum(x <= 2 for x in ratio)} of {len(g)}"])
            out.append(f"| {state} | {', '.join(f'{x:.1f}' for x in ns)} | {', '.join(f'{x:.2f}' for x in ratio)} | "
                       f"{met[0]} | {met[1]} |")
        walls = [float(r["do1_wall_s"]) for r in mine if r["do1_wall_s"]]
        if walls:
            out += ["", f"The DO1 shot itself took {', '.join(f'{w:.1f}' for w in walls)} s in those runs (target 60 s)."]
        out.append("")
    return "\n".join(out) + "(`figures/timing/fe_speed.csv`, appended by `workflow/benchmarks/fe_speed.py`)\n"


def rear_face(read) -> str:
    """The rear-face study: each target of the chain and each change's effect with its interval."""
    t = _rows(read, "figures/fe/rear_face.csv")
    e = _rows(read, "figures/fe/rear_face_effects.csv")
    lines = ["| target | mean depth (m) | range (m) | at rest / through or moving at the end |", "|---|---|---|---|"]
    for r in t:
        bottom = "as deep as needed" if r["bottom_depth_m"] == "" else f"{float(r['bottom_depth_m']):g} m"
        short = {"non_reflecting": "absorbing", "free": "free"}
        lines.append(f"| R {float(r['radius_m']):.3g} m, {short[r['lateral']]} sides, bottom {bottom} {short[r['bottom']]} | "
                     f"{float(r['mean_m']):.3f} | {float(r['min_m']):.3f}-{float(r['max_m']):.3f} | "
                     f"{r['at_rest']} / {int(r['perforated']) + int(r['moving_at_end'])} |")
    lines += ["", "| change | effect on the mean depth (m) | interval (m) |", "|---|---|---|"]
    for r in e:
        what = r["changes"] if r["single_change"] == "True" else "all four (semi-infinite to block)"
        lines.append(f"| {what} | {float(r['effect_m']):+.3f} | {float(r['interval_low_m']):+.3f} to "
                     f"{float(r['interval_high_m']):+.3f} |")
    lines += ["", f"({t[0]['realisations']} realisations per target, {100 * float(e[0]['confidence']):.0f} % Welch "
              "intervals; `figures/fe/rear_face.csv`, `rear_face_effects.csv`)"]
    block = t[-1]
    members = [r for r in _rows(read, "figures/fe/rear_face_members.csv") if r["scene"] == block["scene"]]
    if members:
        bottom = float(block["bottom_depth_m"])
        short = [bottom - float(r["depth_m"]) for r in members if r["status"] == "rest"]
        through, moving = int(block["perforated"]), int(block["moving_at_end"])
        text = f"In the block ({block['scene']}, {bottom:g} m deep), {len(short)} of {len(members)} realisations came to rest"
        text += f", {min(short):.2f}-{max(short):.2f} m short of its rear face" if short else ""
        text += f"; {through} perforated it or bulged through it" if through else ""
        text += f"; {moving} still moved at the run's end" if moving else ""
        lines += ["", text + " (`figures/fe/rear_face_members.csv`)."]
    return "\n".join(lines) + "\n"


def _g(x) -> str:
    return "" if x in ("", "nan") else ("-inf" if x == "-inf" else "inf" if x == "inf" else f"{float(x):.4g}")


def verification(read) -> str:
    """Every check of the FE and cavity verification problems: ours, the reference, the accepted interval."""
    lines = []
    for path in ("figures/fe_verification.csv", "figures/cavity_verification.csv"):
        lines += [f"`{path}`:", "", "| problem | quantity | ours | reference | accepted | unit | source | holds |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in _rows(read, path):
            cell = {k: v.replace("|", "\\|") for k, v in r.items()}
            lines.append(f"| {cell['problem']} | {cell['quantity']} | {_g(r['ours'])} | {_g(r['reference'])} | "
                         f"[{_g(r['low'])}, {_g(r['high'])}] | {cell['unit']} | {cell['source']} | {r['holds']} |")
        lines.append("")
    return "\n".join(lines)


def rebuild(read) -> str:
    """The last recorded fresh-clone run of each target on each machine (the times differ by machine as much as by
    commit), the newest machine first."""
    rows = _rows(read, "figures/timing/fresh_clone.csv")
    last = {}
    for r in rows:
        last[(r["target"], r["machine"])] = r
    out = []
    for target, what in (("reproduce", "`make install` + `make reproduce`"), ("test", "`make install` + `make test`"),
                         ("ci", "`CI=true bash .ci/run`")):
        for r in sorted((r for (t, _), r in last.items() if t == target), key=lambda r: r["date"], reverse=True):
            install = ("install included" if target == "ci" else
                       f"install {float(r['install_s']) / 60:.1f} min, {target} {float(r['target_s']) / 60:.1f} min")
            if r.get("install_cache") in ("warm", "cold"):   # recorded since 2026-12-01: a warm cache installs faster
                install += f"; uv's download cache {r['install_cache']}"
            out.append(f"- {what}: {float(r['total_s']) / 60:.1f} min from a fresh clone ({install}), {r['date'][:10]}, "
                       f"commit {r['commit']}, on {r['machine']}")
    return "\n".join(out) + "\n\n(`figures/timing/fresh_clone.csv`, written by `workflow/benchmarks/fresh_clone.py`)\n"


def validation(read) -> str:
    """Each level's errors on the development shots, per calibration and scoring, at the default and the CI's mesh."""
    lines = []
    for profile in ("full", "ci"):
        path = f"figures/fe/{profile}/validation_levels_summary.csv"
        lines += [f"`{path}`:", "", "| level | calibration | scored on | median | 90th percentile | mean | within 10 % |",
                  "|---|---|---|---|---|---|---|"]
        for r in _rows(read, path):
            if profile == "ci" and r["level"] != "fe":
                continue
            lines.append(f"| {r['level']} | {r['calibration']} | {r['scoring']} | "
                         f"{100 * float(r['median_abs_rel_err']):.1f} % | {100 * float(r['p90_abs_rel_err']):.1f} % | "
                         f"{100 * float(r['mean_rel_err']):+.1f} % | {r['within_10pct']} of {r['shots']} |")
        lines.append("")
    return "\n".join(lines)


def quasi_static(read) -> str:
    """The erosion-free target's quasi-static check: per pilot hole, the steady force over pi a^2 on each mesh, its
    refinement and how it stands against the cavity level's sigma_n and the band set before the runs."""
    rows = _rows(read, "figures/fe/erosion_free/quasi_static.csv")
    meshes = [k for k in rows[0] if k.startswith("force_over_area_at_")]
    across = [k.removeprefix("force_over_area_at_").removesuffix("_across_pa") for k in meshes]
    lines = ["| pilot hole (shank radii) | guide | F / (pi a^2) at " + ", ".join(across) + " across (MPa) | refinement "
             "| judged range / cavity level's sigma_n | 1-D cylinder, sphere from the hole / sigma_n | within the band |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        sigma = float(r["cavity_level_sigma_n_pa"])
        order = "" if r["observed_order"] in ("", "nan") else f", observed order {float(r['observed_order']):.2f}"
        lines.append(f"| {float(r['pilot_hole']):g} | {'yes' if r['pilot_guide'] == 'True' else 'no'} | "
                     + ", ".join(f"{float(r[k]) / 1e6:.0f}" for k in meshes)
                     + f" | {r['status']}{order} | {float(r['judged_low_pa']) / sigma:.2f}-"
                     f"{float(r['judged_high_pa']) / sigma:.2f} | {float(r['cylinder_from_hole_pa']) / sigma:.2f}, "
                     f"{float(r['sphere_from_hole_pa']) / sigma:.2f} | {r['within_band']} (+-{_pct(r['band'])}) |")
    lines += ["", f"The cavity level's sigma_n at {float(rows[0]['velocity_ms']):g} m/s is "
              f"{float(rows[0]['cavity_level_sigma_n_pa']) / 1e6:.0f} MPa (`figures/fe/erosion_free/quasi_static.csv`; "
              "each run with its cost in `quasi_static_runs.csv`). A sequence in the asymptotic range is judged on its "
              "Richardson value, any other on the range of its finest three meshes."]
    return "\n".join(lines) + "\n"


def claims(read) -> str:
    """The paper's claims judged at every level (the pipeline's figures/fe/full/claims.csv), one row a claim, one
    column a level (its label), each cell the verdict and the number that decides it; then the paper's ranking of
    each contrast on the erosion-free target."""
    from ..levels import LABELS

    path = "figures/fe/full/claims.csv"
    rows = _rows(read, path)
    ladder = [r for r in rows if r["level"] in LABELS]
    order = list(dict.fromkeys(r["claim_id"] for r in ladder))
    cell = {(r["claim_id"], r["level"]): f"**{r['verdict']}**: {r['evidence']}" for r in ladder}
    text = {r["claim_id"]: r["claim"].replace("<i>", "*").replace("</i>", "*") for r in ladder}
    lines = ["| claim | " + " | ".join(LABELS.values()) + " |", "|---" * (len(LABELS) + 1) + "|"]
    lines += [f"| {text[c]} | " + " | ".join(cell[(c, lv)] for lv in LABELS) + " |" for c in order]
    free = [f"{r['claim'].removesuffix(' (the paper' + chr(39) + 's ranking)')}: {r['evidence']}"
            for r in rows if r["level"] == "erosion_free"]
    qs = _rows(read, "figures/fe/erosion_free/quasi_static.csv")
    sigma = float(qs[0]["cavity_level_sigma_n_pa"])

    def hole(r):
        return (f"pilot hole {Fraction(float(r['pilot_hole'])).limit_denominator(64)} "
                f"({float(r['judged_low_pa']) / sigma:.2f}-{float(r['judged_high_pa']) / sigma:.2f})")
    passed = [hole(r) for r in qs if r["within_band"] == "True"]
    failed = [hole(r) for r in qs if r["within_band"] != "True"]
    import yaml
    real = yaml.safe_load(read("workflow/config.yaml"))["fe_realisations"]
    scene = real["chaos"]["scene"]
    study_hole = float(yaml.safe_load(read(f"workflow/scenes/fe/{scene}.yaml"))["fe"]["pilot_hole"])
    fails_study = any(float(r["pilot_hole"]) == study_hole and r["within_band"] != "True" for r in qs)
    check = ("That target's quasi-static check (a slowly driven CRH 3 ogive against the cavity level's resistance, a "
             f"band of +-{_pct(qs[0]['band'])} set before the runs; the range over the finest three meshes): "
             + (f"passed on {', '.join(passed)}" if passed else "passed on no pilot hole")
             + (f", failed on {', '.join(failed)}" if failed else "")
             + (f"; the ranking above and the verdict's erosion-free column come from pilot hole "
                f"{Fraction(study_hole).limit_denominator(64)}, which fails it" if fails_study else "")
             + " (`figures/fe/erosion_free/quasi_static.csv`).")
    check += _ejecta(read, real["velocities"])
    return ("\n".join(lines) + "\n\nOn the erosion-free FE target (no element deleted, Table 1's HJC as stated; a study: "
            "realisations of the chaos on several meshes, at zero element size), the paper's ranking of each contrast: "
            + "; ".join(free) + f" (`{path}`). " + check + "\n")


def _ejecta(read, velocities) -> str:
    """The concrete the erosion-free target's shots turn into stress-free ejecta (the lip and the thinned crater
    wall), crater debris and wall debris, in kg per shot over the grid study's realisations, against the concrete of
    a tunnel of the shank's radius to the shot's depth (Table 1's density, Table 2's calibre), at each of the study's
    ``velocities`` run so far."""
    refs = {r["id"]: float(r["value"]) for r in _rows(read, "workflow/reference/paper_values.csv")
            if r["id"] in ("table1.rho", "table2.diameter")}
    area = math.pi * (refs["table2.diameter"] / 2) ** 2
    parts = []
    for v in velocities:
        shots = [r for r in _rows_if_any(read, f"figures/fe/erosion_free/chaos_v{v:g}_shots.csv")
                 if _num(r["ejected_mass_kg"]) == _num(r["ejected_mass_kg"])]
        if not shots:
            continue
        ej = [_num(r["ejected_mass_kg"]) for r in shots]
        share = [_num(r["ejected_mass_kg"]) / (area * _num(r["depth_m"]) * refs["table1.rho"]) for r in shots]
        crater = max(_num(r["crater_debris_mass_kg"]) for r in shots)
        wall = max(_num(r["wall_debris_mass_kg"]) for r in shots)
        parts.append(f"at {v:g} m/s {min(ej):.1f}-{max(ej):.1f} kg of ejecta ({100 * min(share):.0f}-{100 * max(share):.0f} "
                     f"% of the tunnel's concrete), crater debris up to {crater:.2f} kg, "
                     + (f"wall debris up to {1000 * wall:.1f} g" if wall > 0 else "no wall debris")
                     + f" ({len(shots)} shots)")
    if not parts:
        return ""
    return (" Its shots turn concrete into stress-free ejecta (the lip and the thinned crater wall; a tunnel of the "
            "shank's radius to the shot's depth for scale): " + "; ".join(parts)
            + " (`figures/fe/erosion_free/chaos_v*_shots.csv`; halving or doubling the ejection moves the contrasts as "
            "`figures/fe/unstated_erosion_free_v*.csv` shows, and a resolved move joins the verdict's ±).")


def paper_eq9(read) -> str:
    """Eq 9's effective N* and S per nose through each Table 3 column (figures/paper_eq9_effective.csv)."""
    rows = _rows(read, "figures/paper_eq9_effective.csv")
    lines = ["| Table 3 column | nose | N* of the nose | effective N* | effective S | S over CRH 3's | rms ln residual |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {r['column']} | {r['nose']} | {float(r['nstar_of_nose']):.4f} | {float(r['nstar_effective']):.4f} | "
              f"{float(r['S_effective']):.3f} | {float(r['S_effective_over_crh3']):.3f} | "
              f"{100 * float(r['rms_ln_residual']):.2f} % |" for r in rows]
    return "\n".join(lines) + "\n"


def verdict(read) -> str:
    """The verdict on the paper's nose contrasts (figures/verdict.csv): one row per contrast and velocity, one column
    per model (value +- its numerical uncertainty, the unstated inputs' range apart), the paper's value; then one
    paragraph counting, per model, the cells whose interval holds the paper's value and those an unstated input
    reaches."""
    from ..paper.verdict import SHORT

    rows = _rows(read, "figures/verdict.csv")
    models = list(dict.fromkeys(r["model"] for r in rows))
    cells = list(dict.fromkeys((r["contrast"], r["velocity_ms"]) for r in rows))
    at = {(r["contrast"], r["velocity_ms"], r["model"]): r for r in rows}

    def cell(r):
        if r is None:
            return "—"
        value = _num(r["value"])
        if value != value:
            return "pending"
        u = _num(r["uncertainty"])
        text = f"{value:.3f}" + (f" ± {u:.3f}" if u > 0 else "")
        low, high = _num(r["unstated_low"]), _num(r["unstated_high"])
        if low == low:
            text += f" [{low:.3f}–{high:.3f}]"
        return text

    paper = {(r["contrast"], r["velocity_ms"]): _num(r["paper_sim_ratio"]) for r in rows}
    lines = ["| contrast | m/s | paper | " + " | ".join(SHORT.get(m, m) for m in models) + " |",
             "|---" * (len(models) + 3) + "|"]
    lines += [f"| {c} | {float(v):g} | {paper[(c, v)]:.3f} | " + " | ".join(cell(at.get((c, v, m))) for m in models)
              + " |" for c, v in cells]
    counts = []
    for m in models:
        mine = [r for r in rows if r["model"] == m and _num(r["value"]) == _num(r["value"])]
        if not mine:
            counts.append(f"{SHORT.get(m, m)}: pending")
            continue
        inside = sum(r["paper_within_uncertainty"] == "True" for r in mine)
        reach = sorted({x for r in mine for x in r["reached_by"].split("; ") if x and x != "none"})
        widest = max(_num(r["uncertainty"]) for r in mine)
        nolimit = sum(r.get("limit", "True") != "True" for r in mine)
        counts.append(f"{SHORT.get(m, m)}: the paper's value within ± in {inside} of {len(mine)} cells"
                      + (f" (± up to {100 * widest:.1f} points" + (f"; {nolimit} without a limit" if nolimit else "")
                         + ")" if widest > 0 else "")
                      + (f", reached by an unstated input ({', '.join(reach)}) in "
                         f"{sum(bool(r['reached_by']) and r['reached_by'] != 'none' for r in mine)}" if reach else ""))
    return ("\n".join(lines) + "\n\nBrackets: the range over the unstated inputs (friction, failure strain, the cavity "
            "level's conventions), shown apart from the ± of the model's numerics (chaos and mesh). " + "; ".join(counts)
            + ". A ± wider than the paper's distance from the value holds it without confirming it: the diff counts a "
            "cell as reproduced only when the whole interval lies within 2 points of the paper's value, as undecided "
            "when it holds the paper's value and more, and a cell without a limit as undecided "
            "(`figures/verdict.csv`, each model's source in its `provenance` column; `figures/diff.csv`, the rows "
            "`verdict: ...` of Table 3).\n")


def erosion_free_chaos(read) -> str:
    """The erosion-free grid study with the chaos in its error model (figures/fe/erosion_free/chaos_v*.csv): per
    velocity and contrast the estimate at zero size +- U, the pooled chaos, whether the first-order line holds the
    means, the status against the goal and, where it is missed, the next mesh and its cost; a velocity not yet run
    says so."""
    import yaml

    cfg = yaml.safe_load(read("workflow/config.yaml"))["fe_realisations"]
    lines = ["| m/s | contrast | finest mesh mean ± s.e. | pooled s.d. of one realisation | line holds the means "
             "(p) | at zero size ± U | paper | status | next mesh, cost |", "|---|---|---|---|---|---|---|---|---|"]
    missing, cost = [], []
    for v in cfg["velocities"]:
        path = f"figures/fe/erosion_free/chaos_v{v:g}.csv"
        rows = [r for r in _rows_if_any(read, path) if r["kind"] == "contrast"]
        if not rows:
            missing.append(f"{v:g} m/s")
            continue
        shots = _rows_if_any(read, f"figures/fe/erosion_free/chaos_v{v:g}_shots.csv")
        wall = sum(x for x in (_num(r["wall_time_s"]) for r in shots) if x == x)
        by_mesh = {}
        for r in shots:
            if _num(r["wall_time_s"]) == _num(r["wall_time_s"]):
                by_mesh.setdefault(r["elements_across"], []).append(_num(r["wall_time_s"]))
        robust = sum(statistics.median(t) * len(t) for t in by_mesh.values())
        across = sorted(float(a) for a in by_mesh)
        if across:
            cost.append(f"{len(shots)} shots at {v:g} m/s on {len(across)} meshes ({across[0]:g}-{across[-1]:g} "
                        f"across), {wall / 3600:.1f} h (each mesh's median shot times its shots: {robust / 3600:.1f} h)")
        for r in rows:
            if _num(r.get("estimate", "")) != _num(r.get("estimate", "")):
                lines.append(f"| {float(r['velocity_ms']):g} | {r['quantity']} | — | — | — | — | — | {r['status']} | — |")
                continue
            nxt = (f"{_num(r['next_elements_across']):g} across, {_num(r['next_cell_hours']):.1f} h a cell"
                   if r.get("next_elements_across") not in (None, "") else "—")
            lines.append(f"| {float(r['velocity_ms']):g} | {r['quantity']} | {_num(r['finest_mean']):.3f} ± "
                         f"{_num(r['finest_se']):.3f} | {_num(r['sd_pooled']):.4f} | "
                         f"{'yes' if r['fit_holds'] == 'True' else 'no'} ({_num(r['fit_p']):.2f}) | "
                         f"{_num(r['estimate']):.3f} ± {_num(r['uncertainty']):.3f} | {_num(r['paper']):.3f} | "
                         f"{r['status']} | {nxt} |")
    tail = ("\nJob time (2 cores, wall; a shot's wall time includes any pause of its job): " + "; ".join(cost) + "."
            if cost else "")
    tail += ("\nNot yet run: " + ", ".join(f"{v} (`snakemake -c2 figures/fe/erosion_free/chaos_v{v.split()[0]}.csv` "
                                           "resumes its pieces under `figures/fe/realisations/`)" for v in missing)
             + ".\n" if missing else "\n")
    return "\n".join(lines) + "\n" + tail


def _studies(read) -> dict:
    """workflow/studies.yaml: study name -> what it asks, its outputs (patterns) and, if older, what built them."""
    import yaml
    return yaml.safe_load(read("workflow/studies.yaml"))


def studies(read) -> str:
    """The research studies as workflow/studies.yaml lists them: name, what each asks, its outputs (patterns)."""
    listed = _studies(read)
    lines = ["| study | what it asks | output patterns |", "|---|---|---|"]
    lines += [f"| `{name}` | {s['what']} | {len(s['outputs'])} |" for name, s in listed.items()]
    return "\n".join(lines) + "\n"


def built_with(read) -> str:
    """The studies whose committed outputs come from an older code or model than the rebuild's (workflow/studies.yaml,
    each study's `built_with`): what each asks and what its outputs were built with, until it is run again."""
    listed = _studies(read)
    old = {name: s for name, s in listed.items() if s.get("built_with")}
    if not old:
        return "Every study's committed outputs come from the current code and model (`workflow/studies.yaml`).\n"
    lines = [f"{len(old)} of {len(listed)} studies' committed outputs come from an older code or model than the "
             "rebuild's, until `snakemake -c2 studies` runs them again (`built_with` in `workflow/studies.yaml`):", "",
             "| study | what it asks | built with |", "|---|---|---|"]
    lines += [f"| `{name}` | {s['what']} | {' '.join(s['built_with'].split())} |" for name, s in old.items()]
    return "\n".join(lines) + "\n"


BLOCKS = {"verdict": verdict, "built_with": built_with, "erosion_free_chaos": erosion_free_chaos, "claims": claims, "paper_eq9": paper_eq9, "studies": studies, "quasi_static": quasi_static, "levels": levels, "answer": answer, "rebuild": rebuild, "validation": validation, "fe_limit": fe_limit, "fe_band_means": fe_band_means, "fe_single_meshes": fe_single_meshes, "fe_text_claim": fe_text_claim, "fe_table3": fe_table3, "wall_times": wall_times, "accuracy": accuracy, "verification": verification, "erosion": erosion, "fe_speed": fe_speed, "rear_face": rear_face, "erosion_free": erosion_free, "erosion_free_status": erosion_free_status, "erosion_free_depths": erosion_free_depths, "erosion_free_window": erosion_free_window, "laboratory": laboratory, **SCALE_BLOCKS, **UNSTATED_BLOCKS}


def render(text: str, read) -> str:
    """``text`` with every generated block rebuilt from the outputs ``read(path)`` returns."""
    def fill(m):
        name = m.group("name")
        if name not in BLOCKS:
            raise KeyError(f"generated block {name!r}: known {sorted(BLOCKS)}")
        return m.group(1) + BLOCKS[name](read) + m.group(4)
    return BLOCK.sub(fill, text)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description="rewrite the generated blocks of markdown files from figures/")
    p.add_argument("files", nargs="+")
    p.add_argument("--check", action="store_true", help="change nothing; exit 1 if a file's blocks are out of date")
    args = p.parse_args(argv)
    read = lambda path: Path(path).read_text()
    stale = []
    for f in args.files:
        text = Path(f).read_text()
        new = render(text, read)
        if new != text:
            stale.append(f)
            if not args.check:
                from .io import write_text
                write_text(f, new)
    if args.check and stale:
        print(f"out of date: {', '.join(stale)} (python -m penetration.pipeline.docs {' '.join(stale)})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
