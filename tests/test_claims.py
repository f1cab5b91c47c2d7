"""The paper's claims judged at each level (paper.claims): the verdict rules against hand-made tables; the whole table
from the committed outputs against the committed claims and the bottom line of the committed report (which, before
the verdicts moved into the pipeline, judged them with code of its own and gave the same cells)."""
import html
import json
from pathlib import Path

import pandas as pd
import pytest

from penetration.levels import LEVELS
from penetration.paper import claims as C

ROOT = Path(__file__).resolve().parents[1]


def _paper():
    return pd.read_csv(ROOT / "workflow/reference/paper_values.csv").set_index("id")


def _rows(*rows):
    """The verdict table's erosion-free rows for one contrast (figures/verdict.csv as read): (velocity, value,
    uncertainty, limit)."""
    return pd.DataFrame([{"contrast": "DO/CRH 4.5", "velocity_ms": v, "value": e, "uncertainty": u, "limit": str(h)}
                         for v, e, u, h in rows])


NAN = float("nan")


@pytest.mark.parametrize("rows, word, phrase", [
    ([(500.0, 1.05, 0.02, True), (1200.0, 1.08, 0.01, True)], "holds",
     "holds (500 m/s 1.050 ± 0.020; 1200 m/s 1.080 ± 0.010 at zero element size)"),
    ([(1200.0, 0.97, 0.01, True), (500.0, 0.95, 0.02, True)], "fails",
     "fails (500 m/s 0.950 ± 0.020; 1200 m/s 0.970 ± 0.010 at zero element size)"),
    ([(500.0, 1.05, 0.02, True), (1200.0, 1.005, 0.01, True)], "undecided",
     "is undecided (500 m/s 1.050 ± 0.020; 1200 m/s 1.005 ± 0.010 at zero element size)"),
    ([(500.0, 1.05, 0.02, False), (1200.0, 1.08, 0.01, True)], "undecided",
     "is undecided (500 m/s 1.050 ± 0.020 (no limit); 1200 m/s 1.080 ± 0.010 at zero element size)"),
    ([(500.0, 1.05, 0.02, True), (1200.0, NAN, NAN, False)], "undecided",
     "is undecided (500 m/s 1.050 ± 0.020; 1200 m/s pending at zero element size)"),
])
def test_a_contrasts_ranking_is_the_consensus_of_its_velocities(rows, word, phrase):
    """Above 1 where the whole of value +- uncertainty lies above it, at every velocity the study runs; a velocity
    without a limit (the line does not hold the means) or not yet run decides nothing."""
    assert C.contrast_ranking(_rows(*rows)) == (word, phrase)


@pytest.mark.parametrize("low_ratio, word", [(1.06, "holds"), (1.03, "weaker"), (1.0, "fails"), (0.97, "fails")])
def test_the_least_gain_holds_only_when_every_velocitys_ratio_reaches_the_claimed_one(low_ratio, word):
    """The paper claims at least 5 % over the CRH 4.5 ogive (text.gain_pct_crh45): the level's smallest ratio over
    the velocities decides."""
    paper = _paper()
    assert float(paper.value["text.gain_pct_crh45"]) == 5.0
    contrasts = pd.DataFrame({"contrast": ["DO/CRH 4.5"] * 2, "velocity": [500, 1200],
                              "cavity_ratio": [low_ratio, 1.10]})
    ev = C.Evidence(paper, contrasts, None, None, None, None, None, 1.0, None, None)
    verdict, evidence, value = C.least_gain(ev, "cavity", "DO/CRH 4.5")
    assert verdict == word and value == low_ratio and evidence.endswith("at 500 m/s")


def _committed_evidence(profile="full"):
    fig = ROOT / "figures"
    cavity = pd.read_csv(fig / "calibration_cavity_do1.csv")
    return C.Evidence(
        paper=_paper(), contrasts=pd.read_csv(fig / "nose_contrasts_table.csv"), diff=pd.read_csv(fig / "diff.csv"),
        fe_diff=pd.read_csv(fig / f"fe/{profile}/diff.csv"), band=pd.read_csv(fig / "fe/contrast_band.csv"),
        extrapolation=pd.read_csv(fig / "fe/contrast_extrapolation.csv"),
        validation=pd.read_csv(fig / f"fe/{profile}/validation_levels_summary.csv"),
        cavity_scale=float(cavity.value.iloc[0]),
        fe_calibration=pd.read_csv(fig / f"fe/{profile}/calibration_fe_do1.csv").iloc[0],
        erosion_free=pd.read_csv(fig / "verdict.csv"))


def test_the_claims_from_the_committed_outputs_are_the_committed_reports_bottom_line():
    """Every cell of the report's bottom line (verdict: evidence) and every ranking it states on the erosion-free
    target, from the committed outputs of the full profile."""
    rows = C.claim_rows(_committed_evidence())
    report = html.unescape((ROOT / "figures/report.html").read_text())
    judged = [r for r in rows if r["level"] in LEVELS]
    assert len(judged) == 6 * len(LEVELS)
    for r in judged:
        assert f"<b>{r['verdict']}</b>: {r['evidence']}" in report, r
    for r in rows[len(judged):]:
        assert f"the paper's ranking {r['evidence']}" in report, r


