"""The FE level's result tables and studies (penetration.studies.fe_results) against hand-computed values and tabulated
quantiles: intervals, goal flags at their edges, Table 3 ratios, band and ensemble means, the rear-face chain."""
import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from penetration.studies import fe_results as S

# Student's t quantiles from a printed table (two-sided 95 %: 97.5 % quantile; 90 %: 95 %)
T975 = {2: 4.302652729749464, 3: 3.182446305284263, 4: 2.776445105197799}
T95 = {3: 2.353363434801823}
PAPER = {"double_ogive": 2.454, "crh45": 2.255, "crh3": 2.174}


@pytest.mark.parametrize("x, confidence, quantile", [([1.0, 1.1, 1.2], 0.95, T975[2]),
                                                     ([2.0, 2.2, 2.4, 2.2], 0.95, T975[3]),
                                                     ([5.0, 5.3, 5.1, 4.8], 0.90, T95[3])])
def test_t_interval_is_the_mean_plus_minus_t_times_the_standard_error(x, confidence, quantile):
    n = len(x)
    mean = sum(x) / n
    sd = math.sqrt(sum((v - mean) ** 2 for v in x) / (n - 1))
    half = quantile * sd / math.sqrt(n)
    lo, hi = S.t_interval(np.array(x), confidence)
    assert lo == pytest.approx(mean - half, rel=1e-12) and hi == pytest.approx(mean + half, rel=1e-12)
    assert (lo, hi) == pytest.approx(stats.t.interval(confidence, n - 1, loc=mean, scale=sd / math.sqrt(n)), rel=1e-12)


def test_welch_interval_against_the_welch_satterthwaite_degrees_of_freedom():
    x, y = [5.0, 5.1, 5.2], [5.2, 5.5, 6.5, 5.9]
    mx, my = sum(x) / 3, sum(y) / 4
    vx = sum((v - mx) ** 2 for v in x) / 2 / 3
    vy = sum((v - my) ** 2 for v in y) / 3 / 4
    nu = (vx + vy) ** 2 / (vx ** 2 / 2 + vy ** 2 / 3)
    half = stats.t.ppf(0.975, nu) * math.sqrt(vx + vy)
    d, lo, hi = S.welch(x, y, 0.95)
    assert d == pytest.approx(my - mx, rel=1e-12)  # the second sample minus the first
    assert (lo, hi) == pytest.approx((my - mx - half, my - mx + half), rel=1e-10)


@pytest.mark.parametrize("sign", [1, -1])
def test_goal_flags_at_their_edges(sign):
    assert S.depth_within_goal(2.0 * (1 + sign * (0.05 - 1e-9)), 2.0)
    assert not S.depth_within_goal(2.0 * (1 + sign * (0.05 + 1e-9)), 2.0)
    assert S.contrast_within_goal(1.1 + sign * (0.02 - 1e-9), 1.1)
    assert not S.contrast_within_goal(1.1 + sign * (0.02 + 1e-9), 1.1)


def _shots(depths, velocities=(500,)):
    """Shot summaries: depths[nose] per velocity (a scalar for one velocity)."""
    rows = []
    for k, v in enumerate(velocities):
        for nose, d in depths.items():
            rows.append({"velocity": float(v), "nose": nose, "depth_m": d[k] if isinstance(d, list) else d,
                         "time_to_rest_s": 0.01, "peak_deceleration_m_s2": 1e5, "eroded_mass_kg": 100.0,
                         "tunnel_eroded_share": 0.5, "energy_error_max": 1e-3, "hourglass_over_internal": 0.01,
                         "element_steps": 10, "failure_strain": 1.0, "element_size": 0.00875})
    return pd.DataFrame(rows)


