"""The generated blocks of the scale effect (docs/scale-effect.md, the README): from figures/scale/*.csv."""
from __future__ import annotations

from ..studies.scale import GOALS, best_variant, goals_met, recommended_variant
from .docs_read import rows_if_any

LEVEL_FACTOR = {"analytic": "S factor", "cavity": "strength scale", "fe": "failure strain"}


def _f(x, fmt):
    try:
        return format(float(x), fmt)
    except (TypeError, ValueError):
        return "—"


def _facts(read):
    """(DO1's measured depth text, series name -> its calibre in mm, the shots' count) from the reference and the
    development shots as the config's laboratory series name them."""
    import yaml

    from .docs_read import rows
    cfg = yaml.safe_load(read("workflow/config.yaml"))
    ref = {r["id"]: r for r in rows(read, cfg["reference"])}
    do1 = f"{float(ref[cfg['calibration']['do1']['depth']]['value']):g} m"
    shots = rows(read, cfg["validation"]["shots"])
    series = cfg["validation"]["laboratory"]["series"]
    calibre = {}
    for name, text in series.items():
        d = {float(r["diameter_m"]) for r in shots if text in r["source"]}
        calibre[name] = f"{1e3 * min(d):g} mm" if len(d) == 1 else f"{1e3 * min(d):g}-{1e3 * max(d):g} mm"
    return do1, calibre, len(shots)


def _fe_mesh(read) -> str:
    """The sentence that says at which mesh the fe level's study ran (from its calibration record), or ''."""
    import yaml

    fits = rows_if_any(read, "figures/scale/calibration_fe.csv")
    if not fits:
        return ""
    across = sorted({f"{float(r['elements_across_radius']):g}" for r in fits})
    profile = yaml.safe_load(read("workflow/config.yaml"))["scale_effect"]["fe_profile"]
    return (f" The fe level runs at the {profile} mesh ({' or '.join(across)} elements across each shot's shank radius), "
            "one realisation per shot and grid value.")


def _validations(read):
    """(level -> the rows of its figures/scale/validation_LEVEL.csv, the config's levels whose study has not run)."""
    import yaml

    found, missing = {}, []
    for level in yaml.safe_load(read("workflow/config.yaml"))["scale_effect"]["levels"]:
        rows = rows_if_any(read, f"figures/scale/validation_{level}.csv")
        if rows:
            found[level] = rows
        else:
            missing.append(level)
    return found, missing


def scale_effect(read) -> str:
    """Per level and variant of the scale effect: the factor fitted on each series alone and their ratio, the pooled
    leave-one-series-out errors, each series' mean error, DO1's prediction (fold all) and whether the goals hold."""
    do1, cal, n = _facts(read)
    lines = [f"| level | variant | mechanisms | factor on {cal['forrestal2003']} / {cal['forrestal1994']} | ratio | "
             f"held-out median / p90 &#124;error&#124; | mean error {cal['forrestal1994']} / {cal['forrestal2003']} | "
             f"DO1 ({do1}) | goals met |", "|---|---|---|---|---|---|---|---|---|"]
    found, missing = _validations(read)
    for level, rows in found.items():
        for r in rows:
            met = goals_met(r).values()
            lines.append(
                f"| {level} | {r['variant']} | {r['mechanisms']}"
                + (f", {r['beyond']}" if r["beyond"] else "")
                + (f", d_a {1e3 * float(r['aggregate_m']):g} mm" if r["aggregate_m"] else "")
                + f" | {_f(r['value_forrestal2003'], '.3g')} / {_f(r['value_forrestal1994'], '.3g')} "
                f"| {_f(r['split_ratio'], '.2f')} | {100 * float(r['loso_median_abs_rel_err']):.1f} / "
                f"{100 * float(r['loso_p90_abs_rel_err']):.1f} % | {100 * float(r['mean_rel_err_forrestal1994']):+.1f} / "
                f"{100 * float(r['mean_rel_err_forrestal2003']):+.1f} % | {float(r['do1_pred_m']):.2f} m "
                f"({100 * float(r['do1_rel_error']):+.1f} %) | {sum(met)} of {len(met)} |")
    tail = (f"\nGoals: held-out median |error| <= {100 * GOALS['loso_median']:.0f} % and 90th percentile <= "
            f"{100 * GOALS['loso_p90']:.0f} % (both series left out in turn, pooled), the two series' factors within a "
            f"ratio of {GOALS['split_ratio']:.2f}, DO1 within {100 * GOALS['do1']:.0f} % of {do1} (predicted with the "
            f"factor fitted on all {n} laboratory shots; DO1 enters no fit).") + _fe_mesh(read)
    if missing:
        tail += " Not yet run: " + ", ".join(f"`snakemake -c2 figures/scale/validation_{lv}.csv`" for lv in missing) + "."
    return "\n".join(lines) + "\n" + tail + "\n"


