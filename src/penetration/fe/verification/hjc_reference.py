"""An independent Holmquist-Johnson-Cook (1993) point model, the reference of the FE level's HJC checks.

Written from the model's equations (Holmquist, Johnson & Cook 1993; the paper's Eqs 12-18; the conventions the
module docstring of ``penetration.concrete.hjc`` states where published codes differ), not from ``penetration.concrete.hjc``: it
shares no function, parameter layout or root finder with it, so that a wrong branch in either shows as a
difference. It reads the constants of an ``hjc.HJC`` (data only) and supports the conventions the FE level runs
with: ``lock="offset"``, ``tension="openradioss"``, the rate floor, damage on or off, no erosion strain, no hoop
cut-off; any other setting is refused.

Equations (pressure p and mu = rho/rho0 - 1 positive in compression, stresses positive in tension):

- equation of state: p = Ke mu up to (mu_c, p_c), Ke = p_c/mu_c; the crush line to (mu_l, p_l); beyond mu_l the
  fully dense curve K1 m + K2 m^2 + K3 m^3, m = (mu - mu_lock)/(1 + mu_lock), with mu_lock placing the curve
  through (mu_l, p_l) ("offset"). Below the largest mu reached, mu_max: elastic (Ke) if mu_max <= mu_c, the line
  of slope (1 - F) Ke + F K1, F = (mu_max - mu_c)/(mu_l - mu_c), through the crush point if mu_max is on the
  crush line, the dense curve (K1 m in tension) if beyond it; the crush strain left at zero pressure is
  mu_p = mu* - p(mu*)/K_u(mu*), mu* = min(mu_max, mu_l). Tension cut-off p >= -T (1 - D).
- strength: sigma_y = fc min(Smax, [A (1 - D) + B P*^N] (1 + C ln eps*)) for P* = p/fc >= 0, and
  fc A (1 + p/T)(1 - D)(1 + C ln eps*) (not below 0) in tension; eps* = max(rate/eps0, 1).
- plastic flow: radial return of the trial deviator at fixed pressure, d eps_p = (sigma_eq - sigma_y)/(3 G).
- damage: D += (d eps_p + d mu_p)/max(EFMIN, D1 (P* + T*)^D2), at most 1; the cut-off applied again with it.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

# the reference's own layout of the constants
(RHO0, SHEAR, A_, B_, C_, N_, FC, T_, EPS0, EFMIN, SMAX, PC, MUC, PL, MUL, D1, D2, K1, K2, K3, KE, MULOCK,
 DAMAGE) = range(23)


def constants(material) -> np.ndarray:
    """The constants of an hjc.HJC in this module's layout (its conventions checked)."""
    m = material
    if (m.lock, m.tension, m.rate_floor, m.strength_scale, m.hoop_cutoff, m.rate_law) != (
            "offset", "openradioss", True, 1.0, False, "hjc") or math.isfinite(m.erosion_strain):
        raise ValueError("hjc_reference supports lock='offset', tension='openradioss', the rate floor, strength_scale 1, "
                         "no hoop cut-off, HJC's rate law and no erosion strain")
    roots = np.roots([m.k3, m.k2, m.k1, -m.pl])   # the dense curve reaches p_l at m = x
    x = min(r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0)
    k = np.zeros(23)
    for slot, value in ((RHO0, m.rho0), (SHEAR, m.G), (A_, m.A), (B_, m.B), (C_, m.C if m.rate else 0.0), (N_, m.N),
                        (FC, m.fc), (T_, m.T), (EPS0, m.eps0), (EFMIN, m.efmin), (SMAX, m.smax), (PC, m.pc),
                        (MUC, m.muc), (PL, m.pl), (MUL, m.mul), (D1, m.D1), (D2, m.D2), (K1, m.k1), (K2, m.k2),
                        (K3, m.k3), (KE, m.pc / m.muc), (MULOCK, (m.mul - x) / (1.0 + x)), (DAMAGE, float(m.damage))):
        k[slot] = value
    return k


@njit(cache=True)
def virgin_pressure(mu, k):
    """Loading curve p(mu): elastic, crush line, fully dense (paper Eqs 12, 13, 15)."""
    if mu <= k[MUC]:
        return k[KE] * mu
    if mu <= k[MUL]:
        return k[PC] + (k[PL] - k[PC]) / (k[MUL] - k[MUC]) * (mu - k[MUC])
    m = (mu - k[MULOCK]) / (1.0 + k[MULOCK])
    return m * (k[K1] + m * (k[K2] + m * k[K3]))


@njit(cache=True)
def unloading_slope(mu_max, k):
    """(1 - F) Ke + F K1, F the crushed share of the crush line (paper Eq 14)."""
    F = (mu_max - k[MUC]) / (k[MUL] - k[MUC])
    F = 0.0 if F < 0.0 else (1.0 if F > 1.0 else F)
    return k[KE] + F * (k[K1] - k[KE])


