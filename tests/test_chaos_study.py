"""The grid study with the chaos in its error model (studies.chaos) on synthetic realisations whose depths follow an
exact law plus a known scatter: the study must recover the law's limit within its stated uncertainty, the scatter
as the cells' spread, and refuse a mesh effect it cannot resolve (independent oracles: the law and the scatter)."""
import math

import numpy as np
import pandas as pd
import pytest

from penetration.studies import chaos

ACROSS = {"m1": 8.192, "m2": 10.24, "m3": 12.8, "m4": 16.0, "m5": 20.0}
LIMIT = {"double_ogive": 3.3, "crh45": 3.2, "crh3": 3.0}
GOALS = {"500": 0.02, "1200": 0.01}


def pieces(slope=0.0, sd=0.003, members=3, seed=1, velocities=(500.0, 1200.0)):
    """Pieces whose depth is LIMIT (1 + slope h) (1 + sd e), e standard normal, member by member."""
    rng = np.random.default_rng(seed)
    out = []
    for prof, n in ACROSS.items():
        h = 0.07 / n
        for v in velocities:
            for k in range(members):
                shots = [{"scene": "s", "profile": prof, "element_size": h, "nose": nose, "velocity": v,
                          "depth_m": d * v / 500 * (1 + slope * h) * (1 + sd * rng.standard_normal()),
                          "status": "rest", "wall_time_s": n ** 3 * v / 500, "ejected_mass_kg": 40.0,
                          "crater_debris_mass_kg": 0.0, "wall_debris_mass_kg": 0.0, "velocity_factor": 1 + k * 1e-9}
                         for nose, d in LIMIT.items()]
                out.append({"piece": f"{prof}/s/v{v:g}_m{k}", "member": k, "shots": shots})
    return out


def study(**kw):
    shots = chaos.shot_rows(pieces(**kw), ACROSS)
    cells = chaos.cell_rows(shots, ("scene", "profile", "elements_across", "element_size_m", "velocity_ms"))
    rows = chaos.chaos_rows(cells, {}, GOALS, 2.0, shots[["elements_across", "wall_time_s", "velocity_ms"]], 3)
    return shots, cells, rows


def test_weighted_line_matches_numpy_and_recovers_an_exact_line():
    h = np.array([0.008, 0.006, 0.005, 0.004])
    f = 1.02 + 3.0 * h
    se = np.array([0.01, 0.02, 0.01, 0.03])
    f0, se0, a, sea, chi2, dof = chaos.weighted_line(h, f, se)
    assert f0 == pytest.approx(1.02, abs=1e-12) and a == pytest.approx(3.0, rel=1e-9) and chi2 < 1e-20 and dof == 2
    g = f + np.array([0.01, -0.02, 0.005, 0.0])
    b = np.polyfit(h, g, 1, w=1 / se)   # numpy's weights multiply the residuals (1/sigma)
    assert chaos.weighted_line(h, g, se)[0] == pytest.approx(b[1], rel=1e-10)


def test_cells_hold_the_scatter_and_contrasts_propagate_it():
    shots, cells, _ = study(sd=0.004, members=40)
    d = cells[cells.kind == "depth"]
    # 40 realisations: the sample s.d. of a normal scatter is within ~3 x its standard error (sd / sqrt(2 (n - 1)))
    assert np.all(np.abs(d.sd_pct / 100 / 0.004 - 1) < 3 / math.sqrt(78))
    c = cells[(cells.kind == "contrast") & (cells.quantity == "DO/CRH 4.5")]
    assert np.allclose(c["mean"], 3.3 / 3.2, atol=4 * c.se.max())
    assert np.allclose(c.sd, 3.3 / 3.2 * math.sqrt(2) * 0.004, rtol=0.35)


