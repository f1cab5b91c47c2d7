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


def with_verdict(row):
    """A zero-hole row with the study's verdict columns (studies.grid.ranking_verdict, as hole_rows writes them)."""
    from penetration.studies.grid import ranking_verdict
    limit = str(row.get("limit_found", "True")) == "True"
    verdict, basis = ranking_verdict(limit, row.get("ranking", ""), row.get("ls_ranking", "undecided"),
                                     row.get("side_of_1", ""))
    return {**row, "verdict": verdict, "verdict_basis": basis}


@pytest.mark.parametrize("ratio, band, status, ranking", [(1.0686, 0.005, "reproduced", "ordering"),
                                                          (1.0, 0.01, "deviates", "undecided"),
                                                          (1.05, 0.03, "undecided", "ordering"),
                                                          (0.97, 0.01, "deviates", "deviates")])
def test_erosion_free_rows_judge_the_converged_contrast_and_the_ranking_on_its_band(ratio, band, status, ranking):
    """DO/CRH 4.5 at 800 m/s (the paper's simulation: +6.86 %): the converged ratio with its GCI band against the
    paper's increment (2 points, nothing calibrated: agreement is a reproduction) and against 1 (the ranking)."""
    from penetration.paper.diff import erosion_free_rows
    refs = load_reference(REF)
    from penetration.studies.grid import ranking as study_ranking
    row = {"quantity": "depth_ratio", "case": "DO/CRH 4.5", "velocity_ms": 800.0, "at_zero_hole": ratio,
           "uncertainty": band, "mesh_status_all_asymptotic": True, "hole_status": "asymptotic",
           "ranking": study_ranking(ratio, band)}   # the study's verdict column (grid_study.hole_rows)
    eroding = [{"contrast": "DO/CRH 4.5", "velocity_ms": 800, "ratio_at_zero_size": 1.147, "interval_low": 1.097,
                "interval_high": 1.197}]
    table = [{"contrast": "DO/CRH 4.5", "velocity": 800, "cavity_ratio": 1.031, "analytic_stated_S_ratio": 1.014}]
    row = with_verdict(row)
    inc, rank = erosion_free_rows(refs, [row, {**row, "quantity": "depth_m", "case": "crh3"}], eroding, table)
    assert inc.paper == refs["table3.inc_equiv.800.double_ogive"].value and inc.ours == pytest.approx(100 * (ratio - 1))
    assert inc.status == status and rank.status == ranking
    assert "eroding FE at zero size 1.147" in inc.case and "cavity level 1.031" in inc.case


@pytest.mark.parametrize("asymptotic, stopped", [("True", "False"), ("False", "True")])
def test_erosion_free_rows_read_the_csv_booleans_of_the_mesh_status(asymptotic, stopped):
    """The study's CSV holds its booleans as text: "False" must read as not asymptotic and no shot stopped."""
    from penetration.paper.diff import erosion_free_rows
    refs = load_reference(REF)
    row = {"quantity": "depth_ratio", "case": "DO/CRH 4.5", "velocity_ms": "800", "at_zero_hole": "1.05",
           "uncertainty": "0.01", "mesh_status_all_asymptotic": asymptotic, "meshes_stopped": stopped,
           "hole_status": "asymptotic", "ranking": "holds", "limit_found": "True"}
    inc, _ = erosion_free_rows(refs, [with_verdict(row)], [], [])
    assert ("not all asymptotic" in inc.case) == (asymptotic == "False")
    assert ("a shot stopped" in inc.case) == (stopped == "True")


@pytest.mark.parametrize("depth, band, status", [(7.9, 0.05, "reproduced"), (5.3, 0.1, "deviates"),
                                                 (7.3, 0.6, "undecided")])
def test_erosion_free_depth_rows_judge_the_stated_depth_on_its_band_and_call_a_calibrated_one_so(depth, band, status):
    """CRH 3 at 1200 m/s (the paper's simulation: 7.860 m, 7.5 %): the stated HJC's depth at zero size and hole with
    its band against the tolerance (reproduced only when the whole band lies within it); the DO1-calibrated depth of
    one mesh is compared by value and, within the tolerance, agrees after calibration, never reproduces."""
    from penetration.paper.diff import erosion_free_depth_rows
    refs = load_reference(REF)
    ref = refs["table3.sim.1200.crh3"]
    limit = {"quantity": "depth_m", "case": "crh3", "velocity_ms": 1200.0, "at_zero_hole": depth, "uncertainty": band}
    ratio = {**limit, "quantity": "depth_ratio", "case": "DO/CRH 4.5"}
    cal = {"nose": "crh3", "velocity_ms": 1200.0, "depth_calibrated_m": depth, "strength_scale": 0.55,
           "elements_across_radius": 16.0, "pilot_hole": 0.125}
    stated, calibrated = erosion_free_depth_rows(refs, [limit, ratio], [cal])
    assert stated.paper == ref.value == 7.86 and stated.ours == depth and stated.status == status
    want = "agrees-after-calibration" if abs(depth - ref.value) <= ref.tol * ref.value else "deviates"
    assert calibrated.ours == depth and calibrated.status == want and "calibrated on DO1" in calibrated.quantity
    assert "strength scale 0.550" in calibrated.case