@njit(cache=True)
def pressure(mu, mu_max, k):
    """Pressure at mu after the largest compression mu_max (before the tension cut-off)."""
    if mu >= mu_max:
        return virgin_pressure(mu, k)
    if mu_max <= k[MUC]:
        return k[KE] * mu
    if mu_max <= k[MUL]:
        return virgin_pressure(mu_max, k) - unloading_slope(mu_max, k) * (mu_max - mu)
    m = (mu - k[MULOCK]) / (1.0 + k[MULOCK])
    return k[K1] * m if m < 0.0 else m * (k[K1] + m * (k[K2] + m * k[K3]))


@njit(cache=True)
def crush_strain(mu_max, k):
    """Permanent volumetric strain left at zero pressure after mu_max."""
    if mu_max <= k[MUC]:
        return 0.0
    m = min(mu_max, k[MUL])
    return m - virgin_pressure(m, k) / unloading_slope(m, k)


@njit(cache=True)
def yield_strength(p, D, rate, k):
    """sigma_y (Pa) at pressure p, damage D and equivalent strain rate (paper Eq 16, linear in tension)."""
    factor = 1.0 + k[C_] * math.log(max(rate / k[EPS0], 1.0))
    if p >= 0.0:
        s = k[A_] * (1.0 - D) + k[B_] * (p / k[FC]) ** k[N_]
    else:
        s = max(k[A_] * (1.0 + p / k[T_]) * (1.0 - D), 0.0)
    return k[FC] * min(k[SMAX], s * factor)


@njit(cache=True)
def failure_strain(p, k):
    """eps_p^f + mu_p^f = max(EFMIN, D1 (P* + T*)^D2) (paper Eq 18), EFMIN where P* + T* <= 0."""
    x = (p + k[T_]) / k[FC]
    return k[EFMIN] if x <= 0.0 else max(k[EFMIN], k[D1] * x ** k[D2])


@njit(cache=True)
def update(s, state, de, mu, rate, k):
    """One increment of a material point: s the deviator (rr, zz, tt, rz; tensor shear) updated in place; state
    = [p, mu_max, mu_p, D, eps_p] updated in place; de the strain increment (rr, zz, tt, rz); mu the new
    volumetric strain; rate the equivalent deviatoric strain rate."""
    G = k[SHEAR]
    mean = (de[0] + de[1] + de[2]) / 3.0
    for i in range(3):
        s[i] += 2.0 * G * (de[i] - mean)
    s[3] += 2.0 * G * de[3]
    mu_max = max(state[1], mu)
    p = max(pressure(mu, state[1], k), -k[T_] * (1.0 - state[3]))
    seq = math.sqrt(1.5 * (s[0] ** 2 + s[1] ** 2 + s[2] ** 2 + 2.0 * s[3] ** 2))
    sy = yield_strength(p, state[3], rate, k)
    dep = 0.0
    if seq > sy:
        dep = (seq - sy) / (3.0 * G)
        for i in range(4):
            s[i] *= sy / seq
    mu_p = crush_strain(mu_max, k)
    D = state[3]
    if k[DAMAGE] > 0.5:
        D = min(1.0, D + (dep + max(mu_p - state[2], 0.0)) / failure_strain(p, k))
    state[0] = max(p, -k[T_] * (1.0 - D))
    state[1], state[2], state[3], state[4] = mu_max, mu_p, D, state[4] + dep


def homogeneous_path(material, stretch_r, stretch_z, times, D0=0.0):
    """A material point through a homogeneous axisymmetric stretch history (lambda_r = lambda_theta, lambda_z at
    ``times``): log-strain increments between the samples, the rate from them. Returns p, mu, the equivalent
    stress and D at every sample (the first one the initial state)."""
    k = constants(material)
    s, state = np.zeros(4), np.array([0.0, 0.0, 0.0, D0, 0.0])
    out = {key: [0.0] for key in ("p", "mu", "seq")}
    out["D"] = [D0]
    for n in range(1, len(times)):
        dr = math.log(stretch_r[n] / stretch_r[n - 1])
        dz = math.log(stretch_z[n] / stretch_z[n - 1])
        de = np.array([dr, dz, dr, 0.0])
        mu = 1.0 / (stretch_r[n] ** 2 * stretch_z[n]) - 1.0
        rate = abs(dz - dr) * 2.0 / 3.0 / (times[n] - times[n - 1])   # sqrt(2/3 dev:dev) of this stretch
        update(s, state, de, mu, rate, k)
        for key, value in (("p", state[0]), ("mu", mu), ("D", state[3]),
                           ("seq", math.sqrt(1.5 * (s[0] ** 2 + s[1] ** 2 + s[2] ** 2)))):
            out[key].append(value)
    return {key: np.array(v) for key, v in out.items()}
