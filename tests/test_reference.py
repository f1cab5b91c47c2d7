"""Reference data and the diff logic."""
from pathlib import Path

import pytest

from penetration.paper.diff import COLUMNS, STATUSES, arithmetic_check, holds, table1_rows, table3_rows
from penetration.paper.reference import Ref, load_reference

ROOT = Path(__file__).resolve().parents[1]
REF = ROOT / "workflow/reference/paper_values.csv"


def ref(value, unit="%", tol=0.01, relation="eq"):
    return Ref("x", "t", "q", "c", value, unit, relation, tol, "src", "")


def test_reference_file_loads_with_provenance():
    refs = load_reference(REF)
    assert len(refs) > 100
    assert all(r.source for r in refs.values())
    assert refs["table1.pc"].si == pytest.approx(16e6)
    assert refs["text.rho_sec22"].si == pytest.approx(2500.0)


def test_duplicate_ids_rejected(tmp_path):
    p = tmp_path / "r.csv"
    p.write_text(REF.read_text().splitlines()[0] + "\n" + "a,t,q,c,1,m,eq,0,s,\n" * 2)
    with pytest.raises(ValueError, match="duplicate"):
        load_reference(p)


def test_relations():
    assert holds("eq", 1.0, 1.009, 0.01) and not holds("eq", 1.0, 1.02, 0.01)
    assert holds("le", 0.04, 0.0368, 0) and not holds("le", 0.04, 0.244, 0)
    assert holds("lt", 0.0, -1e-3, 0) and not holds("lt", 0.0, 0.0, 0)


def test_arithmetic_check_accounts_for_printing():
    # 2.454 vs 2.248: 8.394 % of 2.454; a printed 8.39 is consistent, 8.50 is not
    a, b = ref(2.454, "m"), ref(2.248, "m")
    assert arithmetic_check(ref(8.39), lambda s, c: 100 * (s - c) / s, [a, b]).status == "paper-consistent"
    assert arithmetic_check(ref(8.50), lambda s, c: 100 * (s - c) / s, [a, b]).status == "paper-inconsistent"


def test_known_contradictions_are_found():
    refs = load_reference(REF)
    rows = {(r.item, r.quantity, r.case): r.status for r in table1_rows(refs) + table3_rows(refs)}
    assert rows[("table1", "K (as elastic bulk modulus pc/muc)", "concrete")] == "paper-inconsistent"
    bad = [k for k, s in rows.items() if s == "paper-inconsistent" and k[0] == "table3"]
    assert any("1000 crh45" in k[2] for k in bad) and any("800 crh45" in k[2] for k in bad)
    assert sum(s == "paper-consistent" for k, s in rows.items() if k[0] == "table3") >= 20
    assert "reproduced" not in rows.values()  # the paper against itself is never a reproduction


def test_committed_diff_has_the_contract():
    """Checks the committed figures/diff.csv (git HEAD's, whatever the working tree holds)."""
    import csv
    import io

    from conftest import committed
    rows = list(csv.DictReader(io.StringIO(committed("figures/diff.csv"))))
    assert tuple(rows[0]) == COLUMNS
    assert {r["status"] for r in rows} <= set(STATUSES)
    assert {r["item"] for r in rows} <= {f"table{i}" for i in range(1, 5)} | {f"fig{i:02d}" for i in range(1, 17)} | {"text"}


def _shot_refs(depth_at_shot_ratio):
    """Table 3 double-ogive row on a straight line in v; the shot at ratio x the line's 835 m/s value."""
    from penetration.paper.diff import table3_sim_at_shot
    line = lambda v: 0.01 * v - 3.0
    R = {f"table3.sim.{v}.double_ogive": ref(line(v), "m") for v in (500, 800, 1000, 1200)}
    R["table2.velocity"] = ref(835.0, "m/s")
    R["table2.dop"] = Ref("table2.dop", "table2", "dop", "DO1", 5.35 * depth_at_shot_ratio, "m", "eq", 0.05, "s", "")
    return table3_sim_at_shot(R)