def scale_levels(read) -> str:
    """README's validation table of the scale effect: each level without it and with the variant of the smallest
    held-out median |error|, its errors left one series out, the ratio of the two series' factors, DO1 predicted by
    no fit of it, and the variant the command line takes by default (studies.scale.recommended_variant)."""
    do1, cal, n = _facts(read)
    lines = [f"| level | scale effect | held-out median / p90 &#124;error&#124; | series' factors apart | DO1 ({do1}, "
             "in no fit) | goals met | `--size auto` takes |", "|---|---|---|---|---|---|---|"]
    found, missing = _validations(read)
    for level, rows in found.items():
        auto = recommended_variant(rows) or "none"
        best = best_variant([r for r in rows if r["variant"] != "none"])
        shown = [r for r in rows if r["variant"] == "none"] + ([best] if best else [])
        for i, r in enumerate(shown):
            lines.append(f"| {level} | {r['variant']} ({r['mechanisms']}) | {100 * float(r['loso_median_abs_rel_err']):.1f}"
                         f" / {100 * float(r['loso_p90_abs_rel_err']):.1f} % | {float(r['split_ratio']):.2f} | "
                         f"{float(r['do1_pred_m']):.2f} m ({100 * float(r['do1_rel_error']):+.1f} %) | "
                         f"{sum(goals_met(r).values())} of {len(GOALS)} | {auto if i == 0 else ''} |")
    tail = (f"\nScope: the {n} laboratory shots ({cal['forrestal2003']} and {cal['forrestal1994']} series, each left "
            "out in turn) and DO1; each level's "
            "one factor is fitted on the laboratory shots with the variant (a calibration); the best variant is the one "
            "of the smallest held-out median. The analytic rows fit a factor on Li & Chen's S per series, hence their "
            "larger errors than the closed form's with S as published, whose authors fitted it on data that include "
            "these shots." + _fe_mesh(read) + " Every variant: [docs/scale-effect.md](docs/scale-effect.md).")
    if missing:
        tail += " Not yet run: " + ", ".join(f"`snakemake -c2 figures/scale/validation_{lv}.csv`" for lv in missing) + "."
    return "\n".join(lines) + "\n" + tail + "\n"


def _pt(x) -> str:
    """A change in points to one decimal, signed, with no negative zero."""
    text = f"{float(x):+.1f}"
    return "+0.0" if text == "-0.0" else text


def scale_table3(read) -> str:
    """Table 3's contrasts (all its shots at 140 mm) at each level without the scale effect and their change with each
    variant, in points, at the lowest and highest velocity, and the largest change over all four
    (figures/scale/table3.csv)."""
    rows = rows_if_any(read, "figures/scale/table3.csv")
    if not rows:
        return "Not yet run: `snakemake -c2 figures/scale/table3.csv`.\n"
    contrasts = list(dict.fromkeys(r["contrast"] for r in rows))
    velocities = sorted({float(r["velocity_ms"]) for r in rows})
    lo, hi = velocities[0], velocities[-1]
    lines = ["| level | variant | " + " | ".join(f"{c} at {lo:g} / {hi:g} m/s" for c in contrasts)
             + " | largest change |", "|---|---|" + "---|" * (len(contrasts) + 1)]
    groups = dict.fromkeys((r["level"], r["variant"]) for r in rows)
    for level, variant in groups:
        mine = [r for r in rows if r["level"] == level and r["variant"] == variant]
        at = {(r["contrast"], float(r["velocity_ms"])): r for r in mine}
        if variant == "none":
            cells = [f"{float(at[c, lo]['ratio']):.3f} / {float(at[c, hi]['ratio']):.3f}" for c in contrasts]
            largest = "-"
        else:
            cells = [f"{_pt(at[c, lo]['change_points'])} / {_pt(at[c, hi]['change_points'])} pt"
                     for c in contrasts]
            big = max(mine, key=lambda r: abs(float(r["change_points"])))
            largest = f"{_pt(big['change_points'])} pt ({big['contrast']}, {float(big['velocity_ms']):g} m/s)"
        lines.append(f"| {level} | {variant} | " + " | ".join(cells) + f" | {largest} |")
    tail = ("\nThe rows `none` give each contrast (a depth ratio) without the effect; the others its change with the "
            "variant, in points (100 x the change of the ratio), each level's factor fitted with the variant on the "
            "laboratory shots (`figures/scale/table3.csv`).")
    return "\n".join(lines) + "\n" + tail + "\n"


