"""The erosion-free target's grid-convergence study on synthetic shots whose depths follow an exact error law:
the study must recover each limit, order and the goals' verdicts (an independent oracle: the law itself)."""
import numpy as np
import pytest

from penetration.studies import grid as grid_study
from penetration.studies.mesh_convergence import MONOTONE

ACROSS = {"m1": 8.192, "m2": 10.24, "m3": 12.8, "m4": 16.0}
HOLES = (0.5, 0.25, 0.125)
LIMIT = {"double_ogive": 3.3, "crh45": 3.1, "crh3": 3.0}


def depth(nose, v, n, hole, p=2.0, c=-30.0, q=2.0, k=1.5):
    h = 0.07 / n
    return LIMIT[nose] * v / 500.0 + c * h ** p + k * hole ** q


def shots(**law):
    out = []
    for hole in HOLES:
        for prof, n in ACROSS.items():
            for nose in LIMIT:
                for v in (500.0, 1200.0):
                    out.append({"profile": prof, "element_size": 0.07 / n, "nose": nose, "velocity": v,
                                "target": {"formulation": "erosion_free", "pilot_hole": hole},
                                "depth_m": depth(nose, v, n, hole, **law), "wall_time_s": n ** 3, "steps": 1000 * n,
                                "elements": 100 * n * n, "energy_error_max": 1e-4, "eroded_mass_kg": 0.0,
                                "ejected_mass_kg": 1.0, "crater_debris_mass_kg": 0.0, "remap_energy_j": 0.0,
                                "status": "rest"})
    return out


def test_the_study_recovers_the_limits_orders_and_goals_of_an_exact_error_law():
    s = grid_study.shot_rows(shots(), ACROSS)
    paper = {(v, n): 1.05 * LIMIT[n] * v / 500.0 for n in LIMIT for v in (500.0, 1200.0)}
    conv = grid_study.convergence_rows(s, paper, 0.01, 0.01)
    d = conv[conv.quantity == "depth_m"]
    assert len(d) == 3 * 6 and (d.status == MONOTONE).all()
    np.testing.assert_allclose(d.observed_order, 2.0, rtol=1e-6)
    for r in d.itertuples():
        assert r.extrapolated == pytest.approx(LIMIT[r.case] * r.velocity_ms / 500.0 + 1.5 * r.pilot_hole ** 2, rel=1e-10)
        # the least-squares uncertainty on all four meshes: the same limit, U the GCI of the finest
        assert r.ls_fit == "p free" and r.ls_order == pytest.approx(2.0, rel=1e-6)
        assert r.ls_exact == pytest.approx(r.extrapolated, rel=1e-9) and r.ls_value == r.value_at_16_across
        assert r.ls_uncertainty == pytest.approx(1.25 * abs(r.ls_value - r.ls_exact), rel=1e-6)
    holes = grid_study.hole_rows(conv, 0.01, 0.01)
    dd = holes[holes.quantity == "depth_m"]
    np.testing.assert_allclose(dd.hole_order, 2.0, rtol=1e-6)
    for r in dd.itertuples():
        assert r.at_zero_hole == pytest.approx(LIMIT[r.case] * r.velocity_ms / 500.0, rel=1e-10)
        assert not r.paper_inside   # the paper's values are 5 % off the limits here
    ratio = holes[(holes.quantity == "depth_ratio") & (holes.case == "DO/CRH 4.5")]
    assert len(ratio) == 2 and all(abs(r.at_zero_hole - 3.3 / 3.1) < 5e-3 for r in ratio.itertuples())
    # the ranking on the limits: DO (3.3) deeper than CRH 4.5 (3.1) than CRH 3 (3.0), by more than the bands
    ratios = holes[holes.quantity == "depth_ratio"]
    assert (ratios.ranking == "holds").all() and (ratios.side_of_1 == "above 1 on every mesh and hole").all()
    # the least-squares hull over the holes: each hole's finest value +- U, here U = 1.25 x its error, above 1
    for r in ratios.itertuples():
        g = conv[(conv.case == r.case) & (conv.velocity_ms == r.velocity_ms)]
        assert r.ls_holes == 3 and r.ls_low == pytest.approx((g.ls_value - g.ls_uncertainty).min(), rel=1e-12)
        assert r.ls_high == pytest.approx((g.ls_value + g.ls_uncertainty).max(), rel=1e-12)
        assert r.ls_ranking == "holds at every hole" and r.ls_low > 1
    assert (holes[holes.quantity == "depth_m"].ranking == "").all()
    cost = grid_study.cost_rows(s)
    assert list(cost.elements_across) == sorted(ACROSS.values()) and (cost.shots == 18).all()
    assert (cost.formulation == "erosion_free").all()
    assert list(cost.wall_time_mean_s) == pytest.approx([n ** 3 for n in sorted(ACROSS.values())], rel=1e-12)
    # the eroding level's same six shots at one mesh: a row of their own; a missing shot is refused
    eroding = [{"profile": "full", "element_size": 0.00875, "nose": nose, "velocity": v, "wall_time_s": 10.0 + v / 100,
                "steps": 1, "elements": 1} for nose in LIMIT for v in (500.0, 1200.0)]
    both = grid_study.cost_rows(s, eroding, 8)
    row = both[both.formulation == "eroding"].iloc[0]
    assert len(both) == len(cost) + 1 and row.elements_across == 8 and row.shots == 6
    assert row.wall_time_mean_s == pytest.approx(10.0 + 8.5, rel=1e-12)
    with pytest.raises(ValueError, match="missing"):
        grid_study.cost_rows(s, eroding[1:], 8)


