"""The verdict table (paper.verdict) on synthetic inputs whose answers are known by construction: which interval holds
the paper's value, which unstated setting brackets it, and the diff's statuses of each."""
import math

import pandas as pd

from penetration.paper import verdict as V


def table(paper=1.07, eq9=1.03, traj=1.04, cav=1.045):
    return pd.DataFrame([{"contrast": "DO/CRH 4.5", "velocity": v, "paper_sim_ratio": paper,
                          "analytic_stated_S_ratio": eq9, "trajectory_ratio": traj, "cavity_ratio": cav}
                         for v in (500.0, 800.0)])


def sensitivity(friction_ratio):
    rows = []
    for v in (500.0, 800.0):
        for variant, zones, do in (("record (100 zones)", 100, 1.045), ("50 zones", 50, 1.2), ("friction 0.1", 100,
                                                                                                 friction_ratio)):
            rows += [{"variant": variant, "zones": zones, "velocity": v, "nose": "double_ogive", "cavity_m": do},
                     {"variant": variant, "zones": zones, "velocity": v, "nose": "crh45", "cavity_m": 1.0}]
    return pd.DataFrame(rows)


def eroding(value=1.10, half=0.05):
    return pd.DataFrame([{"contrast": "DO/CRH 4.5", "velocity_ms": v, "ratio_at_zero_size": value,
                          "interval_low": value - half, "interval_high": value + half, "confidence": 0.95, "meshes": 21}
                         for v in (500.0, 800.0)])


def chaos(value=0.995, u=0.008, holds=True):
    return pd.DataFrame([{"quantity": "DO/CRH 4.5", "velocity_ms": 500.0, "estimate": value, "uncertainty": u,
                          "meshes": 5, "realisations_min": 3, "fit_holds": holds}])


def unstated(change_points, ejection=0.3, resolved=False):
    return pd.DataFrame([{"target": "erosion_free", "scene": s, "baseline": s == "a", "input": i, "setting": mu,
                          "contrast": "DO/CRH 4.5", "velocity_ms": 500.0, "change_points": c, "change_resolved": r}
                         for s, i, mu, c, r in (("a", "friction", 0.0, 0.0, False), ("b", "friction", 0.1, change_points, True),
                                                ("e", "ejection scale", 2.0, ejection, resolved))])


def rows(**kw):
    return V.verdict_rows(table(), sensitivity(kw.get("friction_ratio", 1.08)), eroding(), chaos(),
                          unstated(kw.get("change", 8.0)), {"eq9": "p"})


def pick(frame, model, v=500.0):
    return frame[(frame.model == model) & (frame.velocity_ms == v)].iloc[0]


def test_intervals_and_brackets():
    f = rows()
    assert not pick(f, V.EQ9).paper_within_uncertainty and pick(f, V.EQ9).provenance == "p"
    assert pick(f, V.ERODING).paper_within_uncertainty          # 1.07 in 1.10 +- 0.05
    free = pick(f, V.FREE)
    assert not free.paper_within_uncertainty                      # 1.07 outside 0.995 +- 0.008
    assert free.reached_by == "friction 0.1"                      # 0.995 -> 1.075 brackets 1.07
    assert math.isclose(free.unstated_high, 0.995 + 0.08)
    cav = pick(f, V.CAVITY)                                       # the zone variant is numerics, not an unstated input
    assert "50 zones" not in cav.unstated_inputs and cav.reached_by == "cavity variant friction 0.1"


def test_an_input_that_moves_the_wrong_way_reaches_nothing():
    f = rows(change=-3.0, friction_ratio=1.01)
    assert pick(f, V.FREE).reached_by == "none" and pick(f, V.CAVITY).reached_by == "none"