def test_table3_rows_and_ratios_against_hand_values():
    depth = {"double_ogive": [2.454 * 1.04, 4.0], "crh45": [2.255 * 0.94, 4.0], "crh3": [2.174, 2.0]}
    paper = {(v, n): p * (1 if v == 500 else 2) for v in (500, 800) for n, p in PAPER.items()}
    t = S.table3_rows(_shots(depth, (500, 800)), paper, {"double_ogive"}, 835.0)
    assert list(zip(t.velocity_ms, t.nose))[:3] == [(500, "crh3"), (500, "crh45"), (500, "double_ogive")]
    c = t.set_index(["velocity_ms", "nose"])
    assert c.loc[(500, "double_ogive"), "rel_dev_fe_vs_paper_sim_pct"] == pytest.approx(4.0)
    assert bool(c.loc[(500, "double_ogive"), "within_5pct_goal"]) and not bool(c.loc[(500, "crh45"), "within_5pct_goal"])
    assert list(c.loc[(500, slice(None)), "calibration_nose"]) == [False, False, True]
    assert c.loc[(800, "crh3"), "velocity_minus_calibration_ms"] == -35.0
    r = S.table3_ratios(t).set_index(["velocity_ms", "contrast"])
    assert list(r.loc[500].index) == list(S.CONTRASTS)
    do45 = r.loc[(500, "DO/CRH 4.5")]
    assert do45.fe_ratio == pytest.approx(2.454 * 1.04 / (2.255 * 0.94))
    assert do45.paper_sim_ratio == pytest.approx(2.454 / 2.255)
    assert do45.difference_points == pytest.approx(100 * (2.454 * 1.04 / (2.255 * 0.94) - 2.454 / 2.255))
    assert not bool(do45.within_2_points_goal)                      # 11.1 points over the paper's
    assert r.loc[(800, "CRH 4.5/CRH 3")].fe_ratio == pytest.approx(2.0)
    assert r.loc[(800, "DO/CRH 3")].fe_gain_m == pytest.approx(2.0)


def test_sweep_contrasts_and_the_papers():
    shots = _shots({"double_ogive": [3.0, 6.0], "crh45": [2.5, 5.0], "crh3": [2.0, 4.0], "minimum_nstar": [3.3, 6.0]},
                   (500, 800))
    t = S.sweep_contrasts(shots).set_index(["contrast", "velocity"])
    assert t.loc[("minimum N*/DO", 500.0), "ratio"] == pytest.approx(1.1)
    assert t.loc[("DO/CRH 3", 800.0), "gain_m"] == pytest.approx(2.0)
    p = S.paper_sweep_contrasts({(500, n): d for n, d in PAPER.items()})
    assert list(p.contrast) == ["DO/CRH 4.5", "DO/CRH 3", "CRH 4.5/CRH 3"]   # no paper value for the minimum-N* nose
    assert p.set_index("contrast").loc["CRH 4.5/CRH 3", "ratio"] == pytest.approx(2.255 / 2.174)


def _mesh(across, fs, depth, v=500):
    """(calibration, Table 3, contrasts) of one mesh at one velocity: depth[nose]."""
    h = 0.07 / across
    t3 = pd.DataFrame({"velocity_ms": v, "nose": list(depth), "fe_m": list(depth.values()),
                       "paper_sim_m": [PAPER[n] for n in depth], "element_size_m": h})
    ratios = pd.DataFrame([{"velocity_ms": v, "contrast": name, "fe_ratio": depth[a] / depth[b],
                            "paper_sim_ratio": PAPER[a] / PAPER[b]} for name, (a, b) in S.CONTRASTS.items()])
    return {"element_size": h, "elements_across_radius": across, "fs": fs, "residual_m": 0.01}, t3, ratios


