"""Independent reference solutions ("oracles") for dynamic spherical cavity expansion (similarity ODEs and closed forms,
written apart from the solver in penetration.cavity.expansion; the verification of the cavity level compares with them).

Problem
-------
A spherical cavity opens from zero radius at constant wall velocity ``V`` in an
unbounded medium initially at rest (density ``rho0``).  Motion is radial, and
every field depends only on the similarity variable ``z = r/t`` (equivalently
``xi = r/(V t)``; the wall is at ``xi = 1``).  SI units throughout.

Sign conventions: the radial velocity ``v`` is positive outward.  All stresses
returned by this module are **positive in compression**: ``sigma_r``,
``sigma_theta`` and the mean pressure ``p = (sigma_r + 2 sigma_theta)/3``.
The shear measure is ``tau = sigma_r - sigma_theta`` (> 0 for an expanding cavity).

Elastic region (used alone in Part 1, and ahead of the plastic zone in Parts 2-3)
-------------------------------------------------------------------------------
Linear, small-strain, isotropic elasticity (``lam_L = K - 2G/3``), linearised
momentum ``rho0 dv/dt = -(d sigma_r/dr + 2 tau / r)``.  The displacement is the
gradient of an outgoing-wave potential ``phi = f(t - r/cd)/r`` with
``cd = sqrt((K + 4G/3)/rho0)``.  Self-similarity (displacement homogeneous of
degree one in ``(r, t)``) forces ``f(s) = A s**3`` for ``s > 0`` and ``f = 0``
before the wave arrives.  (``f = A s**2`` gives a displacement of degree zero,
which is not self-similar for a constant-velocity wall.)  With ``x = r/(cd t)``
and the dimensionless amplitude ``b = -A/cd**3``::

    u_disp  = cd t b (1 - x)**2 (1 + 2x) / x**2
    v       = 3 cd b (1 - x**2) / x**2
    sigma_r = b [ 4G/x**3 + (6K - 4G)/x - 6K ]
    sigma_t = b [-2G/x**3 + (6K + 2G)/x - 6K ]
    tau     = 6 G b (1 - x**2) / x**3
    p       = 6 K b (1/x - 1)

Every field vanishes at the wave front ``x = 1``: the front carries no jump, so
the Rankine-Hugoniot condition ``[sigma_r] = rho0 cd [v]`` (compression-positive
stress) is satisfied with zero jumps.

Part 1 (purely elastic) imposes the velocity condition ``v(r = V t) = V`` at
``x = beta = V/cd``, so ``b = beta**3 / (3 (1 - beta**2))`` and::

    sigma_r(wall) = [4G + (6K - 4G) beta**2 - 6K beta**3] / (3 (1 - beta**2)),

which is constant in time.  Validity: small strain requires ``V << cd``.  Even
then, the wall shear is ``tau(wall) = 2G`` for every ``V``, and the wall
displacement is ``u_disp = V t (1 - beta)(1 + 2 beta)/(3 (1 + beta))`` (about a
third of the cavity radius), so the velocity condition on the moving wall is a
formal small-strain idealisation.  As ``V -> 0``, ``sigma_r(wall) -> 4G/3``.

Parts 2-3: plastic zone ``V t <= r <= c t`` (after Forrestal & Luk 1988)
------------------------------------------------------------------------
The elastic solution above holds for ``c t <= r <= cd t``.  Its amplitude ``b``
makes the yield condition hold at ``x_c = c/cd``.  Across the front, ``sigma_r``
and ``v`` are continuous, and the front is not a shock.  Inside the plastic
zone the Eulerian (finite-deformation) equations are used, with ``' = d/dz``::

    momentum : rho (v - z) v' + sigma_r' = -2 tau / z
    mass     : (v - z) rho' + rho (v' + 2 v / z) = 0
    EOS      : p = K (1 - rho0/rho)            (linear in volumetric strain)
    yield    : tau = tau0 + lam p              (EPP / Tresca = von Mises: lam = 0, tau0 = Y)

Because ``sigma_t = sigma_r - tau``, ``p = (sigma_r - 2 tau0/3)/alpha`` with
``alpha = 1 + 2 lam/3``, and ``rho' = rho**2 sigma_r' / (rho0 K alpha)``.  The
linear system for ``(v', sigma_r')`` has the determinant
``D = rho**2 (v - z)**2 / (rho0 K alpha) - 1``, which must stay negative (the
front is subsonic relative to the plastic wave speed).  The system is integrated
from ``z = c`` inward to the wall at ``z = V``.  The front speed ``c`` is found
with ``brentq`` from ``v(V) = V``.  If the elastic wall shear ``2G`` does not
exceed the yield strength at the wall, no plastic zone forms and the elastic
answer is returned.  A shock-free similarity solution exists only while a root
with ``D < 0`` exists.  If none exists, a ``RuntimeError`` is raised (this is
the plastic-shock regime, which is not modelled).

Quasi-static checks: with inertia dropped, ``rho ~ rho0`` in the mass balance and
``v << z`` in the convective term, the plastic zone integrates in closed form.
For EPP this reproduces Hill's compressible result
``p = (2Y/3) [1 + ln(E / (3 (1 - nu) Y))]``.  The Mohr-Coulomb generalisation is
given in :func:`mohr_coulomb_static_wall_stress`.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

__all__ = [
    "dilatational_speed", "elastic_amplitude", "elastic_region_fields",
    "elastic_wall_stress", "elastic_fields", "hill_static_pressure",
    "plastic_solution", "epp_wall_stress", "mohr_coulomb_wall_stress",
    "mohr_coulomb_static_wall_stress",
]


# --------------------------------------------------------------------------- elastic
def dilatational_speed(rho0, K, G):
    """Elastic P-wave speed ``cd = sqrt((K + 4G/3)/rho0)`` [m/s]."""
    return np.sqrt((K + 4.0 * G / 3.0) / rho0)


def elastic_region_fields(x, b, cd, K, G):
    """Outgoing self-similar elastic wave, ``x = r/(cd t)`` in ``(0, 1]``.

    Returns ``(v, sigma_r, sigma_theta)`` (velocity, compression-positive stresses)
    for the dimensionless amplitude ``b`` (see the module docstring).
    """
    x = np.asarray(x, dtype=float)
    v = 3.0 * cd * b * (1.0 - x**2) / x**2
    s_r = b * (4.0 * G / x**3 + (6.0 * K - 4.0 * G) / x - 6.0 * K)
    s_t = b * (-2.0 * G / x**3 + (6.0 * K + 2.0 * G) / x - 6.0 * K)
    return v, s_r, s_t


def elastic_amplitude(V, rho0, K, G):
    """Amplitude ``b = beta^3 / (3 (1 - beta^2))`` from ``v(wall) = V``, ``beta = V/cd``."""
    beta = V / dilatational_speed(rho0, K, G)
    if not 0.0 < beta < 1.0:
        raise ValueError("need 0 < V < cd")
    return beta**3 / (3.0 * (1.0 - beta**2))


def elastic_wall_stress(V, rho0, K, G):
    """Compression-positive radial stress at the cavity wall, linear elasticity [Pa].

    ``sigma_r = [4G + (6K - 4G) beta^2 - 6K beta^3] / (3 (1 - beta^2))``, with
    ``beta = V/cd``.  This is independent of time, and valid only for ``V << cd``.
    """
    beta = V / dilatational_speed(rho0, K, G)
    elastic_amplitude(V, rho0, K, G)  # range check
    return (4.0 * G + (6.0 * K - 4.0 * G) * beta**2 - 6.0 * K * beta**3) / (3.0 * (1.0 - beta**2))


def elastic_fields(xi, V, rho0, K, G, hoop=False):
    """Elastic similarity fields versus ``xi = r/(V t)``, for ``1 <= xi <= cd/V``.

    Returns ``(v, sigma_r)``, or ``(v, sigma_r, sigma_theta)`` if ``hoop``.
    ``v`` is the particle velocity [m/s], and the stresses are compression-positive [Pa].
    """
    cd = dilatational_speed(rho0, K, G)
    out = elastic_region_fields(np.asarray(xi, float) * V / cd,
                                elastic_amplitude(V, rho0, K, G), cd, K, G)
    return out if hoop else out[:2]


# --------------------------------------------------------------------------- plastic
def hill_static_pressure(K, G, Y):
    """Hill's quasi-static pressure for a compressible EPP cavity from zero radius.

    ``p = (2Y/3) [1 + ln(E / (3 (1 - nu) Y))]``, with ``E = 9KG/(3K+G)`` and
    ``nu = (3K - 2G)/(2(3K + G))``.
    """
    E = 9.0 * K * G / (3.0 * K + G)
    nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G))
    return 2.0 * Y / 3.0 * (1.0 + np.log(E / (3.0 * (1.0 - nu) * Y)))


def _integrate_plastic(c, V, rho0, K, G, tau0, lam, dense=False):
    """Integrate the plastic-zone ODEs from the front ``z = c`` down to ``z = V``.

    Returns the ``solve_ivp`` result, or ``None`` if the state is unphysical
    (no admissible elastic amplitude, ``p >= K``, or ``D >= 0``).
    """
    cd, alpha = dilatational_speed(rho0, K, G), 1.0 + 2.0 * lam / 3.0
    x = c / cd
    den = 6.0 * G * (1.0 - x**2) / x**3 - 6.0 * K * lam * (1.0 - x) / x
    if den <= 0.0:
        return None
    v_c, s_c, _ = elastic_region_fields(x, tau0 / den, cd, K, G)

    def state(z, y):
        p = (y[1] - 2.0 * tau0 / 3.0) / alpha
        rho = rho0 / (1.0 - p / K)
        k = rho * (y[0] - z) / (rho0 * K * alpha)        # d(rho)/rho per d(sigma_r), times (v - z)
        return rho, k, rho * (y[0] - z) * k - 1.0, tau0 + lam * p

    def rhs(z, y):
        rho, k, D, tau = state(z, y)
        r1, r2 = -2.0 * tau / z, -2.0 * y[0] / z            # momentum / (mass / rho) right-hand sides
        return [(r1 * k - r2) / D, (rho * (y[0] - z) * r2 - r1) / D]

    def bad(z, y):  # sonic point, or p reaching K
        p = (y[1] - 2.0 * tau0 / 3.0) / alpha
        return min(-state(z, y)[2], 1.0 - p / K) if p < K else -1.0
    bad.terminal = True

    if bad(c, [v_c, s_c]) <= 0.0:
        return None
    sol = solve_ivp(rhs, (c, V), [v_c, s_c], method="DOP853", rtol=1e-11,
                    atol=[1e-13 * V, 1e-9 * tau0], events=bad, dense_output=dense)
    return sol if sol.status == 0 else None


def plastic_solution(V, rho0, K, G, tau0, lam=0.0, dense=False):
    """Solve the elastic/plastic similarity problem (see the module docstring).

    Returns a dict containing ``wall_stress`` [Pa], the front speed ``c`` [m/s]
    (``None`` if the response is purely elastic) and, when ``dense`` is set, the
    ``solve_ivp`` solution ``sol`` with ``y = (v, sigma_r)`` as functions of ``z = r/t``.
    """
    cd = dilatational_speed(rho0, K, G)
    s_el = elastic_wall_stress(V, rho0, K, G)
    p_el = elastic_region_fields(V / cd, elastic_amplitude(V, rho0, K, G), cd, K, G)
    p_el = (p_el[1] + 2.0 * p_el[2]) / 3.0
    if tau0 + lam * p_el >= 2.0 * G:        # elastic wall shear is exactly 2G
        return {"wall_stress": s_el, "c": None, "sol": None}

    def g(c):
        sol = _integrate_plastic(c, V, rho0, K, G, tau0, lam)
        return None if sol is None else sol.y[0, -1] - V

    lo, hi, bad = V * (1.0 + 1e-9), None, None   # g(lo) < 0 because tau0 + lam p < 2G
    for c in np.geomspace(V * 1.01, cd, 200)[:-1]:  # coarse scan for the first g >= 0
        gc = g(c)
        if gc is None:
            bad = c
            break
        if gc >= 0.0:
            hi = c
            break
        lo = c
    for _ in range(200 if hi is None and bad is not None else 0):  # bisect towards validity
        mid = 0.5 * (lo + bad)
        gm = g(mid)
        if gm is None:
            bad = mid
        elif gm < 0.0:
            lo = mid
        else:
            hi = mid
            break
    if hi is None:
        raise RuntimeError("no shock-free similarity solution (plastic-shock regime)")
    c = brentq(g, lo, hi, xtol=1e-12 * V, rtol=1e-13, maxiter=200)
    sol = _integrate_plastic(c, V, rho0, K, G, tau0, lam, dense=dense)
    return {"wall_stress": float(sol.y[1, -1]), "c": c, "sol": sol if dense else None}


def epp_wall_stress(V, rho0, K, G, Y):
    """Wall radial stress [Pa] for compressible elastic-perfectly-plastic material.

    Uses the Tresca (= von Mises) yield condition ``sigma_r - sigma_theta = Y``
    and a plastic zone with bulk modulus ``K`` (Forrestal & Luk 1988, option b).
    As ``V -> 0`` the result tends to :func:`hill_static_pressure`.  For
    ``Y >= 2G`` it equals :func:`elastic_wall_stress`.
    """
    return plastic_solution(V, rho0, K, G, Y, 0.0)["wall_stress"]


def mohr_coulomb_wall_stress(V, rho0, K, G, tau0, lam):
    """Wall radial stress [Pa] for a pressure-dependent (Mohr-Coulomb type) solid.

    The model is ``sigma_r - sigma_theta = tau0 + lam p`` in the plastic zone,
    with ``p = K (1 - rho0/rho)`` and linear elasticity ahead of it.  This is
    Forrestal & Tzou (1997) without the cracked region, the tension cutoff or
    the locking (comminuted) behaviour.
    """
    return plastic_solution(V, rho0, K, G, tau0, lam)["wall_stress"]


def mohr_coulomb_static_wall_stress(K, G, tau0, lam):
    """Quasi-static limit (V -> 0) of :func:`mohr_coulomb_wall_stress`, Hill-type closed form.

    At the front: ``tau = tau0``, ``sigma_r = 2 tau0/3`` and ``v = tau0 c/(2G)``.
    In the plastic zone: ``tau0 + lam sigma_r = alpha tau0 (c/r)^n``, with
    ``n = 2 lam/alpha``.  Volume balance, with ``rho ~ rho0`` and ``v << r``,
    gives ``q = c/a`` from
    ``1 = tau0 q^3/(2G) + 2 tau0 (q^3 - q^n) / (alpha K (3 - n))``.
    Then ``sigma_r(wall) = tau0 (alpha q^n - 1)/lam``, which tends to Hill's formula as ``lam -> 0``.
    """
    alpha = 1.0 + 2.0 * lam / 3.0
    n = 2.0 * lam / alpha
    f = lambda q: tau0 * q**3 / (2 * G) + 2 * tau0 * (q**3 - q**n) / (alpha * K * (3 - n)) - 1
    q = brentq(f, 1.0, 1e6)
    if lam == 0.0:
        return 2.0 * tau0 / 3.0 + 2.0 * tau0 * np.log(q)
    return tau0 * (alpha * q**n - 1.0) / lam