def test_table3_row_interpolated_at_the_shot():
    # a monotone cubic reproduces a straight line; 835 m/s -> 5.35 m
    assert _shot_refs(1.0).ours == pytest.approx(5.35, rel=1e-12) and _shot_refs(1.0).status == "paper-consistent"
    assert _shot_refs(1.0 / 1.06).status == "paper-inconsistent"


def test_paper_table3_row_sits_above_the_shot():
    from penetration.paper.diff import table3_sim_at_shot
    row = table3_sim_at_shot(load_reference(REF))
    # linear interpolation between 800 and 1000 m/s gives 5.307 m, a chord above the convex row
    assert 5.27 < row.ours < 5.307 and row.rel_err == pytest.approx(0.037, abs=0.005)


def test_calibrated_agreement_has_its_own_status():
    """Agreement that a calibration produced is never counted as reproduction."""
    from penetration.paper.diff import compare
    r = ref(5.0)
    assert compare(r, 5.0).status == "reproduced"
    assert compare(r, 5.0, calibrated=True).status == "agrees-after-calibration"
    assert compare(r, 9.0, calibrated=True).status == "deviates"


def test_statuses_say_what_held():
    """Only a computed number compared with nothing fitted is `reproduced`: a sign or an axis range that holds is an
    `ordering`, an exact shape result `geometry`, the paper against its own numbers `paper-consistent`; each fails as
    `deviates` (ours) or `paper-inconsistent` (the paper's own)."""
    from penetration.paper.diff import AGREES, STATUS_MEANINGS, STATUSES, compare, consistency
    bound = Ref("x.b", "fig09", "t_axis_max", "c", 4.0, "ms", "le", 0.0, "s", "")
    assert compare(bound, 3.0, kind="ordering").status == "ordering"
    assert compare(bound, 5.0, kind="ordering").status == "deviates"
    assert compare(bound, 3.0).status == "reproduced"  # a computed number within the paper's bound for it
    assert compare(bound, 3.0, calibrated=True, kind="ordering").status == "agrees-after-calibration"
    assert compare(ref(5.0), 5.01, kind="geometry").status == "geometry"
    assert compare(ref(5.0), 6.0, kind="geometry").status == "deviates"
    assert consistency(ref(5.0), 5.001, 0.01).status == "paper-consistent"
    assert consistency(ref(5.0), 6.0, 0.01).status == "paper-inconsistent"
    assert set(AGREES) < set(STATUSES) and "deviates" not in AGREES and STATUSES[0] == "reproduced"
    assert all(len(m) > 20 for m in STATUS_MEANINGS.values())


def test_the_paper_against_itself_and_its_shapes_are_not_counted_as_reproduced():
    """The diff's rows that check the paper's arithmetic (Table 3's derived columns, the text's gains from its own
    table) and the nose's exact geometry (Table 4's N* and masses) hold under their own statuses, so the count of
    `reproduced` is a count of computed model numbers."""
    from penetration.paper.diff import table3_rows, table4_rows
    refs = load_reference(REF)
    assert {r.status for r in table3_rows(refs)} <= {"paper-consistent", "paper-inconsistent"}
    ours = {f"{q}.{n}": refs[f"table4.{q}.{s}"].si for q in ("nstar", "mass")
            for s, n in (("cone", "cone"), ("jones", "minimum_nstar"), ("double_ogive", "double_ogive"), ("crh45", "crh45"))}
    statuses = {r.status for r in table4_rows(refs, ours)}
    assert "reproduced" not in statuses and "geometry" in statuses


