"""Checks of the dynamic spherical cavity-expansion oracles in penetration/cavity/oracles.py."""
import numpy as np
import pytest
from scipy.integrate import quad

from penetration.cavity.oracles import (dilatational_speed, elastic_fields, elastic_region_fields, elastic_wall_stress,
                                        epp_wall_stress, hill_static_pressure, mohr_coulomb_static_wall_stress,
                                        mohr_coulomb_wall_stress, plastic_solution)

RHO0, K, G, Y = 2440.0, 16e9, 14.86e9, 100e6
CD = dilatational_speed(RHO0, K, G)


# ------------------------------------------------------------------ elastic helpers
def _fields_rt(r, t, V, hoop=True):
    return elastic_fields(r / (V * t), V, RHO0, K, G, hoop=hoop)


def _displacement(r, t, V):
    """Independent route: time-integrate the particle velocity at fixed r."""
    v = lambda s: _fields_rt(r, s, V, hoop=False)[0]
    return quad(v, r / CD, t, epsabs=0.0, epsrel=1e-13, limit=200)[0]


def _hooke_from_displacement(r, t, V, one_sided=False):
    """Compression-positive (sigma_r, sigma_theta) from FD strains of the integrated displacement."""
    h = 1e-4 * r
    if one_sided:  # second-order forward difference (r at the wall)
        w0, w1, w2 = (_displacement(r + k * h, t, V) for k in range(3))
        dw = (-3 * w0 + 4 * w1 - w2) / (2 * h)
    else:
        w0 = _displacement(r, t, V)
        dw = (_displacement(r + h, t, V) - _displacement(r - h, t, V)) / (2 * h)
    e_r, e_t = dw, w0 / r
    lam_l = K - 2 * G / 3
    return -((lam_l + 2 * G) * e_r + 2 * lam_l * e_t), -(lam_l * e_r + 2 * (lam_l + G) * e_t)


# ------------------------------------------------------------------ elastic tests
@pytest.mark.parametrize("V", [10.0, 100.0, 1000.0])
def test_elastic_wall_bc_and_front(V):
    v_w, s_w = elastic_fields(1.0, V, RHO0, K, G)
    assert v_w == pytest.approx(V, rel=1e-12)
    assert s_w == pytest.approx(elastic_wall_stress(V, RHO0, K, G), rel=1e-12)
    v_f, s_r_f, s_t_f = elastic_fields(CD / V, V, RHO0, K, G, hoop=True)
    scale = abs(s_w)
    # Fields vanish at the wave front: zero jump, so [sigma_r] = rho0 cd [v] holds trivially.
    assert abs(v_f) < 1e-12 * V and abs(s_r_f) < 1e-12 * scale and abs(s_t_f) < 1e-12 * scale
    assert abs(s_r_f - RHO0 * CD * v_f) < 1e-12 * scale
    # Wall shear is exactly 2G for any V (the yield criterion used by the plastic oracles).
    _, s_r, s_t = elastic_fields(1.0, V, RHO0, K, G, hoop=True)
    assert s_r - s_t == pytest.approx(2 * G, rel=1e-12)


@pytest.mark.parametrize("V", [10.0, 300.0])
def test_elastic_stress_matches_hooke_of_integrated_velocity(V):
    t = 1e-3
    for r in np.linspace(1.05 * V * t, 0.95 * CD * t, 7):
        s_r, s_t = _hooke_from_displacement(r, t, V)
        _, s_r_ref, s_t_ref = _fields_rt(r, t, V)
        scale = max(abs(s_r_ref), abs(s_t_ref))
        assert abs(s_r - s_r_ref) < 1e-6 * scale
        assert abs(s_t - s_t_ref) < 1e-6 * scale


@pytest.mark.parametrize("V", [10.0, 300.0, 1000.0])
def test_elastic_momentum_equation_fd(V):
    """rho0 dv/dt = -(d sigma_r/dr + 2 (sigma_r - sigma_theta)/r), compression-positive."""
    t = 2e-3
    for r in np.linspace(1.02 * V * t, 0.98 * CD * t, 9):
        hr, ht = 1e-5 * r, 1e-5 * t
        dv_dt = (_fields_rt(r, t + ht, V)[0] - _fields_rt(r, t - ht, V)[0]) / (2 * ht)
        ds_dr = (_fields_rt(r + hr, t, V)[1] - _fields_rt(r - hr, t, V)[1]) / (2 * hr)
        _, s_r, s_t = _fields_rt(r, t, V)
        res = RHO0 * dv_dt + ds_dr + 2 * (s_r - s_t) / r
        assert abs(res) < 1e-6 * (abs(ds_dr) + abs(2 * (s_r - s_t) / r))


def test_elastic_wall_stress_independent_of_time():
    V = 100.0
    ref = elastic_wall_stress(V, RHO0, K, G)
    for t in [1e-6, 1e-4, 1e-2]:
        s_r, _ = _hooke_from_displacement(V * t, t, V, one_sided=True)
        assert s_r == pytest.approx(ref, rel=1e-6)
        assert _fields_rt(V * t, t, V)[0] == pytest.approx(V, rel=1e-12)


def test_elastic_closed_form_limits():
    assert elastic_wall_stress(1e-6, RHO0, K, G) == pytest.approx(4 * G / 3, rel=1e-12)
    with pytest.raises(ValueError):
        elastic_wall_stress(1.01 * CD, RHO0, K, G)


# ------------------------------------------------------------------ EPP tests
@pytest.mark.parametrize("V", [0.01, 0.1, 1.0])
def test_epp_quasistatic_limit_is_hill(V):
    p_hill = hill_static_pressure(K, G, Y)
    assert epp_wall_stress(V, RHO0, K, G, Y) == pytest.approx(p_hill, rel=0.01)


