"""Every level for users' shots: the HJC fc scaling rule, the closed form against the integrated trajectory,
the sigma_n cache, the fe level's scaling with the projectile, and the command line."""
import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from penetration.cavity.expansion import Controls as CavityControls, Mesh as CavityMesh
from penetration.concrete import material as concrete
from penetration.concrete.hjc import HJC
from penetration.errors import ParameterError
from penetration.nose.geometry import Ogive
from penetration.shots import ladder as L
from penetration.shots.records import context_from_files, context_from_pipeline

ROOT = Path(__file__).resolve().parents[1]


def cli(*args, cwd=ROOT):
    """The command line, run in this process (conftest.run_cli)."""
    from conftest import run_cli
    return run_cli(*args, cwd=cwd)


# ------------------------------------------------------------------ the HJC fc scaling rule
def table1():
    return context_from_pipeline(ROOT).base


def test_scaling_returns_the_table1_set_exactly_at_48_mpa():
    base = table1()
    assert base.fc == 48e6
    assert concrete.hjc_for_strength(48e6, base) == base
    assert concrete.hjc_for_strength(48e6, base, 2440.0) == base


def youngs(m: HJC):
    K = m.pc / m.muc
    return 9 * K * m.G / (3 * K + m.G), (3 * K - 2 * m.G) / (2 * (3 * K + m.G))


@pytest.mark.parametrize("fc", [25e6, 32.4e6, 101.4e6, 200e6])
def test_scaling_follows_its_published_relations(fc):
    base = table1()
    m = concrete.hjc_for_strength(fc, base, 2300.0)
    # Holmquist, Johnson & Cook (1993): the crush point of the uniaxial compression test, pc = fc/3, mu_c = pc/K
    assert m.pc == pytest.approx(fc / 3, rel=1e-14)
    # fib Model Code 2010 Eq 5.1-21: Eci proportional to fcm^(1/3), at the Poisson ratio of Table 1's set
    (E, nu), (E0, nu0) = youngs(m), youngs(base)
    assert E / E0 == pytest.approx((fc / 48e6) ** (1 / 3), rel=1e-13)
    assert nu == pytest.approx(nu0, rel=1e-13)
    # fib Model Code 2010 Eqs 5.1-3a/b with fck = fcm - 8 MPa: 0.30 fck^(2/3) up to fck 50, 2.12 ln(1 + fcm/10) above
    fctm = lambda fcm: 0.30 * (fcm - 8) ** (2 / 3) if fcm - 8 <= 50 else 2.12 * math.log(1 + fcm / 10)
    assert m.T / base.T == pytest.approx(fctm(fc / 1e6) / fctm(48.0), rel=1e-13)
    assert m.fc == fc and m.rho0 == 2300.0
    for name in concrete.HJC_SCALING_RULE["carried_over"]:
        assert getattr(m, name) == getattr(base, name), name


def test_table1_tension_and_modulus_are_near_the_code_at_48_mpa():
    """A check of the rule's anchor, not an input: Table 1's T and implied E beside the fib Model Code 2010's at
    fcm = 48 MPa (fctm = 0.30 * 40^(2/3) = 3.51 MPa; Eci = 21.5 GPa * 4.8^(1/3) = 36.3 GPa): T 14 % above, E 6 %
    below."""
    base = table1()
    assert base.T / (0.30 * 40 ** (2 / 3) * 1e6) == pytest.approx(1.14, abs=0.01)
    assert youngs(base)[0] / (21.5e9 * 4.8 ** (1 / 3)) == pytest.approx(0.937, abs=0.01)
    # the code's two branches of fctm meet at fck = 50 MPa (fcm 58) within 0.3 %, and 2.12 ln(11) at fcm = 100
    assert concrete.tensile_strength_mc2010(58e6) == pytest.approx(0.30e6 * 50 ** (2 / 3), rel=1e-12)
    assert concrete.tensile_strength_mc2010(58.001e6) == pytest.approx(0.30e6 * 50 ** (2 / 3), rel=3e-3)
    assert concrete.tensile_strength_mc2010(100e6) == pytest.approx(5.0835e6, rel=1e-4)