def test_contrast_claims_use_the_least_gain_over_table3_velocities():
    """'+10 % over CRH 3 at the same velocity' is a lower bound: one velocity below it makes the level deviate,
    and a calibrated level that meets it agrees only after calibration."""
    from penetration.paper.diff import CONTRAST_LEVELS, contrast_rows
    from penetration.tasks.contrasts import contrast_rows as gather
    refs = load_reference(REF)
    claim = refs["text.gain_pct_crh3"].quantity

    def rows_for(do500):
        depths = {}
        for v, do, crh45, crh3 in ((500.0, do500, 2.0, 1.9), (1200.0, 9.0, 8.0, 7.0)):
            depths.update({("double_ogive", v): do, ("crh45", v): crh45, ("crh3", v): crh3})
        return [r for level, variant, _ in CONTRAST_LEVELS for r in gather(depths, level, variant, "table3")]

    rows = rows_for(2.2)
    ratios = {(r["contrast"], r["velocity"]): r["ratio"] for r in rows if r["level"] == "cavity"}
    assert ratios[("DO/CRH 4.5", 1200.0)] == pytest.approx(1.125, rel=1e-14)
    assert ratios[("CRH 4.5/CRH 3", 500.0)] == pytest.approx(2.0 / 1.9, rel=1e-14)
    least = [r for r in contrast_rows(refs, rows) if r.quantity == claim]
    assert len(least) == len(CONTRAST_LEVELS)
    assert all(r.ours == pytest.approx(100 * (2.2 / 1.9 - 1), rel=1e-12) for r in least)  # 500 m/s: the smaller gain
    assert [r.status for r in least] == ["agrees-after-calibration", "reproduced", "agrees-after-calibration"]
    low = [r for r in contrast_rows(refs, rows_for(2.05)) if r.quantity == claim]  # +7.9 % at 500 m/s
    assert {r.status for r in low} == {"deviates"}


@pytest.mark.parametrize("low, high, status", [(10.0, 13.0, "agrees-after-calibration"), (7.0, 13.0, "undecided"),
                                               (9.5, 20.0, "undecided"), (12.5, 20.0, "deviates"), (1.0, 9.0, "deviates")])
def test_an_interval_is_judged_on_where_it_lies_against_the_paper_and_the_tolerance(low, high, status):
    """Paper 11.5 with a 2-point goal: inside the goal agrees, excluding the paper deviates, anything else is
    undecided (the interval holds the paper's value and values outside the goal)."""
    from penetration.paper.diff import interval_status
    assert interval_status(11.5, low, high, 2.0) == status


def test_fe_limit_rows_compare_the_extrapolated_increment_with_the_paper():
    from penetration.paper.diff import fe_limit_rows
    refs = load_reference(REF)
    row = {"contrast": "DO/CRH 4.5", "velocity_ms": 800, "meshes": 21, "confidence": 0.95,
           "ratio_at_zero_size": 1.147, "interval_low": 1.097, "interval_high": 1.197}
    (r,) = fe_limit_rows(refs, [row])
    assert r.paper == refs["table3.inc_equiv.800.double_ogive"].value and r.ours == pytest.approx(14.7)
    assert r.status == "deviates" and "9.7 to 19.7 points" in r.case
    (r,) = fe_limit_rows(refs, [{**row, "interval_low": 1.0}])
    assert r.status == "undecided"


def _chaos_row(quantity, kind, velocity, estimate, u, holds):
    """A row of the erosion-free grid study with the chaos (studies.chaos.chaos_rows), as its CSV holds it."""
    return {"quantity": quantity, "kind": kind, "velocity_ms": str(float(velocity)), "estimate": str(estimate),
            "uncertainty": str(u), "fit_holds": str(holds), "meshes": "3", "realisations_min": "3",
            "status": "limit within the goal" if holds else
            "no limit: the means do not follow a first-order line within their chaos"}


@pytest.mark.parametrize("ratio, band, limit, ranking", [(1.0686, 0.005, True, "ordering"), (1.0, 0.01, True, "undecided"),
                                                          (1.05, 0.03, True, "ordering"), (0.97, 0.01, True, "deviates"),
                                                          (1.0686, 0.005, False, "undecided"),
                                                          (float("nan"), float("nan"), True, "undecided")])
def test_erosion_free_rows_judge_the_ranking_on_the_verdicts_interval(ratio, band, limit, ranking):
    """DO/CRH 4.5 at 800 m/s on the erosion-free target: the paper's ranking (the ratio above 1) judged on the verdict
    table's value +- uncertainty (its booleans as the CSV's text): ordering where the whole interval lies above 1,
    deviates below, undecided where it holds 1, where the study found no limit or has not run (pending)."""
    from penetration.paper.diff import erosion_free_rows
    refs = load_reference(REF)
    row = {"contrast": "DO/CRH 4.5", "velocity_ms": "800", "value": ratio, "uncertainty": band, "limit": str(limit),
           "uncertainty_basis": "t x s.e. of the line through 3 meshes, ..."}
    (rank,) = erosion_free_rows(refs, [row])
    assert rank.status == ranking and rank.paper == 1.0 and "3 meshes; ..." in rank.case