def test_the_goals_fail_when_the_fine_mesh_is_too_far_from_the_limit():
    s = grid_study.shot_rows(shots(c=-3000.0), ACROSS)   # a large mesh error: GCI about 1-2 %
    conv = grid_study.convergence_rows(s, {}, 0.01, 0.01)
    d = conv[conv.quantity == "depth_m"]
    assert (d.status == MONOTONE).all()
    assert list(d.goal_met) == list(d.gci_fine_relative <= 0.01)
    assert 0 < d.goal_met.sum() < len(d)


def test_the_study_refuses_meshes_not_refined_by_one_ratio_and_another_formulation():
    with pytest.raises(ValueError, match="constant ratio"):
        grid_study.refinement_ratio([8.0, 10.0, 13.0])
    bad = shots()
    bad[0]["target"] = {"formulation": "eroding", "pilot_hole": 0.25}
    with pytest.raises(ValueError, match="erosion_free"):
        grid_study.shot_rows(bad, ACROSS)
    with pytest.raises(ValueError, match="profile"):
        grid_study.shot_rows(shots(), {"m1": 8.192})
    # one shot with the moving window among whole-domain shots: the meshes would not compare
    mixed = [{**s, "domain": "whole"} for s in shots()]
    assert set(grid_study.shot_rows(mixed, ACROSS).domain) == {"whole"}
    mixed[3] = {**mixed[3], "domain": "window"}
    with pytest.raises(ValueError, match=r"domains \['whole', 'window'\]; allowed: one"):
        grid_study.shot_rows(mixed, ACROSS)


def test_a_record_from_before_the_wall_debris_rule_reads_as_none_and_a_later_one_keeps_its_value():
    """shot_rows: a shot's record without wall_debris_mass_kg (run before the rule, when such a loss stopped the run)
    reads as 0 kg; a record with it keeps its value; every other column of the record is required."""
    data = shots()
    data[0]["wall_debris_mass_kg"] = 0.002
    s = grid_study.shot_rows(data, ACROSS)
    first = ((s.profile == data[0]["profile"]) & (s.nose == data[0]["nose"]) & (s.velocity_ms == data[0]["velocity"])
             & (s.pilot_hole == data[0]["target"]["pilot_hole"]))
    assert first.sum() == 1 and (s.wall_debris_mass_kg[first] == 0.002).all() and (s.wall_debris_mass_kg[~first] == 0.0).all()
    del data[1]["crater_debris_mass_kg"]
    with pytest.raises(KeyError, match="crater_debris_mass_kg"):
        grid_study.shot_rows(data, ACROSS)