def test_band_means_intervals_and_flags_of_a_synthetic_band():
    """Three meshes; DO depths 2.3, 2.4, 2.5 (mean 2.4, sd 0.1): interval 2.4 -+ t(2) 0.1 / sqrt(3); CRH 4.5 and
    CRH 3 equal on every mesh (ratio 1, zero width)."""
    meshes = [_mesh(7.5, 1.0, {"double_ogive": 2.3, "crh45": 2.0, "crh3": 2.0}),
              _mesh(8.0, 1.2, {"double_ogive": 2.4, "crh45": 2.0, "crh3": 2.0}),
              _mesh(8.5, 0.9, {"double_ogive": 2.5, "crh45": 2.0, "crh3": 2.0})]
    m, d, t = S.band_tables(meshes, "full", 0.95)
    assert len(m) == 9 and set(m.centre_elements_across) == {7.5}
    do = d.set_index("nose").loc["double_ogive"]
    half = T975[2] * 0.1 / math.sqrt(3)
    assert do.meshes == 3 and do.mean_m == pytest.approx(2.4) and do.std_m == pytest.approx(0.1)
    assert (do.interval_low_m, do.interval_high_m) == pytest.approx((2.4 - half, 2.4 + half))
    assert do.mean_rel_dev_pct == pytest.approx(100 * (2.4 / 2.454 - 1)) and bool(do.within_5pct_goal)
    assert bool(do.paper_inside_interval)                            # 2.454 within 2.4 +- 0.248
    c = t.set_index("contrast")
    assert c.loc["DO/CRH 4.5", "mean_ratio"] == pytest.approx(1.2)
    assert c.loc["CRH 4.5/CRH 3", "std_ratio"] == 0.0 and not bool(c.loc["CRH 4.5/CRH 3", "paper_inside_interval"])
    assert (c.loc["DO/CRH 3", "failure_strain_min"], c.loc["DO/CRH 3", "failure_strain_max"]) == (0.9, 1.2)
    with pytest.raises(ValueError, match="at least 2"):
        S.band_tables(meshes[:1], "full", 0.95)
    with pytest.raises(ValueError, match="bands"):
        S.bands_tables(meshes, [("full", 2)], 0.95)


def test_a_table_of_another_mesh_is_refused():
    cal, t3, _ = _mesh(8.0, 1.0, {"double_ogive": 2.0, "crh45": 2.0, "crh3": 2.0})
    S.check_one_mesh(cal, t3, "t", "c")
    with pytest.raises(ValueError, match="element sizes"):
        S.check_one_mesh(cal, t3.assign(element_size_m=0.007), "t", "c")


def test_convergence_rows_pair_each_contrast_with_its_two_depths():
    rows = S.convergence_rows([_mesh(3.0, 0.7, {"double_ogive": 3.0, "crh45": 2.5, "crh3": 2.0}),
                               _mesh(8.0, 1.0, {"double_ogive": 2.6, "crh45": 2.5, "crh3": 2.0})])
    r = rows[(rows.contrast == "DO/CRH 3") & (rows.elements_across_radius == 3.0)].iloc[0]
    assert (r.depth_num_m, r.depth_den_m, r.fe_ratio) == pytest.approx((3.0, 2.0, 1.5))
    assert list(rows.contrast.unique()) == sorted(S.CONTRASTS)


def test_ensemble_pairs_members_of_equal_number():
    """DO 2.0, 2.2, 2.4 over CRH 4.5 2.0, 2.0, 2.0: ratios 1.0, 1.1, 1.2; a member absent from one nose is left out
    of its contrasts."""
    shots = [{"nose": n, "velocity": 500.0, "depth_m": d, "element_size": 0.00875, **({"member": k} if k else {})}
             for n, ds in {"double_ogive": [2.0, 2.2, 2.4], "crh45": [2.0] * 3, "crh3": [2.0, 2.0]}.items()
             for k, d in enumerate(ds)]
    paper = {(n, 500): p for n, p in PAPER.items()}
    paper_ratio = {(name, 500): PAPER[a] / PAPER[b] for name, (a, b) in S.CONTRASTS.items()}
    d, t, members = S.ensemble_tables(shots, paper, paper_ratio, 0.95)
    c = t.set_index("contrast")
    assert c.loc["DO/CRH 4.5", "mean_ratio"] == pytest.approx(1.1) and c.loc["DO/CRH 4.5", "std_ratio"] == pytest.approx(0.1)
    half = T975[2] * 0.1 / math.sqrt(3)
    assert c.loc["DO/CRH 4.5", "interval_high"] == pytest.approx(1.1 + half)
    assert c.loc["DO/CRH 3", "realisations"] == 2 and c.loc["DO/CRH 3", "mean_ratio"] == pytest.approx(1.05)
    assert list(members[members.contrast == "DO/CRH 4.5"].ratio) == pytest.approx([1.0, 1.1, 1.2])
    assert d.set_index("nose").loc["double_ogive", "rel_std_pct"] == pytest.approx(100 * 0.2 / 2.2)
    with pytest.raises(ValueError, match="one mesh"):
        S.ensemble_tables([*shots[:-1], {**shots[-1], "element_size": 0.007}], paper, paper_ratio, 0.95)


