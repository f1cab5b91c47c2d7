"""Trajectory engine against the closed form, energy, effects and hard cases."""
import math

import numpy as np
import pytest

from conftest import recorded_work
from penetration.analytic.dop import penetration_depth
from penetration.analytic.resistance import (Target, double_ogive_force_eq11, forrestal_stress, nose_force,
                                             nose_surface, tunnel_force)
from penetration.analytic.trajectory import assemble, integrate
from penetration.errors import ParameterError
from penetration.nose.geometry import Cone, DoubleOgive, Flat, MinimumNstar, Ogive
from penetration.nose.nstar import nstar

TG = Target(2440.0, 48e6, 6.69)
FORRESTAL = ("crater", "static", "inertial")
DO = DoubleOgive(0.07, S1=0.8576, S2=0.42, a1=0.0397, a2=0.0638, alpha=0.245)


def run(nose, vs, effects=FORRESTAL, mass=81.1, rtol=1e-10, **kw):
    n = nstar(nose)
    return integrate(assemble(effects, nose, n, mass, TG, vs, **kw), mass, vs, rtol=rtol)


@pytest.mark.parametrize("nose", [Ogive(3, 0.07), Ogive(4.5, 0.07), DO, MinimumNstar(0.07, 0.29), Flat(0.07)],
                         ids=lambda n: n.kind)
@pytest.mark.parametrize("vs", [60.0, 150.0, 500.0, 835.0, 1200.0, 2000.0])
def test_reproduces_eq9_and_conserves_energy(nose, vs):
    tr = run(nose, vs)
    exact = float(penetration_depth(81.1, 0.07, nstar(nose), TG, vs))
    assert tr.depth == pytest.approx(exact, rel=1e-6)
    assert recorded_work(tr, 81.1) == pytest.approx(0.5 * 81.1 * vs**2, rel=1e-3)


def test_error_falls_with_tolerance():
    exact = float(penetration_depth(81.1, 0.07, nstar(DO), TG, 835.0))
    errs = [abs(run(DO, 835.0, rtol=r).depth - exact) / exact for r in (1e-3, 1e-6, 1e-9)]
    assert errs[0] > errs[2] and errs[2] < 1e-8


def test_crater_threshold_both_sides():
    m, a = 81.1, 0.07
    vcrit = math.sqrt(4 * math.pi * a**3 * TG.R / m)
    for vs in (vcrit * (1 - 1e-6), vcrit * (1 + 1e-6), 1.0):
        tr = run(Ogive(3, a), vs)
        assert np.isfinite(tr.depth) and tr.depth == pytest.approx(
            float(penetration_depth(m, a, nstar(Ogive(3, a)), TG, vs)), rel=1e-6)


@pytest.mark.parametrize("mass", [0.2, 1e4])
def test_light_and_heavy(mass):
    tr = run(Ogive(3, 0.07), 900.0, mass=mass)
    assert tr.depth == pytest.approx(float(penetration_depth(mass, 0.07, nstar(Ogive(3, 0.07)), TG, 900.0)), rel=1e-6)


def test_only_listed_effects_are_built():
    asm = assemble(("static",), Ogive(3, 0.07), 0.1, 81.1, TG, 800.0)
    assert [type(e).__name__ for e in asm.effects] == ["Static"]
    tr = integrate(asm, 81.1, 800.0)
    # constant force: z = m v^2 / (2 F)
    assert tr.depth == pytest.approx(81.1 * 800.0**2 / (2 * math.pi * 0.07**2 * TG.R), rel=1e-8)


def test_inertial_only_never_stops_but_static_plus_inertial_closed_form():
    nose = Ogive(3, 0.07)
    n = nstar(nose)
    tr = run(nose, 800.0, effects=("static", "inertial"))
    k = math.pi * 0.07**2
    exact = 81.1 / (2 * k * TG.rho * n) * math.log(1 + n * TG.rho * 800.0**2 / TG.R)
    assert tr.depth == pytest.approx(exact, rel=1e-7)


def test_nose_entry_friction_and_ramp_are_consistent():
    nose = Ogive(3, 0.07)
    base = run(nose, 800.0, effects=("static", "inertial"))
    entry = run(nose, 800.0, effects=("nose_entry", "static", "inertial"))
    fric = run(nose, 800.0, effects=("nose_entry", "static", "inertial", "friction"), mu=0.1)
    ramp = run(nose, 800.0, effects=("nose_entry", "static", "inertial", "free_surface_ramp"))
    assert base.depth < entry.depth < ramp.depth
    assert fric.depth < entry.depth
    for tr in (entry, fric, ramp):
        assert recorded_work(tr, 81.1) == pytest.approx(0.5 * 81.1 * 800.0**2, rel=1e-3)


def test_effect_errors_name_the_field():
    with pytest.raises(ParameterError, match="effects"):
        assemble(("crater", "drag"), Ogive(3, 0.07), 0.1, 81.1, TG, 800.0)
    with pytest.raises(ParameterError, match="crater is not allowed with"):
        assemble(("crater", "nose_entry"), Ogive(3, 0.07), 0.1, 81.1, TG, 800.0)
    with pytest.raises(ParameterError, match="static needs a target"):
        assemble(("static",), Ogive(3, 0.07), 0.1, 81.1, None, 800.0)
    with pytest.raises(ParameterError, match="cavity needs a sigma_n"):
        assemble(("cavity",), Ogive(3, 0.07), 0.1, 81.1, TG, 800.0)