def test_a_stopped_shot_ends_its_sequences_there_and_meets_no_goal():
    """A shot that stopped (no depth) at the finest mesh: its depth and the contrasts it enters are refined on the
    three coarser meshes (status stopped, their order and limit), the other noses' as before; stopped at the
    second mesh, nothing is refined and the zero-hole value is not extrapolated."""
    from penetration.studies.grid import STOPPED
    finest = max(ACROSS.values())
    data = shots()
    for s in data:
        if (s["nose"], s["velocity"], s["target"]["pilot_hole"], ACROSS[s["profile"]]) == ("crh3", 500.0, HOLES[0], finest):
            s.update(depth_m=float("nan"), status="stopped", diagnostic="element 1 lost its shape")
    s = grid_study.shot_rows(data, ACROSS)
    assert (s.diagnostic != "").sum() == 1
    conv = grid_study.convergence_rows(s, {}, 0.01, 0.01)
    at = conv[(conv.pilot_hole == HOLES[0]) & (conv.velocity_ms == 500.0)].set_index("case")
    assert at.loc["crh3", "status"] == STOPPED and at.loc["crh3", "meshes_refined"] == 3 and not at.loc["crh3", "goal_met"]
    assert at.loc["crh3", "observed_order"] == pytest.approx(2.0, rel=1e-6)   # the exact law on the coarser three
    assert at.loc["crh3", "extrapolated"] == pytest.approx(LIMIT["crh3"] + 1.5 * HOLES[0] ** 2, rel=1e-9)
    assert at.loc["CRH 4.5/CRH 3", "status"] == STOPPED and at.loc["DO/CRH 4.5", "status"] == MONOTONE
    # three meshes ran: too few for the least-squares uncertainty, which the complete sequences have
    assert at.loc["crh3", "ls_fit"] == "" and np.isnan(at.loc["crh3", "ls_uncertainty"])
    assert at.loc["DO/CRH 4.5", "ls_fit"] != "" and np.isfinite(at.loc["DO/CRH 4.5", "ls_uncertainty"])
    holes = grid_study.hole_rows(conv, 0.01, 0.01).set_index(["case", "velocity_ms"])
    assert holes.loc[("crh3", 500.0), "meshes_stopped"] and not holes.loc[("crh3", 500.0), "goal_met"]
    # a hole without a least-squares interval (three meshes ran): no hull, the ranking on it undecided
    assert holes.loc[("crh3", 500.0), "ls_holes"] == 2 and np.isnan(holes.loc[("crh3", 500.0), "ls_low"])
    assert holes.loc[("CRH 4.5/CRH 3", 500.0), "ls_ranking"] == "undecided"
    assert holes.loc[("DO/CRH 4.5", 500.0), "ls_ranking"] == "holds at every hole"
    assert not holes.loc[("crh3", 1200.0), "meshes_stopped"]
    # stopped on the second mesh: fewer than three meshes before it
    second = sorted(ACROSS.values())[1]
    for s_ in data:
        if (s_["nose"], s_["velocity"], s_["target"]["pilot_hole"], ACROSS[s_["profile"]]) == ("crh3", 500.0, HOLES[0], second):
            s_.update(depth_m=float("nan"), status="stopped")
    conv = grid_study.convergence_rows(grid_study.shot_rows(data, ACROSS), {}, 0.01, 0.01)
    row = conv[(conv.pilot_hole == HOLES[0]) & (conv.velocity_ms == 500.0) & (conv.case == "crh3")].iloc[0]
    assert row.meshes_refined == 0 and np.isnan(row.extrapolated) and row.status == STOPPED
    h = grid_study.hole_rows(conv, 0.01, 0.01).set_index(["case", "velocity_ms"]).loc[("crh3", 500.0)]
    assert h.hole_status == STOPPED and np.isnan(h.at_zero_hole) and not h.goal_met