@pytest.mark.parametrize("fc", [10e6, 250e6, math.nan])
def test_scaling_refuses_strengths_outside_its_range(fc):
    with pytest.raises(ParameterError) as err:
        concrete.hjc_for_strength(fc, HJC())
    assert "fc" in str(err.value) and "allowed" in str(err.value) and "200" in str(err.value)


# ------------------------------------------------------------------ analytic against trajectory
@pytest.mark.parametrize("mass,radius,velocity,fc", [
    (0.904, 0.01345, 800.0, 32.4e6),    # a Forrestal 2003 shot
    (81.1, 0.07, 835.0, 48e6),          # the DO1 caliber
    (5.9, 0.0381, 250.0, 62.8e6),       # slow
    (81.1, 0.07, 120.0, 48e6),          # stops inside the crater (V1^2 < 0)
])
def test_closed_form_time_and_peak_equal_the_integrated_trajectory(mass, radius, velocity, fc):
    ctx = L.Context()
    shot = L.UserShot(Ogive(3.0, radius), mass, velocity, fc, 2440.0)
    a, t = L.run(shot, "analytic", ctx), L.run(shot, "trajectory", ctx)
    assert a.depth_m == pytest.approx(t.depth_m, rel=1e-7)
    assert a.time_to_rest_s == pytest.approx(t.time_to_rest_s, rel=1e-6)
    assert a.peak_deceleration_m_s2 == pytest.approx(t.peak_deceleration_m_s2, rel=1e-6)


def test_shot_fields_are_checked_by_name():
    """A UserShot (SI) names the shot field of the shots CSV and the command line, in that field's unit."""
    for field, value, name in (("mass", 0.0, "mass_kg"), ("velocity", -1.0, "velocity_ms"), ("fc", math.inf, "fc_MPa"),
                               ("density", 50.0, "target_density_kgm3")):
        kw = dict(nose=Ogive(3.0, 0.07), mass=10.0, velocity=500.0, fc=40e6, density=2400.0)
        kw[field] = value
        with pytest.raises(ParameterError) as err:
            L.UserShot(**kw)
        assert f"shot.{name} = " in str(err.value) and "allowed" in str(err.value)
    with pytest.raises(ParameterError, match="shot.length_m"):
        L.UserShot(Ogive(3.0, 0.07), 10.0, 500.0, 40e6, length=0.1)  # shorter than the nose (0.2417 m)


# ------------------------------------------------------------------ cavity level: one table per concrete and caliber
def cheap_context():
    return L.Context(strength_scale=0.6, strength_scale_source="test", cavity_velocities=(100.0, 300.0, 600.0, 1000.0),
                     cavity_mesh=CavityMesh(zones=40, cap=40.0), cavity_controls=CavityControls(tol=1e-4))


def test_sigma_tables_are_built_once_per_concrete_and_caliber():
    ctx = cheap_context()
    nose = Ogive(3.0, 0.03)
    d1 = L.run(L.UserShot(nose, 5.0, 600.0, 40e6), "cavity", ctx).depth_m
    d2 = L.run(L.UserShot(nose, 7.0, 400.0, 40e6), "cavity", ctx).depth_m
    assert ctx.table_builds == 1 and d1 != d2
    L.run(L.UserShot(nose, 5.0, 600.0, 80e6), "cavity", ctx)
    assert ctx.table_builds == 2
    L.run(L.UserShot(Ogive(3.0, 0.05), 5.0, 600.0, 40e6), "cavity", ctx)
    assert ctx.table_builds == 3


def test_cavity_level_resists_more_in_stronger_concrete():
    ctx = cheap_context()
    depths = [L.run(L.UserShot(Ogive(3.0, 0.03), 5.0, 600.0, fc), "cavity", ctx).depth_m for fc in (30e6, 60e6, 120e6)]
    assert depths[0] > depths[1] > depths[2] > 0