def test_scene_schema_effects_are_the_registries():
    """Every effect a scene may name is a registered trajectory, material or FE effect or the scale effect, and the
    reverse; the scale effect's variants (the config's, which a scene names) use its registry's mechanisms."""
    import json
    from pathlib import Path

    from penetration.analytic.trajectory import EFFECTS
    from penetration.concrete.effects import MATERIAL_EFFECTS
    from penetration.concrete.size import SIZE_MECHANISMS
    from penetration.pipeline.scenes import FE_EFFECTS, SIZE
    schema = json.loads((Path(__file__).resolve().parents[1] / "workflow/schemas/scene.schema.json").read_text())
    named = set(schema["properties"]["effects"]["items"]["enum"])
    assert named == set(EFFECTS) | set(MATERIAL_EFFECTS) | set(FE_EFFECTS) | {SIZE}
    groups = [set(EFFECTS), set(MATERIAL_EFFECTS), set(FE_EFFECTS), {SIZE}]
    assert sum(map(len, groups)) == len(set().union(*groups))
    import yaml
    config = yaml.safe_load((Path(__file__).resolve().parents[1] / "workflow/config.yaml").read_text())
    named = {m for v in config["scale_effect"]["variants"].values() if v for m in v["mechanisms"]}
    assert named == set(SIZE_MECHANISMS)   # the variants a scene names use every registered mechanism, no other


@pytest.mark.parametrize("nose", [Ogive(3, 0.07), Cone(0.07, 0.3), DO, MinimumNstar(0.07, 0.3), Flat(0.07)],
                         ids=lambda n: n.kind)
def test_differential_area_law_equals_eq7(nose):
    s = nose_surface(nose)
    for v in (0.0, 300.0, 1500.0):
        assert nose_force(s, v, forrestal_stress(TG)) == pytest.approx(
            float(tunnel_force(0.07, nstar(nose), TG, v)), rel=1e-12)


def test_eq11_region_form_equals_general_law():
    s = nose_surface(DO)
    for v in (0.0, 500.0, 1200.0):
        assert double_ogive_force_eq11(DO, v, TG) == pytest.approx(nose_force(s, v, forrestal_stress(TG)), rel=1e-12)


def test_partial_embedding_of_a_cone():
    """Wetted cone of depth z: pi y(z)^2 (R + rho v^2 sin^2 beta) exactly."""
    cone = Cone(0.07, 0.3)
    s = nose_surface(cone)
    sin2 = 0.07**2 / (0.07**2 + 0.3**2)
    for z in (0.05, 0.15, 0.29):
        y = 0.07 * z / 0.3
        expected = math.pi * y**2 * (TG.R + TG.rho * 400.0**2 * sin2)
        assert nose_force(s, 400.0, forrestal_stress(TG), depth=z) == pytest.approx(expected, rel=1e-12)


def test_friction_adds_the_axial_share():
    cone = Cone(0.07, 0.3)
    s = nose_surface(cone)
    sig = forrestal_stress(TG)
    f0, f1 = nose_force(s, 500.0, sig), nose_force(s, 500.0, sig, mu=0.2)
    # for a cone dx = dy * b/a: friction adds mu * b/a of the normal term
    assert f1 / f0 == pytest.approx(1 + 0.2 * 0.3 / 0.07, rel=1e-12)


@pytest.mark.parametrize("fc", [10e6, 200e6])
@pytest.mark.parametrize("nose", [Ogive(0.5, 0.07), Flat(0.07), MinimumNstar(0.07, 0.29)], ids=lambda n: n.kind)
def test_trajectory_monotone_in_velocity_for_hard_noses_and_strengths(fc, nose):
    from penetration.analytic.resistance import strength_factor
    tg = Target(2400.0, fc, float(strength_factor(fc)))
    n = nstar(nose)
    depths = []
    for vs in (1.0, 50.0, 200.0, 600.0, 1200.0, 2000.0):
        tr = integrate(assemble(FORRESTAL, nose, n, 81.1, tg, vs), 81.1, vs, rtol=1e-9)
        assert np.isfinite(tr.depth)
        assert tr.depth == pytest.approx(float(penetration_depth(81.1, 0.07, n, tg, vs)), rel=1e-6)
        depths.append(tr.depth)
    assert np.all(np.diff(depths) > 0)


@pytest.mark.parametrize("fraction", [0.0, 0.3, 0.9, 1.0, 1.5, 4.0])
def test_crater_coefficient_of_eq7_and_of_a_general_law(fraction):
    """With Forrestal's sigma_n = S fc + rho v_n^2 integrated over the nose, F(V) = pi a^2 (S fc + N* rho V^2), so
    Eq 7's crater coefficient and the general one (any sigma_n law; the cavity level) solve the same c 4a = F(V1),
    V1^2 = vs^2 - 16 a^2 c / m, and agree above the critical velocity. Below it the closed form continues to
    V1^2 < 0 (Li & Chen's shallow branch) while the general law takes c = F(0)/4a: larger by at most the factor
    1 + 4 pi a^3 N* rho / m (reached at vs = 0)."""
    from penetration.analytic.resistance import crater_coefficient
    from penetration.analytic.trajectory import cavity_crater_coefficient
    m, a, nose = 81.1, 0.07, Ogive(3, 0.07)
    n = nstar(nose)
    vs = fraction * math.sqrt(4 * math.pi * a**3 * TG.R / m)
    force = lambda v: math.pi * a * a * (TG.R + n * TG.rho * v * v)
    closed, general = float(crater_coefficient(m, a, n, TG, vs)), cavity_crater_coefficient(m, a, vs, force)
    if fraction >= 1.0:
        assert closed == pytest.approx(general, rel=1e-10)
    else:
        bound = 1 + 4 * math.pi * a**3 * n * TG.rho / m
        assert 1.0 < general / closed <= bound * (1 + 1e-12)
        if fraction == 0.0:
            assert general / closed == pytest.approx(bound, rel=1e-12)