def scale_do1_gap(read) -> str:
    """How much calibre dependence DO1 asks of each level beside what the series show and each mechanism supplies
    (figures/scale/do1_gap.csv): the table and one sentence on the cavity level read off it."""
    rows = rows_if_any(read, "figures/scale/do1_gap.csv")
    if not rows:
        return "Not yet run: `snakemake -c2 figures/scale/do1_gap.csv`.\n"
    _, cal, _ = _facts(read)
    series = sorted(cal, key=lambda s: float(rows[0][f"calibre_{s}_m"]))
    small, large = series
    mm = {p: f"{1e3 * float(rows[0][f'calibre_{p}_m']):g} mm" for p in (*series, "do1")}
    ms = {p: f"{float(rows[0][f'velocity_{p}_ms']):.0f} m/s" for p in (*series, "do1")}
    lines = [f"| source | quantity | {mm[small]} ({ms[small]}) | {mm[large]} ({ms[large]}) | DO1, {mm['do1']} "
             f"({ms['do1']}) | {mm[large]} / {mm[small]} | DO1 / {mm[large]} | as a power of calibre |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        source = f"{r['name']} level" if r["kind"] == "level" else f"{r['name']} (mechanism)"
        lines.append(f"| {source} | {r['quantity']} | {float(r[f'value_{small}']):.3g} | "
                     f"{float(r[f'value_{large}']):.3g} | {float(r['value_do1']):.3g} | {float(r['ratio_series']):.3f} | "
                     f"{float(r['ratio_do1']):.3f} | {float(r['exponent_series']):+.2f} / "
                     f"{float(r['exponent_do1']):+.2f} |")
    tail = (f"\nThe level rows: the factor fitted on each series alone without the effect (`figures/scale/calibration_"
            f"LEVEL.csv`) and the level's calibration on DO1 (the fe level's at the study's mesh); the mechanism rows: "
            f"the factor on the resistance that each variant of the effect gives at each calibre and velocity (the "
            f"series' median), at the closed form's rate V/d. The last column: each ratio as a power of the calibre "
            f"ratio, {mm[small]} to {mm[large]} / {mm[large]} to DO1.")
    level = {r["name"]: r for r in rows if r["kind"] == "level"}
    mech = [r for r in rows if r["kind"] == "mechanism"]
    if "cavity" in level and mech:
        c = level["cavity"]
        frac = [float(r["ratio_do1"]) for r in mech if r["name"].startswith("fracture")]
        rate = [r for r in mech if r["name"] == "rate"]
        tail += (f" At the cavity level DO1 asks for a strength {float(c['ratio_do1']):.2f} times the {mm[large]} "
                 f"series' (a power {float(c['exponent_do1']):+.2f} of calibre), where the two series differ by "
                 f"{float(c['ratio_series']):.2f} (a power {float(c['exponent_series']):+.2f})")
        if frac:
            tail += f"; over the step to DO1, Bazant's law gives {min(frac):.2f}-{max(frac):.2f}"
        if rate:
            tail += (f" and the rate factor {float(rate[0]['ratio_do1']):.2f} (DO1 strikes at {ms['do1']}, the "
                     f"{mm[large]} series at a median {ms[large]}: a higher V/d)")
        tail += "."
    return "\n".join(lines) + "\n" + tail + "\n"


def do1_test_fe(read) -> str:
    """DO1 as a test of the fe level with its laboratory failure strain over realisations, in the semi-infinite target
    and in the experiment's block (figures/fe/do1_test.csv): the table and each target's effect against the first."""
    import yaml

    rows = rows_if_any(read, "figures/fe/do1_test.csv")
    if not rows:
        return "Not yet run: `snakemake -c2 figures/fe/do1_test.csv`.\n"
    bottom = yaml.safe_load(read("workflow/config.yaml"))["fe"]["block_depth"]
    place = {"semi_infinite": "the semi-infinite target", "block": "the experiment's block"}
    note = {"semi_infinite": " (users' shots)", "block": f" ({bottom:g} m deep, free faces)"}
    conf = f"{100 * float(rows[0]['confidence']):.0f} %"
    lines = [f"| target | realisations | mean depth (m) | range (m) | {conf} interval of the mean (m) | at rest / "
             f"perforated / moving at the end | DO1 deeper by |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {place.get(r['target'], r['target'])}{note.get(r['target'], '')} | {r['realisations']} | {float(r['mean_m']):.3f} | "
                     f"{float(r['min_m']):.3f}-{float(r['max_m']):.3f} | {float(r['mean_low_m']):.3f}-"
                     f"{float(r['mean_high_m']):.3f} | {r['at_rest']} / {r['perforated']} / {r['moving_at_end']} | "
                     f"{100 * float(r['excess']):+.1f} % ({100 * float(r['excess_low']):+.1f} to "
                     f"{100 * float(r['excess_high']):+.1f} %) |")
    first = rows[0]
    tail = []
    members = rows_if_any(read, "figures/fe/do1_test_members.csv")
    if members:
        v = sorted({float(m["striking_velocity_ms"]) for m in members})
        mantissa, exponent = f"{(v[1] / v[0] - 1) if len(v) > 1 else 0.0:.0e}".split("e")
        step = f"{mantissa}e{int(exponent)}"   # 1e-9, not 1e-09
        tail.append(f"Failure strain {float(members[0]['failure_strain']):.3f}, fitted on the laboratory shots at the "
                    f"full mesh ({float(members[0]['element_size_m']) * 1e3:g} mm elements at DO1); DO1 struck at "
                    f"{v[0]:g} m/s times 1 + k x {step}, k = 0-{int(first['realisations']) - 1} "
                    "(`figures/fe/do1_test.csv`, `figures/fe/do1_test_members.csv`).")
    for r in rows[1:]:
        tail.append(f"From {place.get(first['target'], first['target'])} to {place.get(r['target'], r['target'])} "
                    "the mean depth changes by "
                    f"{float(r['effect_vs_first_m']):+.3f} m ({conf} Welch interval {float(r['effect_low_m']):+.3f} to "
                    f"{float(r['effect_high_m']):+.3f} m).")
    return "\n".join(lines) + "\n" + ("\n" + " ".join(tail) + "\n" if tail else "")


def do1_test_fe_sentence(read) -> str:
    """One sentence for the README: the fe level's DO1 test in the semi-infinite target and in the block."""
    rows = {r["target"]: r for r in rows_if_any(read, "figures/fe/do1_test.csv")}
    if {"semi_infinite", "block"} - set(rows):
        return "The fe level's DO1 test in the experiment's block has not run: `snakemake -c2 figures/fe/do1_test.csv`.\n"
    import yaml

    s, b = rows["semi_infinite"], rows["block"]
    bottom = yaml.safe_load(read("workflow/config.yaml"))["fe"]["block_depth"]
    short = bottom - float(b["measured_depth_m"])
    return (f"Nor does DO1's block, {bottom:g} m deep with the shot stopped {short:.1f} m short of its rear face: the fe "
            f"level with its "
            f"failure strain fitted on the laboratory shots (full mesh, {b['realisations']} realisations each) goes "
            f"{float(s['mean_m']):.2f} m deep in the semi-infinite target and {float(b['mean_m']):.2f} m in the block "
            f"(the block adds {float(b['effect_vs_first_m']):+.2f} m, {100 * float(b['confidence']):.0f} % interval "
            f"{float(b['effect_low_m']):+.2f} to {float(b['effect_high_m']):+.2f} m), so DO1 is still "
            f"{100 * float(b['excess']):.0f} % deeper than predicted (`figures/fe/do1_test.csv`).\n")


BLOCKS = {"scale_effect": scale_effect, "scale_levels": scale_levels, "scale_table3": scale_table3,
          "scale_do1_gap": scale_do1_gap, "do1_test_fe": do1_test_fe,
          "do1_test_fe_sentence": do1_test_fe_sentence}