def test_the_claims_table_has_its_columns_and_a_value_where_one_number_decides():
    rows = pd.DataFrame(C.claim_rows(_committed_evidence()), columns=C.COLUMNS)
    assert list(rows.columns) == C.COLUMNS and rows.claim_id.nunique() == 6 + 3
    peaks = rows[(rows.claim_id == "smaller_peak") & (rows.level != "analytic")]
    assert peaks.value.notna().all() and ((peaks.value < 0) == peaks.verdict.str.startswith("holds")).all()
    assert json.dumps(list(rows.level.unique())) == json.dumps([*LEVELS, "erosion_free"])


@pytest.mark.parametrize("profile", ["full", "ci"])
def test_the_committed_claims_are_those_of_the_committed_outputs(profile):
    """figures/fe/{profile}/claims.csv is what paper.claims makes of the outputs committed beside it."""
    made = pd.DataFrame(C.claim_rows(_committed_evidence(profile)), columns=C.COLUMNS)
    committed = pd.read_csv(ROOT / f"figures/fe/{profile}/claims.csv")
    pd.testing.assert_frame_equal(made, committed, check_exact=False, rtol=1e-11)


# Each remaining verdict rule against small hand-made tables that reach every word it can give (the committed-output
# tests above compare the rules with their own earlier output, so they cannot tell a wrong rule).

def _evidence(**frames):
    base = dict(paper=_paper(), contrasts=None, diff=None, fe_diff=None, band=None, extrapolation=None,
                validation=None, cavity_scale=0.8, fe_calibration=None, erosion_free=None)
    return C.Evidence(**{**base, **frames})


def _extrapolation(contrast, *cells):
    """Zero-size intervals of one contrast: (velocity, low, high, paper inside)."""
    return pd.DataFrame([{"contrast": contrast, "velocity_ms": v, "interval_low": lo, "interval_high": hi,
                          "paper_inside_interval": inside} for v, lo, hi, inside in cells])


@pytest.mark.parametrize("cells, word, evidence", [
    ([(500, 1.06, 1.09), (1200, 1.07, 1.12)], "holds", "+6.0 % to +9.0 % at zero element size (500 m/s)"),
    ([(500, 1.01, 1.04), (1200, 1.07, 1.12)], "weaker", "+1.0 % to +4.0 % at zero element size (500 m/s)"),
    ([(500, 0.95, 0.99), (1200, 1.07, 1.12)], "fails", "-5.0 % to -1.0 % at zero element size (500 m/s)"),
    ([(500, 1.00, 1.08), (1200, 1.03, 1.20)], "cannot decide", "+3.0 % to +20.0 % at zero element size (1200 m/s)"),
])
def test_the_fe_least_gain_reads_the_zero_size_intervals(cells, word, evidence):
    """At least 5 % deeper (text.gain_pct_crh45): holds where every interval lies at or above 1.05; weaker or fails
    (above or below 1) where one lies below it; else undecidable, shown by the widest interval that straddles it."""
    ev = _evidence(extrapolation=_extrapolation("DO/CRH 4.5", *[(v, lo, hi, True) for v, lo, hi in cells]))
    got = C.least_gain(ev, "fe", "DO/CRH 4.5")
    assert got[:2] == (word, evidence) and got[2] != got[2]


def test_without_an_extrapolation_the_fe_least_gain_reports_the_spread_of_one_mesh_size():
    band = pd.DataFrame({"contrast": ["DO/CRH 4.5"] * 2, "velocity_ms": [500, 1200], "min_ratio": [1.00, 1.02],
                         "max_ratio": [1.03, 1.09]})
    assert C.least_gain(_evidence(band=band), "fe", "DO/CRH 4.5")[:2] == (
        "cannot decide", "meshes of one size spread it over 7 pts")


def _contrasts_1200(do_crh45, do_crh3, level="cavity"):
    """The nose-contrast table at the claim's velocity (1200 m/s, text.gain_1200_crh45): a level's ratios and gains
    beside the paper's simulated ratios 1.10 and 1.20."""
    return pd.DataFrame({"contrast": ["DO/CRH 4.5", "DO/CRH 3"], "velocity": [1200, 1200],
                         f"{level}_ratio": [do_crh45, do_crh3], f"{level}_gain_m": [0.55, 1.1],
                         "paper_sim_ratio": [1.10, 1.20]})


@pytest.mark.parametrize("ratios, word", [((1.11, 1.185), "matches"), ((1.11, 1.17), "misses"),
                                          ((1.075, 1.20), "misses")])
def test_the_gains_at_the_claimed_velocity_match_within_two_points_of_both_ratios(ratios, word):
    ev = _evidence(contrasts=_contrasts_1200(*ratios))
    assert C.gains_at_v(ev, "cavity") == (word, "+0.55 m and +1.10 m", pytest.approx(float("nan"), nan_ok=True))