def test_without_a_limit_the_hole_rows_give_the_range_of_every_value():
    """Depths scattered about the law by +-2 % (no order, no limit): the zero-hole row finds no limit and gives the
    range and median of every mesh's and hole's value instead."""
    rng = np.random.default_rng(3)
    data = shots()
    for s in data:
        s["depth_m"] *= 1 + 0.02 * rng.uniform(-1, 1)
    paper = {(v, n): LIMIT[n] * v / 500.0 for n in LIMIT for v in (500.0, 1200.0)}   # the law's own limits
    conv = grid_study.convergence_rows(grid_study.shot_rows(data, ACROSS), paper, 0.01, 0.01)
    holes = grid_study.hole_rows(conv, 0.01, 0.01)
    for r in holes.itertuples():
        g = conv[(conv.quantity == r.quantity) & (conv.case == r.case) & (conv.velocity_ms == r.velocity_ms)]
        vals = g[[c for c in g.columns if c.startswith("value_at_")]].to_numpy().ravel()
        assert r.values == 12 and r.values_min == vals.min() and r.values_max == vals.max()
        assert r.values_median == pytest.approx(np.median(vals), rel=1e-15)
    assert not holes.limit_found.all()          # the scatter defeats the refinement somewhere
    ratios = holes[holes.quantity == "depth_ratio"]
    # a ranking is a side of 1 that the whole zero-hole interval lies on; without a limit there is none
    for r in ratios.itertuples():
        low, high = r.at_zero_hole - r.uncertainty, r.at_zero_hole + r.uncertainty
        expected = (("holds" if low > 1 else "fails" if high < 1 else "undecided") if r.limit_found else "undecided")
        assert r.ranking == expected, r
    # the least-squares ranking from each hole's own interval (the convergence rows, not the hull): above 1 at every
    # hole, below at every hole, or undecided
    for r in ratios.itertuples():
        g = conv[(conv.quantity == r.quantity) & (conv.case == r.case) & (conv.velocity_ms == r.velocity_ms)]
        lows, highs = g.ls_value - g.ls_uncertainty, g.ls_value + g.ls_uncertainty
        expected = ("holds at every hole" if (lows > 1).all() else "fails at every hole" if (highs < 1).all()
                    else "undecided")
        assert r.ls_ranking == expected, r
    assert (ratios.ls_high - ratios.ls_low > ratios.values_max - ratios.values_min).all()
    # an infinite band holds no paper value, though the paper's (the law's limits here) lie within it
    inf_band = holes[np.isinf(holes.uncertainty) & np.isfinite(holes.at_zero_hole)]
    assert len(inf_band) > 0 and not inf_band.paper_inside.any()
    clean = grid_study.hole_rows(grid_study.convergence_rows(grid_study.shot_rows(shots(), ACROSS), {}, 0.01, 0.01),
                                 0.01, 0.01)
    assert clean.limit_found.all()


def test_ranking_and_side_of_one_on_their_edges():
    assert grid_study.ranking(1.05, 0.04) == "holds" and grid_study.ranking(0.95, 0.04) == "fails"
    assert grid_study.ranking(1.05, 0.05) == "undecided" and grid_study.ranking(1.0, 0.0) == "undecided"
    assert grid_study.side_of_one(1.001, 1.2) == "above 1 on every mesh and hole"
    assert grid_study.side_of_one(0.8, 0.999) == "below 1 on every mesh and hole"
    assert grid_study.side_of_one(0.99, 1.01) == "on both sides of 1" and grid_study.side_of_one(1.0, 1.1) == "reaching 1"
