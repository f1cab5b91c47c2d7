"""Closed-form DOP (Eq 9): Li & Chen form, dimensions, crater stop, hard cases."""
import math

import numpy as np
import pytest

from penetration.analytic.dop import geometry_function, impact_function, li_chen_depth, penetration_depth
from penetration.analytic.resistance import Target, crater_velocity_squared, strength_factor
from penetration.nose.geometry import Flat, MinimumNstar, Ogive
from penetration.nose.nstar import nstar

TG = Target(2440.0, 48e6, 6.69)


def test_li_chen_form_equals_eq9():
    v = np.linspace(50, 2000, 300)
    for n in (0.05, 0.1065, 0.5, 1.0):
        d = 0.14
        I, N = impact_function(81.1, d, TG, v), geometry_function(81.1, d, n, TG)
        assert np.allclose(li_chen_depth(I, N) * d, penetration_depth(81.1, 0.07, n, TG, v), rtol=1e-12)


def test_geometric_similarity_confirms_a_cubed():
    """Scaling lengths by L and mass by L^3 scales the depth by L only with a^3 in V1."""
    for L in (0.1, 3.0, 17.0):
        p1 = penetration_depth(81.1, 0.07, 0.07, TG, np.array([300.0, 835.0]))
        pL = penetration_depth(81.1 * L**3, 0.07 * L, 0.07, TG, np.array([300.0, 835.0]))
        assert np.allclose(pL, L * p1, rtol=1e-12)


def test_crater_stop_is_continuous_and_shallow():
    m, a, n = 81.1, 0.07, 0.0608
    vcrit = math.sqrt(4 * math.pi * a**3 * TG.R / m)
    assert crater_velocity_squared(m, a, n, TG, vcrit) == pytest.approx(0, abs=1e-6)
    below, at, above = penetration_depth(m, a, n, TG, vcrit * np.array([1 - 1e-9, 1, 1 + 1e-9]))
    assert below == pytest.approx(4 * a, rel=1e-6) and above == pytest.approx(4 * a, rel=1e-6)
    low = penetration_depth(m, a, n, TG, np.array([1.0, 10.0, 0.5 * vcrit]))
    assert np.all(np.isfinite(low)) and np.all(low < 4 * a) and np.all(np.diff(low) > 0)


NOSES = [Ogive(3, 0.07), Ogive(0.5, 0.07), Flat(0.07), MinimumNstar(0.07, 0.29), Ogive(100, 0.07)]


@pytest.mark.parametrize("nose", NOSES, ids=lambda n: n.kind)
@pytest.mark.parametrize("mass", [0.05, 81.1, 1e5])
@pytest.mark.parametrize("fc", [10e6, 48e6, 200e6])
def test_monotone_and_finite_over_hard_cases(nose, mass, fc):
    tg = Target(2400.0, fc, float(strength_factor(fc)))
    v = np.concatenate(([1.0], np.linspace(2, 2000, 800)))
    p = penetration_depth(mass, nose.radius, nstar(nose), tg, v)
    assert np.all(np.isfinite(p)) and np.all(p > 0)
    assert np.all(np.diff(p) > 0)


def test_vectorised_over_targets_and_shots():
    tg = Target(np.array([2300.0, 2440.0]), np.array([30e6, 48e6]), np.array([10.0, 6.69]))
    p = penetration_depth(np.array([81.1, 81.1]), 0.07, 0.0608, tg, np.array([835.0, 835.0]))
    single = [penetration_depth(81.1, 0.07, 0.0608, Target(r, f, s), 835.0) for r, f, s in
              zip(tg.rho, tg.fc, tg.S)]
    assert np.allclose(p, single, rtol=1e-14)