@pytest.mark.parametrize("V", [10.0, 300.0])
def test_epp_large_yield_tends_to_elastic(V):
    s_el = elastic_wall_stress(V, RHO0, K, G)
    assert epp_wall_stress(V, RHO0, K, G, 0.999 * 2 * G) == pytest.approx(s_el, rel=1e-4)
    assert epp_wall_stress(V, RHO0, K, G, 2.5 * G) == s_el
    vals = [epp_wall_stress(V, RHO0, K, G, f * 2 * G) for f in (0.5, 0.9, 0.99)]
    assert np.all(np.diff(vals) > 0) and vals[-1] < s_el


def test_epp_smooth_and_increasing_in_V():
    Vs = np.arange(50.0, 1001.0, 50.0)
    s = np.array([epp_wall_stress(V, RHO0, K, G, Y) for V in Vs])
    d = np.diff(s)
    d2 = np.diff(d)
    assert s[0] > hill_static_pressure(K, G, Y)
    assert np.all(d > 0)
    assert np.all(d2 > 0)                      # convex, roughly A + B rho0 V^2
    assert np.all(np.abs(d2[1:] / d2[:-1] - 1) < 0.05)  # no kinks or jumps


@pytest.mark.parametrize("V", [300.0, 1000.0])
def test_epp_incompressible_limit_inertia_coefficient(V):
    """K -> inf: sigma_w -> (2Y/3)(1 + ln(2E/3Y)) + 1.5 rho0 V^2 (Hopkins / Forrestal-Luk)."""
    k_big = 1e4 * G
    s = epp_wall_stress(V, RHO0, k_big, G, Y)
    coeff = (s - hill_static_pressure(k_big, G, Y)) / (RHO0 * V**2)
    assert coeff == pytest.approx(1.5, rel=0.01)


@pytest.mark.parametrize("V,lam", [(100.0, 0.0), (1000.0, 0.0), (300.0, 0.5)])
def test_plastic_zone_satisfies_conservation_and_interface(V, lam):
    out = plastic_solution(V, RHO0, K, G, Y, lam, dense=True)
    c, sol = out["c"], out["sol"]
    alpha = 1 + 2 * lam / 3
    # Front: continuity with the elastic solution, which is at yield there.
    x = c / CD
    v_c, s_c = sol.sol(c)
    b = v_c * x**2 / (3 * CD * (1 - x**2))
    _, s_r_e, s_t_e = elastic_region_fields(x, b, CD, K, G)
    p_e = (s_r_e + 2 * s_t_e) / 3
    assert s_c == pytest.approx(s_r_e, rel=1e-10)
    assert s_r_e - s_t_e == pytest.approx(Y + lam * p_e, rel=1e-10)
    # Wall: the particle velocity equals V.
    assert sol.sol(V)[0] == pytest.approx(V, rel=1e-8)
    # Interior: the Eulerian momentum and mass balances hold (FD in z = r/t).
    for z in np.linspace(V, c, 12)[1:-1]:
        h = 1e-6 * z
        (v0, s0), (vp, sp), (vm, sm) = sol.sol(z), sol.sol(z + h), sol.sol(z - h)
        dv, ds = (vp - vm) / (2 * h), (sp - sm) / (2 * h)
        p = lambda s_: (s_ - 2 * Y / 3) / alpha
        rho = lambda s_: RHO0 / (1 - p(s_) / K)
        drho = (rho(sp) - rho(sm)) / (2 * h)
        tau = Y + lam * p(s0)
        mom = rho(s0) * (v0 - z) * dv + ds + 2 * tau / z
        mass = (v0 - z) * drho + rho(s0) * (dv + 2 * v0 / z)
        assert abs(mom) < 1e-6 * (2 * tau / z)
        assert abs(mass) < 1e-6 * rho(s0) * (abs(dv) + 2 * v0 / z)


# ------------------------------------------------------------------ Mohr-Coulomb tests
def test_mohr_coulomb_reduces_to_epp_and_is_monotone():
    for V in [10.0, 300.0]:
        assert mohr_coulomb_wall_stress(V, RHO0, K, G, Y, 0.0) == epp_wall_stress(V, RHO0, K, G, Y)
        assert mohr_coulomb_wall_stress(V, RHO0, K, G, Y, 1e-7) == pytest.approx(
            epp_wall_stress(V, RHO0, K, G, Y), rel=1e-5)
        s = [mohr_coulomb_wall_stress(V, RHO0, K, G, Y, lam) for lam in (0.0, 0.2, 0.5, 1.0)]
        assert np.all(np.diff(s) > 0)
    s = [mohr_coulomb_wall_stress(V, RHO0, K, G, Y, 0.5) for V in (10.0, 100.0, 300.0, 600.0)]
    assert np.all(np.diff(s) > 0)


@pytest.mark.parametrize("lam", [0.0, 0.2, 0.5, 1.0])
def test_mohr_coulomb_quasistatic_limit(lam):
    ref = mohr_coulomb_static_wall_stress(K, G, Y, lam)
    assert mohr_coulomb_wall_stress(0.1, RHO0, K, G, Y, lam) == pytest.approx(ref, rel=0.02)


def test_mohr_coulomb_static_closed_form_reduces_to_hill():
    assert mohr_coulomb_static_wall_stress(K, G, Y, 0.0) == pytest.approx(
        hill_static_pressure(K, G, Y), rel=0.005)
    assert mohr_coulomb_static_wall_stress(K, G, Y, 1e-6) == pytest.approx(
        mohr_coulomb_static_wall_stress(K, G, Y, 0.0), rel=1e-5)
