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
    assert peaks.value.notna().all() and (peaks.value < 0).all() == (peaks.verdict.str.startswith("holds")).all()
    assert json.dumps(list(rows.level.unique())) == json.dumps([*LEVELS, "erosion_free"])


@pytest.mark.parametrize("profile", ["full", "ci"])
def test_the_committed_claims_are_those_of_the_committed_outputs(profile):
    """figures/fe/{profile}/claims.csv is what paper.claims makes of the outputs committed beside it."""
    made = pd.DataFrame(C.claim_rows(_committed_evidence(profile)), columns=C.COLUMNS)
    committed = pd.read_csv(ROOT / f"figures/fe/{profile}/claims.csv")
    pd.testing.assert_frame_equal(made, committed, check_exact=False, rtol=1e-11)