# ------------------------------------------------------------------ fe level: the calibration mesh scaled with the shot
def fe_context():
    ctx = context_from_pipeline(ROOT, "ci")
    ctx.failure_strain, ctx.failure_strain_source = 0.75, "test"
    return ctx


def test_fe_settings_keep_the_elements_across_the_radius():
    ctx = fe_context()
    shot = L.UserShot(Ogive(2.0, 0.01345), 0.904, 800.0, 32.4e6, 2300.0, 0.2427)
    s, k = L.fe_settings_for(shot, ctx)
    assert k == pytest.approx(0.01345 / 0.07)
    assert shot.nose.radius / s.element_size == pytest.approx(0.07 / ctx.fe_settings.element_size)
    assert s.body_length == 0.2427 and s.controls.erosion_value == 0.75


def test_fe_level_is_scale_invariant_without_the_rate_term(monkeypatch):
    """Without the rate term nothing in the fe level has a length or time scale but the shot's: a projectile twice
    as large (mass x 8, same velocity and concrete) goes exactly twice as deep, in twice the time, at half the
    deceleration. Factors of two are exact in floating point, so the erosion's chaos does not blur the test. The
    one other length, the 1 pm grid the rigid outline is rounded to (fe.mesh.OUTLINE_DIGITS), is switched off:
    a decimal grid does not scale by two."""
    import penetration.fe.mesh as mesh
    monkeypatch.setattr(mesh, "OUTLINE_DIGITS", None)
    ctx = fe_context()
    ctx.base = dataclasses.replace(ctx.base, rate=False)
    runs = [L.run(L.UserShot(Ogive(3.0, 0.0625 * k), 40.0 * k**3, 700.0, 48e6, 2440.0, 0.8 * k), "fe", ctx)
            for k in (1.0, 2.0)]
    assert runs[0].status == runs[1].status == "rest"
    assert runs[1].depth_m == 2 * runs[0].depth_m
    assert runs[1].time_to_rest_s == 2 * runs[0].time_to_rest_s
    assert runs[1].peak_deceleration_m_s2 == 0.5 * runs[0].peak_deceleration_m_s2


def test_fe_level_needs_the_projectile_length():
    with pytest.raises(ParameterError, match="shot.length_m"):
        L.run(L.UserShot(Ogive(3.0, 0.05), 10.0, 500.0, 40e6), "fe", fe_context())


# ------------------------------------------------------------------ command line
SHOT = ("ogive", "psi=3", "diameter_m=0.14", "mass_kg=81.1", "velocity_ms=835", "fc_MPa=48")


def test_dop_json_is_the_closed_form():
    out = cli("dop", *SHOT, "--json")
    assert out.returncode == 0, out.stderr
    rec = json.loads(out.stdout)
    # Forrestal's two-phase model by hand: Li & Chen's S = 72 fc^-0.5 (fc in MPa), N* = (8 psi - 1)/(24 psi^2) for
    # CRH 3, the default concrete density 2440; Eq 9 for the depth, and the crater (F = c z, c 4a = F(V1)) and tunnel
    # (F = pi a^2 (S fc + N* rho v^2)) laws integrated numerically for the time to rest and the peak force
    from scipy.integrate import solve_ivp
    m, a, fc, rho, vs, n = 81.1, 0.07, 48e6, 2440.0, 835.0, 23 / 216
    R = 72 * 48**-0.5 * fc
    from conftest import eq9_by_hand, v1_squared_by_hand
    v1sq, depth = v1_squared_by_hand(m, a, n, rho, R, vs), eq9_by_hand(m, a, n, rho, R, vs)
    c = math.pi * a**2 * (R + n * rho * v1sq) / (4 * a)
    force = lambda z, v: c * z if z < 4 * a else math.pi * a**2 * (R + n * rho * v * v)
    rest = lambda t, y: y[1]
    rest.terminal = True
    sol = solve_ivp(lambda t, y: (y[1], -force(y[0], y[1]) / m), (0, 1), (0.0, vs), events=rest, rtol=1e-11,
                    atol=1e-12, max_step=2e-6)
    t, peak = sol.t_events[0][0], max(force(z, v) for z, v in zip(*sol.y)) / m
    assert sol.y_events[0][0][0] == pytest.approx(depth, rel=1e-6)     # the integration meets Eq 9
    assert rec["level"] == "analytic"
    assert rec["depth_m"] == pytest.approx(depth, rel=1e-9)
    assert rec["time_to_rest_s"] == pytest.approx(t, rel=1e-6)
    assert rec["peak_deceleration_m_s2"] == pytest.approx(peak, rel=1e-4)   # the samples' largest force