def test_flat_sequence_covers_the_limit_at_its_stated_confidence():
    """Over many synthetic studies with a flat law, the contrasts' limits lie within +-U about 95 % of the time
    (Student's t on the pooled chaos): the interval is neither far too narrow nor a blanket."""
    exact = {"DO/CRH 4.5": 3.3 / 3.2, "CRH 4.5/CRH 3": 3.2 / 3.0, "DO/CRH 3": 3.3 / 3.0}
    inside, widths, scaled = [], [], []
    for seed in range(40):
        _, _, rows = study(sd=0.003, seed=seed, velocities=(1200.0,))
        con = rows[rows.kind == "contrast"]
        inside += [abs(r.estimate - exact[r.quantity]) <= r.uncertainty for _, r in con.iterrows()]
        scaled += [abs(r.estimate - exact[r.quantity]) / r.uncertainty for _, r in con.iterrows()]
        widths += list(con.uncertainty)
    coverage = np.mean(inside)
    assert coverage >= 0.85, coverage
    # the error's median is about t(0.75)/t(0.975) of U for a 95 % Student-t interval: 0.34 with many degrees of
    # freedom, 0.27 with 4; an interval several times too wide (a blanket) would put it near 0.1, one too narrow
    # above 0.5
    assert 0.2 < np.median(scaled) < 0.5, np.median(scaled)
    # 3 realisations of 0.3 % on 5 meshes: the zero-size value of a contrast known to about a point, not ten
    assert 0.002 < np.median(widths) < 0.015


def test_a_resolved_first_order_mesh_effect_is_extrapolated():
    _, _, rows = study(slope=4.0, sd=0.0005)   # 4 % per cm on DO only
    # all noses share the slope: contrasts flat, depths slope; the depth's zero-size value is the law's
    d = rows[(rows.kind == "depth") & (rows.quantity == "crh3") & (rows.velocity_ms == 500.0)].iloc[0]
    assert d.slope_resolved and d.fit_holds
    assert abs(d.estimate - 3.0) <= d.uncertainty < 0.01 * 3.0


def test_scatter_beyond_the_chaos_is_no_limit_and_names_the_next_mesh():
    p = pieces(sd=0.0005)
    # one mesh's DO realisations all moved by 3 %: a jump the chaos cannot explain
    for piece in p:
        for s in piece["shots"]:
            if s["profile"] == "m3" and s["nose"] == "double_ogive":
                s["depth_m"] *= 1.03
    shots = chaos.shot_rows(p, ACROSS)
    cells = chaos.cell_rows(shots, ("scene", "profile", "elements_across", "element_size_m", "velocity_ms"))
    rows = chaos.chaos_rows(cells, {}, GOALS, 2.0, shots[["elements_across", "wall_time_s", "velocity_ms"]], 3)
    r = rows[(rows.quantity == "DO/CRH 4.5") & (rows.velocity_ms == 1200.0)].iloc[0]
    assert not r.fit_holds and not r.within_goal and r.status.startswith("no limit")
    assert r.next_elements_across == pytest.approx(25.0)
    # wall time grows as n^3 in the synthetic shots: the next mesh costs 1.25^3 of the finest's
    assert r.cost_exponent == pytest.approx(3.0, rel=1e-9)
    assert r.next_wall_time_per_shot_s == pytest.approx(20.0 ** 3 * 1200 / 500 * 1.25 ** 3, rel=1e-9)
    # one shot paused for an hour (its wall time 30 times the others') moves no mesh's median, so not the cost
    slow = shots[["elements_across", "wall_time_s", "velocity_ms"]].copy()
    slow.loc[slow.index[slow.elements_across == slow.elements_across.max()][0], "wall_time_s"] *= 30.0
    again = chaos.chaos_rows(cells, {}, GOALS, 2.0, slow, 3)
    assert again.next_wall_time_per_shot_s.to_list() == pytest.approx(rows.next_wall_time_per_shot_s.to_list(), rel=1e-9,
                                                                       nan_ok=True)


def test_a_realisation_given_twice_is_refused():
    p = pieces()
    with pytest.raises(ValueError, match="given twice"):
        chaos.shot_rows(p + p[:1], ACROSS)


def test_unstated_rows_measure_a_change_against_the_baseline():
    base = chaos.shot_rows(pieces(sd=0.002, members=4, seed=3))
    other = chaos.shot_rows(pieces(sd=0.002, members=4, seed=4)).assign(scene="t")
    other.loc[other.nose == "double_ogive", "depth_m"] *= 1.05
    cells = chaos.cell_rows(pd.concat([base, other]), ("scene", "profile", "element_size_m", "velocity_ms"))
    rows = chaos.unstated_rows(cells, {"x": "s"}, {"s": ("x", "friction", 0.0), "t": ("x", "friction", 0.1)}, {})
    t = rows[(rows.scene == "t") & (rows.contrast == "DO/CRH 4.5")]
    assert np.allclose(t.change_points, 5.0 * 3.3 / 3.2, atol=1.0) and t.change_resolved.all()
    s = rows[rows.scene == "s"]
    assert (s.change_points == 0).all() and not s.change_resolved.any()