def test_missing_studies_give_pending_rows_and_undecided_statuses():
    f = V.verdict_rows(table(), sensitivity(1.08), None, None, None, {})
    assert pick(f, V.FREE).uncertainty_basis.startswith("pending") and math.isnan(pick(f, V.FREE).value)
    assert V.FREE not in set(f[f.velocity_ms == 800.0].model)     # the erosion-free scene has 500 and 1200 only
    st = {(r.quantity, r.case.split(" m/s")[0]): r.status for r in V.verdict_diff_rows(f)}
    assert st[(f"verdict: DO/CRH 4.5 ({V.FREE})", "500")] == "undecided"
    assert st[(f"verdict: DO/CRH 4.5 ({V.EQ9})", "500")] == "deviates"     # 4 points off, closed form


def test_diff_statuses_follow_the_interval_and_the_calibration():
    f = V.verdict_rows(table(eq9=1.065, cav=1.075), sensitivity(1.08), eroding(1.07, 0.005), chaos(1.07, 0.05), None, {})
    st = {r.quantity: r.status for r in V.verdict_diff_rows(f) if r.case.startswith("500")}
    assert st[f"verdict: DO/CRH 4.5 ({V.EQ9})"] == "reproduced"                      # within 2 points, nothing fitted
    assert st[f"verdict: DO/CRH 4.5 ({V.CAVITY})"] == "agrees-after-calibration"     # within 2 points, calibrated on DO1
    assert st[f"verdict: DO/CRH 4.5 ({V.ERODING})"] == "agrees-after-calibration"
    assert st[f"verdict: DO/CRH 4.5 ({V.FREE})"] == "undecided"                      # +-5 points holds values beyond 2


def test_a_numerical_control_joins_the_uncertainty_only_when_resolved():
    quiet = pick(rows(), V.FREE)
    assert "ejection" not in quiet.unstated_inputs and math.isclose(quiet.uncertainty, 0.008)
    f = V.verdict_rows(table(), sensitivity(1.08), eroding(), chaos(), unstated(8.0, ejection=-1.5, resolved=True), {})
    loud = pick(f, V.FREE)
    assert math.isclose(loud.uncertainty, math.hypot(0.008, 0.015)) and "ejection scale 2" in loud.uncertainty_basis


def test_nothing_reaches_what_is_already_inside_and_a_line_that_fails_is_undecided(tmp_path):
    f = V.verdict_rows(table(paper=1.0), sensitivity(1.08), eroding(), chaos(0.995, 0.008), unstated(-5.0), {})
    assert pick(f, V.FREE).paper_within_uncertainty and pick(f, V.FREE).reached_by == ""
    # the table read back from its CSV (booleans as text) and a study whose line does not hold the means
    bad = V.verdict_rows(table(), sensitivity(1.08), eroding(), chaos(1.07, 0.001, holds="False"), None, {})
    path = tmp_path / "verdict.csv"
    bad.to_csv(path, index=False)
    back = pd.read_csv(path)
    st = {r.quantity: r.status for r in V.verdict_diff_rows(back) if r.case.startswith("500")}
    assert st[f"verdict: DO/CRH 4.5 ({V.FREE})"] == "undecided"          # 1.07 +- 0.001 would be reproduced, but no limit
    assert st[f"verdict: DO/CRH 4.5 ({V.EQ9})"] == "deviates"


def test_the_docs_blocks_read_a_partial_study(tmp_path):
    from penetration.pipeline import docs
    f = V.verdict_rows(table(), sensitivity(1.08), eroding(), None, None, {})
    files = {"figures/verdict.csv": f.to_csv(index=False),
             "workflow/config.yaml": "fe_realisations: {velocities: [500.0, 1200.0]}\n",
             "figures/fe/erosion_free/chaos_v500.csv": "quantity,kind,velocity_ms,status,estimate\n"
                                                      "DO/CRH 4.5,contrast,500,fewer than 3 meshes with a mean,\n"}
    read = lambda p: files[p] if p in files else (_ for _ in ()).throw(FileNotFoundError(p))  # noqa: E731
    text = docs.verdict(read)
    assert "pending" in text and "Eq 9 (stated S)" in text
    block = docs.erosion_free_chaos(read)
    assert "fewer than 3 meshes with a mean" in block and "chaos_v1200.csv" in block