def test_simulate_writes_the_history(tmp_path):
    out = cli("simulate", *SHOT, "--model", "trajectory", "--out", str(tmp_path / "h.csv"), "--json")
    assert out.returncode == 0, out.stderr
    rec = json.loads(out.stdout)
    import pandas as pd
    h = pd.read_csv(tmp_path / "h.csv")
    assert list(h.columns) == ["t_s", "depth_m", "velocity_m_s", "deceleration_m_s2"]
    assert h.depth_m.iloc[-1] == pytest.approx(rec["depth_m"], rel=1e-10)  # the CSV keeps 12 digits
    assert h.velocity_m_s.iloc[0] == 835.0 and h.velocity_m_s.iloc[-1] == 0.0


def test_keys_may_follow_the_options():
    """key=value pairs after an option are the same keys as before it (argparse alone would reject them)."""
    before = cli("dop", *SHOT, "--model", "trajectory", "--json")
    after = cli("dop", *SHOT[:3], "--model", "trajectory", *SHOT[3:5], "--json", SHOT[5])
    assert before.returncode == 0 and after.returncode == 0, after.stderr
    a, b = json.loads(before.stdout), json.loads(after.stdout)
    assert a.pop("wall_time_s") > 0 and b.pop("wall_time_s") > 0
    assert a == b
    nstar = cli("nstar", "ogive", "--json", "psi=3", "radius=0.07")
    assert nstar.returncode == 0 and json.loads(nstar.stdout)["nstar"] == pytest.approx(23 / 216, rel=1e-10)


@pytest.mark.parametrize("args,needle", [
    (("dop", "ogive", "psi=3", "diameter_m=0.14", "velocity_ms=835", "fc_MPa=48"), "shot.mass_kg"),
    (("dop", *SHOT, "--json", "--colour"), "unrecognized arguments: --colour"),
    (("dop", *SHOT, "--json", "stray"), "unrecognized arguments: stray"),
    (("dop", *SHOT, "--model", "fe", "psi=2"), "each key once (psi=3 is given already)"),
    (("dop", *SHOT, "target_density_kgm3=abc"), "shot.target_density_kgm3"),
    (("dop", *SHOT[:-1], "fc_MPa=500", "--model", "cavity", "--strength-scale", "0.6"), "shot.fc_MPa"),
    (("dop", *SHOT, "--model", "cavity", "--strength-scale", "-1"), "--strength-scale"),
    (("dop", *SHOT, "--model", "fe", "--failure-strain", "0.7"), "shot.length_m"),
    (("simulate", *SHOT, "--out", "x.csv"), "analytic has no history"),
    (("dop", *SHOT, "colour=red"), "colour"),
])
def test_one_shot_errors_name_the_field(args, needle):
    out = cli(*args)
    assert out.returncode == 2 and needle in out.stderr and out.stdout == ""