def test_mesh_study_takes_the_run_nearest_the_measured_depth():
    def cal(h, depths):
        return {"element_size": h, "elements_across_radius": 0.07 / h, "fs": 1.0, "residual_m": 0.0, "wall_time_s": 9.0,
                "converged": True, "data": {"measured_depth": 5.1},
                "runs": [{"depth_m": d, "wall_time_s": 10 * d} for d in depths]}
    t = S.mesh_study_rows([cal(0.00875, [4.0, 5.2, 5.05]), cal(0.0175, [5.1])])
    assert list(t.element_size_m) == [0.0175, 0.00875]                  # coarsest first
    assert t.iloc[1].depth_m == 5.05 and t.iloc[1].runs == 3 and math.isnan(t.iloc[1].peak_deceleration_m_s2)


def _target(scene, depth, radius=1.2, bottom="non_reflecting", lateral="non_reflecting", kind="semi_infinite"):
    return {"scene": scene, "target_kind": kind, "radius_m": radius, "bottom_depth_m": depth, "lateral": lateral,
            "bottom": bottom, "element_size_m": 0.00875}


def test_rear_face_chain_one_change_a_step_and_welch_effects():
    semi, cut, free = _target("semi", math.nan), _target("cut", 5.4), _target("cut_free", 5.4, bottom="free")
    rows = [{**t, "member": k, "depth_m": d, "status": "rest" if d < 6 else "perforated"}
            for t, ds in ((free, [5.2, 5.5, 6.5]), (semi, [5.0, 5.2, 5.1]), (cut, [5.0, 5.1, 5.2])) for k, d in enumerate(ds)]
    chain = ["semi", "cut", "cut_free"]
    m = S.rear_face_members(pd.DataFrame(rows), chain)
    assert list(m.scene) == ["semi"] * 3 + ["cut"] * 3 + ["cut_free"] * 3
    t = S.rear_face_targets(m, chain, 5.1).set_index("scene")
    assert t.loc["cut_free", "least_distance_to_bottom_m"] == pytest.approx(5.4 - 6.5)
    assert (t.loc["cut_free", "perforated"], t.loc["cut_free", "at_rest"]) == (1, 2)
    assert math.isnan(t.loc["semi", "least_distance_to_bottom_m"])
    assert t.loc["cut_free", "std_m"] == pytest.approx(math.sqrt(0.4633333333333333))   # sample variance, n - 1
    e = S.rear_face_effects(m, chain, 0.95)
    assert list(e.changes) == ["the bottom's depth", "the bottom face", "the bottom's depth + the bottom face"]
    assert list(e.single_change) == [True, True, False]
    assert e.effect_m.iloc[1] == pytest.approx(17.2 / 3 - 5.1)        # to minus from
    with pytest.raises(ValueError, match="one change a step"):
        S.rear_face_effects(m, ["semi", "cut_free", "cut"], 0.95)
    with pytest.raises(ValueError, match="the chain"):
        S.rear_face_members(pd.DataFrame(rows), ["semi", "cut"])