def test_erosion_free_rows_without_a_limit_give_the_spread_and_decide_nothing():
    """A zero-hole row with no limit (the study's refinement found none) and no least-squares interval at some hole:
    the diff gives the median and range of every mesh's and hole's value, never a verdict, for the increment, the
    ranking and the depth."""
    from penetration.paper.diff import erosion_free_depth_rows, erosion_free_rows
    refs = load_reference(REF)
    row = {"quantity": "depth_ratio", "case": "CRH 4.5/CRH 3", "velocity_ms": 1200.0, "at_zero_hole": 1.02,
           "uncertainty": float("inf"), "limit_found": "False", "values": 12, "values_min": 1.072,
           "values_median": 1.10, "values_max": 1.16, "mesh_status_all_asymptotic": False, "hole_status": "oscillatory",
           "side_of_1": "above 1 on every mesh and hole", "ranking": "undecided", "ls_low": "", "ls_high": "",
           "ls_ranking": "undecided"}
    row = with_verdict(row)
    eroding = [{"contrast": "CRH 4.5/CRH 3", "velocity_ms": 1200, "ratio_at_zero_size": 0.95, "interval_low": 0.9,
                "interval_high": 1.0}]
    table = [{"contrast": "CRH 4.5/CRH 3", "velocity": 1200, "cavity_ratio": 1.041, "analytic_stated_S_ratio": 1.03}]
    inc, rank = erosion_free_rows(refs, [row], eroding, table)
    assert "eroding FE at zero size 0.950" in inc.case and "cavity level 1.041" in inc.case
    assert inc.status == rank.status == "undecided" and inc.ours == pytest.approx(10.0)
    assert "1.072 to 1.160" in inc.case and "above 1 on every mesh and hole" in rank.case and rank.ours == 1.10
    (depth,) = erosion_free_depth_rows(refs, [{**row, "quantity": "depth_m", "case": "crh3", "values_min": 5.2,
                                                "values_median": 5.5, "values_max": 6.6}], [])
    assert depth.status == "undecided" and depth.ours == 5.5 and "5.200 m to 6.600 m" in depth.case


@pytest.mark.parametrize("low, high, ls_ranking, inc_status, rank_status",
                         [(1.03, 1.09, "holds at every hole", "undecided", "ordering"),
                          (1.08, 1.20, "holds at every hole", "deviates", "ordering"),
                          (0.98, 1.09, "undecided", "undecided", "undecided"),
                          (0.90, 0.98, "fails at every hole", "deviates", "deviates")])
def test_erosion_free_rows_without_a_limit_are_judged_on_the_holes_least_squares_hull(low, high, ls_ranking,
                                                                                        inc_status, rank_status):
    """No limit, but every hole has a least-squares interval: the increment is judged on their hull (the paper's
    CRH 4.5/CRH 3 at 1200 m/s, +5.9 %, outside the hull: deviates; inside: undecided) and the ranking on the
    study's verdict on its ls_ranking (above 1 at every hole: the ordering holds, at the holes run); the depth likewise on
    its hull."""
    from penetration.paper.diff import erosion_free_depth_rows, erosion_free_rows
    refs = load_reference(REF)
    row = {"quantity": "depth_ratio", "case": "CRH 4.5/CRH 3", "velocity_ms": 1200.0, "at_zero_hole": 1.02,
           "uncertainty": float("inf"), "limit_found": "False", "values": 12, "values_min": 1.072,
           "values_median": 1.10, "values_max": 1.16, "side_of_1": "above 1 on every mesh and hole",
           "ranking": "undecided", "ls_low": str(low), "ls_high": str(high), "ls_ranking": ls_ranking}
    row = with_verdict(row)
    inc, rank = erosion_free_rows(refs, [row], [], [])
    assert refs["table3.inc_crh3.1200.crh45"].value == pytest.approx(5.87, abs=1e-9)
    assert inc.status == inc_status and rank.status == rank_status
    assert f"{low:.3f} to {high:.3f} (at the holes run)" in inc.case and "(at the holes run)" in rank.case
    depth = {**row, "quantity": "depth_m", "case": "crh3", "values_median": 5.5, "ls_low": "5.0", "ls_high": "6.0"}
    (d,) = erosion_free_depth_rows(refs, [depth], [])
    assert d.status == "deviates" and "5.000 to 6.000 m" in d.case   # the paper's 7.86 m outside the hull


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