def _rows_of(p, goals=GOALS):
    shots = chaos.shot_rows(p, ACROSS)
    cells = chaos.cell_rows(shots, ("scene", "profile", "elements_across", "element_size_m", "velocity_ms"))
    return chaos.chaos_rows(cells, {}, goals, 2.0, shots[["elements_across", "wall_time_s", "velocity_ms"]], 3)


def test_resolved_steps_give_richardson_and_unresolved_ones_do_not():
    # depths LIMIT (1 + 4 h): every step far beyond a 0.02 % chaos; the finest triple is first order and monotone,
    # so Richardson's value is the law's limit and the line agrees with it
    r = study(slope=4.0, sd=0.0002)[2]
    d = r[(r.quantity == "crh3") & (r.velocity_ms == 500.0)].iloc[0]
    assert d.refinement == "asymptotic" and d.order == pytest.approx(1.0, abs=0.2)
    assert d.richardson == pytest.approx(3.0, rel=2e-3) and d.uncertainty_order < 0.005
    flat = study(sd=0.003)[2]
    assert (flat.refinement == "steps within noise").mean() > 0.8 and flat.richardson.isna().mean() > 0.8


def test_a_mesh_with_one_realisation_keeps_its_mean_and_the_pool_comes_from_the_others():
    p = [q for q in pieces(sd=0.003) if not (q["piece"].startswith("m5/") and q["member"] > 0)]
    r = _rows_of(p)
    c = r[(r.quantity == "DO/CRH 4.5") & (r.velocity_ms == 1200.0)].iloc[0]
    assert c.meshes == 5 and c.realisations_min == 1 and c.sd_pooled_dof == 8   # 4 meshes x (3 - 1)
    assert np.isfinite(c.estimate) and c.element_size_finest_m == pytest.approx(0.07 / 20.0)


def test_identical_realisations_and_too_few_meshes_say_so():
    r = _rows_of(pieces(sd=0.0))
    assert set(r.status) == {"no chaos measured (fewer than two realisations, or identical ones)"}
    assert set(r[r.quantity == "DO/CRH 3"].kind) == {"contrast"}
    few = _rows_of([q for q in pieces() if q["piece"].split("/")[0] in ("m1", "m2")])
    assert set(few.status) == {"fewer than 3 meshes with a mean"}
    with pytest.raises(ValueError, match="goals has no goal for 1200"):
        _rows_of(pieces(), {"500": 0.02})


def test_the_ejected_concrete_is_booked_per_cell_contrast_and_finest_mesh():
    """Each nose's ejected mass per cell is its realisations' mean; a contrast's the mean of its two noses'; the study's
    row the finest mesh's."""
    p = pieces()
    for piece in p:
        for s in piece["shots"]:
            s["ejected_mass_kg"] = {"double_ogive": 30.0, "crh45": 20.0, "crh3": 10.0}[s["nose"]] + piece["member"]
    shots = chaos.shot_rows(p, ACROSS)
    cells = chaos.cell_rows(shots, ("scene", "profile", "elements_across", "element_size_m", "velocity_ms"))
    one = cells[(cells.profile == "m5") & (cells.velocity_ms == 500.0)].set_index("quantity")
    assert one.ejected_mass_kg["double_ogive"] == pytest.approx(31.0) and one.ejected_mass_kg["crh3"] == pytest.approx(11.0)
    assert one.ejected_mass_kg["DO/CRH 3"] == pytest.approx(21.0) and one.ejected_mass_kg["CRH 4.5/CRH 3"] == pytest.approx(16.0)
    rows = chaos.chaos_rows(cells, {}, GOALS, 2.0)
    r = rows[(rows.quantity == "DO/CRH 4.5") & (rows.velocity_ms == 1200.0)].iloc[0]
    assert r.ejected_mass_finest_kg == pytest.approx(26.0) and r.wall_debris_mass_finest_kg == 0.0
