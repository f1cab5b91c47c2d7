"""Cavity-expansion solver against exact and similarity solutions; convergence."""
import math

import numpy as np
import pytest

from oracles.cavity import epp_wall_stress, mohr_coulomb_wall_stress
from penetration.cavity import Controls, Mesh, Simple, expand, single_expansion, stress_table
from penetration.hjc import HJC

RHO, K, G = 2440.0, 16e9, 14.86e9


def elastic_wall_stress_history(t, V, a, rho, K, G):
    """Exact linear-elastic wall stress (compression positive) for a cavity of radius a
    whose wall moves outwards at V from t = 0 (potential f(t - (r - a)/c)/r)."""
    c = math.sqrt((K + 4 * G / 3) / rho)
    k = c / a
    f = -V * c * a * (t / k - 1 / k**2 + np.exp(-k * t) / k**2)
    f1 = -V * c * a * (1 / k - np.exp(-k * t) / k)
    f2 = -V * c * a * np.exp(-k * t)
    return -(rho * f2 / a + 4 * G * f1 / (c * a**2) + 4 * G * f / a**3)


def test_small_strain_elastic_against_exact_solution():
    a0, V = 1.0, 1.0
    t_end = 2.0 * a0 / math.sqrt((K + 4 * G / 3) / RHO)  # two wave transits of the radius
    ours = single_expansion(Simple(RHO, K, G), V, a0, a0 + V * t_end, xi_max=20.0, zones=2000,
                            controls=Controls(q_quad=0.0, q_lin=0.0))
    t = np.linspace(0.5 * t_end, t_end, 20001)
    exact = np.trapezoid(elastic_wall_stress_history(t, V, a0, RHO, K, G), t) / (0.5 * t_end)
    assert ours == pytest.approx(exact, rel=0.02)


@pytest.mark.parametrize("V", [100.0, 300.0, 1000.0])
def test_elastic_perfectly_plastic_against_similarity_solution(V):
    ours = expand(Simple(RHO, K, G, 100e6), V, mesh=Mesh(zones=200)).wall_stress
    assert ours == pytest.approx(epp_wall_stress(V, RHO, K, G, 100e6), rel=0.02)


@pytest.mark.parametrize("V", [300.0, 1000.0])
def test_mohr_coulomb_against_similarity_solution(V):
    ours = expand(Simple(RHO, K, G, 100e6, lam=0.5), V, mesh=Mesh(zones=200)).wall_stress
    assert ours == pytest.approx(mohr_coulomb_wall_stress(V, RHO, K, G, 100e6, 0.5), rel=0.02)


@pytest.mark.parametrize("V", [200.0, 1000.0])
def test_zone_count_convergence_hjc(V):
    coarse, fine = (expand(HJC(), V, mesh=Mesh(zones=z)).wall_stress for z in (100, 200))
    assert abs(coarse - fine) / fine < 0.005


def test_far_boundary_convergence_hjc():
    near, far = (expand(HJC(), 300.0, mesh=Mesh(zones=120, cap=c)).wall_stress for c in (80.0, 160.0))
    assert abs(near - far) / far < 0.005


def test_cycles_converge_and_table_is_monotone():
    s, res = stress_table(HJC(), [100.0, 400.0, 900.0, 1600.0], mesh=Mesh(zones=80))
    assert all(r.converged for r in res)
    assert np.all(np.diff(s) > 0)


def test_bad_velocity():
    with pytest.raises(ValueError, match="V > 0"):
        expand(HJC(), 0.0)


def test_erosion_strain_weakens_the_wall_monotonically_and_vanishes_when_large():
    import dataclasses
    base = HJC(strength_scale=0.6)
    ref = expand(base, 500.0, mesh=Mesh(zones=80)).wall_stress
    walls = [expand(dataclasses.replace(base, erosion_strain=fs), 500.0, mesh=Mesh(zones=80)).wall_stress
             for fs in (1e3, 1.0, 0.3, 0.1)]
    assert walls[0] == pytest.approx(ref, rel=1e-12)  # never reached: same as no erosion
    assert np.all(np.diff(walls) < 0) and walls[-1] < 0.8 * ref