def test_window_summary_is_welchs_difference_relative_to_the_whole_domain():
    w, f = [5.00, 5.02, 5.04], [5.01, 5.03, 5.05, 5.02]
    runs = pd.DataFrame({"domain": ["window"] * 3 + ["whole"] * 4, "depth_m": w + f})
    s = S.window_summary(runs, 0.9, 1.0)
    # Welch by hand: the window's mean minus the whole domain's, +- t(0.95, Welch-Satterthwaite dof) times the
    # standard error of the difference
    from scipy.stats import t as student
    mw, mf = sum(w) / 3, sum(f) / 4
    vw, vf = (sum((x - mw) ** 2 for x in w) / 2 / 3, sum((x - mf) ** 2 for x in f) / 3 / 4)
    dof = (vw + vf) ** 2 / (vw**2 / 2 + vf**2 / 3)
    d, half = mw - mf, student.ppf(0.95, dof) * math.sqrt(vw + vf)
    assert s["difference_pct"] == pytest.approx(100 * d / mf, rel=1e-9)
    assert s["interval_low_pct"] == pytest.approx(100 * (d - half) / mf, rel=1e-9)
    assert s["interval_high_pct"] == pytest.approx(100 * (d + half) / mf, rel=1e-9)
    assert s["within_goal"] and not S.window_summary(runs, 0.9, 0.1)["within_goal"]


def test_do1_test_tables_means_excess_bounds_and_the_block_effect_by_hand():
    semi, block = [3.6, 3.7, 3.65, 3.55], [3.7, 3.9, 3.8]
    rows = [{"target": t, "member": k, "depth_m": d, "status": s}
            for t, ds, s in (("block", block, "rest"), ("semi_infinite", semi, "rest")) for k, d in enumerate(ds)]
    rows[2]["status"] = "perforated"
    rows[1]["status"] = "end_time"
    frame = pd.DataFrame(rows)   # the block's rows first: the reference is the targets' first, not the rows'
    t = S.do1_test_tables(frame, ["semi_infinite", "block"], 5.1, 0.95).set_index("target")
    assert list(t.index) == ["semi_infinite", "block"]
    n, mean = 4, sum(semi) / 4
    sd = math.sqrt(sum((v - mean) ** 2 for v in semi) / (n - 1))
    half = T975[3] * sd / math.sqrt(n)
    r = t.loc["semi_infinite"]
    assert (r.mean_low_m, r.mean_high_m) == pytest.approx((mean - half, mean + half), rel=1e-12)
    # the measured depth's excess over the mean, and over the interval's ends (a deeper end: a smaller excess)
    assert r.excess == pytest.approx(5.1 / mean - 1, rel=1e-12)
    assert (r.excess_low, r.excess_high) == pytest.approx((5.1 / (mean + half) - 1, 5.1 / (mean - half) - 1), rel=1e-12)
    assert math.isnan(r.effect_vs_first_m)
    b = t.loc["block"]
    mb = sum(block) / 3
    vx = sd ** 2 / n
    vy = sum((v - mb) ** 2 for v in block) / 2 / 3
    nu = (vx + vy) ** 2 / (vx ** 2 / (n - 1) + vy ** 2 / 2)
    whalf = stats.t.ppf(0.975, nu) * math.sqrt(vx + vy)
    assert b.effect_vs_first_m == pytest.approx(mb - mean, rel=1e-12)   # the block's mean minus the first target's
    assert (b.effect_low_m, b.effect_high_m) == pytest.approx((mb - mean - whalf, mb - mean + whalf), rel=1e-10)
    assert (b.at_rest, b.perforated, b.moving_at_end, b.realisations) == (1, 1, 1, 3)
    # the other way round: the block is the reference and the semi-infinite target's effect is the negative
    u = S.do1_test_tables(frame, ["block", "semi_infinite"], 5.1, 0.95).set_index("target")
    assert u.loc["semi_infinite", "effect_vs_first_m"] == pytest.approx(mean - mb, rel=1e-12)
    with pytest.raises(ValueError, match=r"do1_test_fe.members: 1 realisation of target semi_infinite; allowed: >= 2"):
        S.do1_test_tables(frame.iloc[:4], ["block", "semi_infinite"], 5.1, 0.95)
    with pytest.raises(ValueError, match=r"do1_test_fe.targets: \['block'\]; allowed: the records' targets"):
        S.do1_test_tables(frame, ["block"], 5.1, 0.95)