@pytest.mark.parametrize("cells, word", [
    ([(1.09, 1.11, True), (1.19, 1.22, True)], "matches"),           # both within +-1.5 points, the paper inside
    ([(1.05, 1.15, True), (1.19, 1.22, True)], "cannot decide"),     # one +-5 points wide: holds the paper and more
    ([(1.11, 1.13, False), (1.19, 1.22, True)], "misses"),           # the paper outside one interval
])
def test_the_fe_gains_at_the_claimed_velocity_read_the_zero_size_intervals(cells, word):
    (a_lo, a_hi, a_in), (b_lo, b_hi, b_in) = cells
    ext = pd.concat([_extrapolation("DO/CRH 4.5", (1200, a_lo, a_hi, a_in)),
                     _extrapolation("DO/CRH 3", (1200, b_lo, b_hi, b_in)),
                     _extrapolation("DO/CRH 4.5", (500, 0.5, 2.0, False))])
    got = C.gains_at_v(_evidence(extrapolation=ext), "fe")
    halves = [50 * (a_hi - a_lo), 50 * (b_hi - b_lo)]
    assert got[0] == word and got[1] == f"zero-size intervals ±{halves[0]:.0f} pts and ±{halves[1]:.0f} pts"


@pytest.mark.parametrize("ratio, word", [(1.0, "matches"), (1.049, "matches"), (0.94, "misses"), (1.06, "misses")])
def test_the_do1_depth_with_the_papers_s_matches_within_the_papers_tolerance(ratio, word):
    """Eq 9's DO1 depth is the diff's Pd/d ratio (ours over the paper's) times the measured 5.1 m; it matches within
    the paper's tolerance of 5 % (table2.dop)."""
    paper = _paper()
    assert float(paper.value["table2.dop"]) == 5.1 and float(paper.tol["table2.dop"]) == 0.05
    diff = pd.DataFrame({"item": ["fig15", "fig15"], "quantity": ["pd_over_d"] * 2,
                         "case": ["DO1 (S = 72)", "DO1 (S = 60)"], "ours": [36.0 * ratio, 1.0], "paper": [36.0, 1.0]})
    word_got, evidence, depth = C.do1(_evidence(diff=diff), "analytic")
    assert word_got == word and depth == pytest.approx(5.1 * ratio, rel=1e-12)
    assert evidence == f"{5.1 * ratio:.2f} m ({100 * (ratio - 1):+.0f} %) with the paper's S"


def test_do1_is_a_calibration_at_the_cavity_and_fe_levels_never_a_match():
    fit = pd.Series({"value": 1.0103, "element_size_m": 0.00875})
    ev = _evidence(cavity_scale=0.8002, fe_calibration=fit)
    assert C.do1(ev, "cavity") == ("fitted to it", "strength × 0.80", 0.8002)
    assert C.do1(ev, "fe") == ("fitted to it", "fs = 1.01 at 8.75 mm", 1.0103)


@pytest.mark.parametrize("margins, word, evidence", [
    ((-0.08, -0.03), "holds", "3.0 % lower at least"),
    ((-0.08, 0.02), "fails", "+2.0 % higher at worst"),
])
def test_the_smallest_peak_holds_only_when_the_double_ogive_is_below_every_other_nose(margins, word, evidence):
    """The largest (least negative) of the double ogive's peak deceleration margins over the other noses decides."""
    def rows(tag):
        return pd.DataFrame({"item": ["fig08"] * 2 + ["fig14"] * 2,
                             "quantity": ["peak_deceleration_double_ogive_minus_crh3",
                                          "peak_deceleration_double_ogive_minus_crh45"] * 2,
                             "case": ["", "", tag, tag], "ours": [*margins, *margins]})
    ev = _evidence(diff=rows("(cavity level)"), fe_diff=rows("(FE level)"))
    assert C.smaller_peak(ev, "trajectory") == (word, evidence, max(margins))
    assert C.smaller_peak(ev, "fe") == (word + " on one mesh", evidence, max(margins))
    assert C.smaller_peak(ev, "analytic")[0] == "—"


@pytest.mark.parametrize("err, word, text", [(0.072, "good", "median error 7.2 %"), (0.10, "good", "median error 10.0 %"),
                                             (0.103, "poor", "median error 10.3 %"), (0.178, "poor", "median error 17.8 %")])
def test_a_level_predicts_well_when_its_out_of_sample_median_error_is_within_ten_per_cent(err, word, text):
    """The users' row: the laboratory calibration where a level has one, else its only one."""
    summary = pd.DataFrame([
        {"level": "analytic", "calibration": "do1", "primary": True, "shots": 25, "median_abs_rel_err": 0.5},
        {"level": "cavity", "calibration": "laboratory", "primary": True, "shots": 25, "median_abs_rel_err": err},
        {"level": "cavity", "calibration": "do1", "primary": True, "shots": 25, "median_abs_rel_err": 0.9},
        {"level": "cavity", "calibration": "laboratory", "primary": False, "shots": 25, "median_abs_rel_err": 0.0}])
    assert C.predicts(_evidence(validation=summary), "cavity") == (word, text, err)
    assert C.predicts(_evidence(validation=summary), "analytic")[0] == "poor"