def test_a_missing_calibration_says_how_to_build_it(tmp_path):
    (tmp_path / "workflow").mkdir()
    (tmp_path / "workflow/config.yaml").write_text((ROOT / "workflow/config.yaml").read_text())
    (tmp_path / "workflow/reference").symlink_to(ROOT / "workflow/reference")
    out = cli("dop", *SHOT, "--model", "cavity", "--root", str(tmp_path))
    assert out.returncode == 2 and "snakemake -c2 figures/calibration_cavity_laboratory.csv" in out.stderr
    assert "--strength-scale" in out.stderr and "--calibration" in out.stderr
    out = cli("dop", *SHOT, "--model", "cavity", "--root", str(tmp_path), "--calibration", "do1")
    assert out.returncode == 2 and "snakemake -c2 figures/calibration_cavity_do1.csv" in out.stderr
    out = cli("dop", *SHOT, "--model", "cavity", "--root", str(tmp_path), "--calibration", "nowhere.csv")
    assert out.returncode == 2 and "--calibration" in out.stderr and "laboratory" in out.stderr


def test_the_trajectory_and_cavity_levels_read_no_fe_section(tmp_path):
    """The validation rules of the trajectory and cavity levels pass no fe section (an fe edit must not rerun
    them): the context then leaves the fe settings at their defaults and refuses an fe calibration."""
    import yaml
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    ref = ROOT / cfg["reference"]
    full = context_from_files(cfg, ref)
    lean = context_from_files({k: cfg[k] for k in ("concrete", "cavity", "validation")}, ref)
    assert full.fe_settings is not None and lean.fe_settings is None
    assert lean.base == full.base and lean.cavity_mesh == full.cavity_mesh and lean.cavity_velocities == full.cavity_velocities
    cal = tmp_path / "cal.json"
    cal.write_text(json.dumps({"element_size": 0.01, "fs": 1.0, "elements_across_radius": 8}))
    with pytest.raises(ValueError, match="fe section"):
        context_from_files({k: cfg[k] for k in ("concrete", "cavity", "validation")}, ref, fe_cal=cal)


def test_predict_at_the_trajectory_level_adds_every_column(tmp_path):
    out_csv = tmp_path / "out.csv"
    out = cli("predict", str(ROOT / "workflow/data/experiments-dev.csv"), "--model", "trajectory", "--out", str(out_csv))
    assert out.returncode == 0, out.stderr
    import pandas as pd
    got, shots = pd.read_csv(out_csv), pd.read_csv(ROOT / "workflow/data/experiments-dev.csv")
    assert len(got) == len(shots)
    assert list(got.columns[-5:]) == ["model", "dop_pred_m", "time_to_rest_pred_s", "peak_deceleration_pred_m_s2",
                                      "wall_time_s"]
    assert (got.model == "trajectory").all() and np.all(got.dop_pred_m > 0) and np.all(got.time_to_rest_pred_s > 0)


def test_table3_cells_are_matched_by_velocity_and_nose_not_by_row():
    """accuracy_cost compares the FE tables (noses in the order crh3, crh45, double_ogive) with figures/table3.csv
    (double_ogive, crh45, crh3): the deviation of a cell must not depend on the order of the rows."""
    import pandas as pd

    from penetration.tasks.levels import cell_deviation
    ref = pd.DataFrame({"velocity_ms": [500, 500, 800, 800], "nose": ["double_ogive", "crh3"] * 2,
                        "paper_sim_m": [2.0, 1.0, 4.0, 3.0]})
    fe = pd.DataFrame({"velocity_ms": [800, 500, 800, 500], "nose": ["crh3", "crh3", "double_ogive", "double_ogive"],
                       "fe_m": [3.3, 1.1, 4.0, 1.0]})
    dev = cell_deviation(fe, ref, "fe_m", "paper_sim_m")
    assert np.allclose(np.sort(dev), np.sort([0.1, 0.1, 0.0, 0.5]))
    assert np.isclose(cell_deviation(fe, fe.iloc[::-1], "fe_m", "fe_m").max(), 0.0)
    with pytest.raises(ValueError, match="without a partner"):
        cell_deviation(fe.iloc[:3], ref, "fe_m", "paper_sim_m")