@pytest.mark.parametrize("depth, band, holds, status", [(7.9, 0.05, True, "reproduced"), (5.3, 0.1, True, "deviates"),
                                                        (7.3, 0.6, True, "undecided"), (7.9, 0.05, False, "undecided")])
def test_erosion_free_depth_rows_judge_the_stated_depth_on_its_interval_and_call_a_calibrated_one_so(depth, band, holds,
                                                                                                   status):
    """CRH 3 at 1200 m/s (the paper's simulation: 7.860 m, 7.5 %): the stated HJC's depth at zero element size +- U
    against the tolerance (reproduced only when the whole interval lies within it; no limit: undecided); the
    DO1-calibrated depth of one mesh is compared by value and, within the tolerance, agrees after calibration, never
    reproduces."""
    from penetration.paper.diff import erosion_free_depth_rows
    refs = load_reference(REF)
    ref = refs["table3.sim.1200.crh3"]
    limit = _chaos_row("crh3", "depth", 1200, depth, band, holds)
    ratio = _chaos_row("DO/CRH 4.5", "contrast", 1200, 1.0, 0.01, True)
    cal = {"nose": "crh3", "velocity_ms": 1200.0, "depth_calibrated_m": depth, "strength_scale": 0.55,
           "elements_across_radius": 16.0, "pilot_hole": 0.125}
    stated, calibrated = erosion_free_depth_rows(refs, [limit, ratio], [cal])
    assert stated.paper == ref.value == 7.86 and stated.ours == depth and stated.status == status
    want = "agrees-after-calibration" if abs(depth - ref.value) <= ref.tol * ref.value else "deviates"
    assert calibrated.ours == depth and calibrated.status == want and "calibrated on DO1" in calibrated.quantity
    assert "strength scale 0.550" in calibrated.case


def test_erosion_free_depth_rows_of_a_velocity_without_an_estimate_decide_nothing():
    """A velocity whose study has fewer than three meshes has no estimate (an empty cell in the CSV): undecided,
    and the case says why."""
    from penetration.paper.diff import erosion_free_depth_rows
    refs = load_reference(REF)
    row = {**_chaos_row("crh3", "depth", 1200, "", "", False), "status": "fewer than 3 meshes with a mean"}
    (d,) = erosion_free_depth_rows(refs, [row], [])
    assert d.status == "undecided" and "fewer than 3 meshes" in d.case


def test_do1_predicted_by_a_level_never_fitted_on_it_is_predicted_within_the_tolerance_else_deviates():
    """DO1 as a test (figures/scale/do1_LEVEL.csv): 5.1 m measured, tolerance 5 %; a depth from a factor fitted on the
    laboratory shots is `predicted` inside it (never `reproduced`, never `agrees-after-calibration`), `deviates`
    outside, and the case names the level, the variant and the fitted factor."""
    from penetration.paper.diff import AGREES, scale_do1_rows
    refs = load_reference(REF)
    ref = refs["table2.dop"]
    base = {"parameter": "s_scale", "value": 0.1}
    table = [{**base, "variant": "none", "dop_pred_m": 3.83}, {**base, "variant": "rate", "dop_pred_m": 5.1 * 1.049},
             {**base, "variant": "rate_fracture", "dop_pred_m": 5.1 * 0.949}]
    rows = scale_do1_rows(refs, {"cavity": table})
    assert [r.status for r in rows] == ["deviates", "predicted", "deviates"] and ref.tol == 0.05
    assert "predicted" in AGREES and "predicted" in STATUSES
    assert "cavity level with the scale effect rate (s_scale 0.1 fitted on the laboratory shots; DO1 in no fit)" in rows[1].case
    assert "without the scale effect" in rows[0].case and rows[0].paper == 5.1
