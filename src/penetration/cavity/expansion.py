"""Dynamic spherical cavity expansion at constant wall velocity (1-D Lagrangian).

The target is meshed by Lagrangian spherical shells (staggered grid: node
velocities, cell stresses, von Neumann-Richtmyer time stepping with a
quadratic plus linear artificial viscosity). The wall node moves outwards at
the prescribed velocity V. A cavity opened from zero radius at constant V is
self-similar in xi = r/a (a the wall radius), so the steady wall stress is
reached by cycles: expand from a0 to k a0, then map every field back onto
the initial mesh as a function of xi (the similarity remap) and repeat until
the wall stress changes by less than a tolerance between cycles. Within a
cycle the mesh is purely Lagrangian; the remap keeps the zones near the
wall from being crushed without end.

Materials (``kind``): 0 elastic (K, G; p = K (1 - rho0/rho)); 1 elastic-perfectly-plastic
(K, G, Y); 2 linear Mohr-Coulomb |sigma_r - sigma_theta| = tau0 + lam p,
capped at Ymax, elastic K, G; 3 HJC (penetration.concrete.hjc). Stresses are
tension positive inside; the reported wall stress is compression positive.
Strain rates use the physical scale set by ``radius`` (the wall reaches that
radius at the end of each cycle), as the HJC rate term needs one.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..concrete.hjc import (HJC, I_DAMAGE, I_G, I_HOOP, I_K1, I_K2, I_K3, I_KE, I_MULOCK, I_T, eos, fracture_strain,
                            unloading_modulus, yield_stress)

ELASTIC, EPP, MOHR_COULOMB, HJC_KIND = 0, 1, 2, 3


@dataclass(frozen=True)
class Simple:
    """Elastic (Y = inf), elastic-perfectly-plastic or linear Mohr-Coulomb solid."""
    rho0: float
    K: float
    G: float
    Y: float = math.inf
    lam: float = 0.0
    Ymax: float = math.inf

    @property
    def kind(self):
        if self.lam > 0:
            return MOHR_COULOMB
        return ELASTIC if math.isinf(self.Y) else EPP

    def as_array(self):
        return np.array([self.rho0, self.G, self.K, min(self.Y, 1e300), self.lam, min(self.Ymax, 1e300)], float)

    @property
    def wave_speed(self):
        return math.sqrt((self.K + 4 * self.G / 3) / self.rho0)


@dataclass(frozen=True)
class Mesh:
    """Initial mesh in xi = r/a0: geometric zones (size proportional to r) from the wall to xi_max.

    xi_max = 0 places the far boundary beyond the elastic front at the end of
    a cycle (margin times k c/V), but never further than ``cap`` times k: at
    low V the far field responds quasi-statically and a fixed boundary at
    r/a >= cap costs little accuracy (see the far-boundary study).
    """
    zones: int = 160
    xi_max: float = 0.0
    margin: float = 1.5
    cap: float = 40.0


@dataclass(frozen=True)
class Controls:
    cycle_ratio: float = 2.0  # k: the wall radius grows by this factor per cycle
    max_cycles: int = 30
    tol: float = 1e-4
    cfl: float = 0.5
    q_quad: float = 1.5
    q_lin: float = 0.06
    quasi_static_from: tuple = (50.0, 100.0)  # rate-free runs behind the v = 0 node of a sigma_n table (m/s)


@dataclass
class Result:
    wall_stress: float
    history: list = field(default_factory=list)
    cycles: int = 0
    steps: int = 0
    converged: bool = False
    profile: dict = field(default_factory=dict)


def material_of(model):
    if isinstance(model, HJC):
        return HJC_KIND, model.as_array(), model.rho0, math.sqrt((model.k1 + 4 * model.G / 3) / model.rho0)
    return model.kind, model.as_array(), model.rho0, model.wave_speed


# ------------------------------------------------------------------ kernel
@njit(cache=True, inline="always")
def _stress_update(kind, q, j, mu, de_r, de_v, rate, sr, p, mumax, mup, dmg, eps):
    """Update deviatoric s_r (s_theta = -s_r/2), pressure and history of cell j."""
    if kind == HJC_KIND:
        G = q[I_G]
    else:
        G = q[1]
    sr[j] += 2.0 * G * (de_r - de_v / 3.0)
    if kind == HJC_KIND:
        pn, mumax[j], mup_new = eos(mu, mumax[j], q)
        pn = max(pn, -q[I_T] * (1.0 - dmg[j]))
        sy = yield_stress(pn, dmg[j], eps[j], rate, q)
    else:
        pn = q[2] * mu / (1.0 + mu)  # K (1 - rho0/rho), the Forrestal-Luk equation of state
        mup_new = 0.0
        if kind == ELASTIC:
            sy = 1e300
        elif kind == EPP:
            sy = q[3]
        else:
            sy = min(max(q[3] + q[4] * pn, 0.0), q[5])
    seq = 1.5 * abs(sr[j])
    dep = 0.0
    if seq > sy:
        dep = (seq - sy) / (3.0 * G)
        sr[j] *= sy / seq
    if kind == HJC_KIND and q[I_HOOP] > 0.5:
        # radial cracking: hoop stress -p - s_r/2 <= T (1 - D), returned at fixed pressure
        floor = -2.0 * (pn + q[I_T] * (1.0 - dmg[j]))
        if sr[j] < floor:
            dep += 1.5 * (floor - sr[j]) / (3.0 * G)
            sr[j] = floor
    eps[j] += dep
    if kind == HJC_KIND:
        dmu = max(mup_new - mup[j], 0.0)
        mup[j] = mup_new
        if q[I_DAMAGE] > 0.5:
            dmg[j] = min(1.0, dmg[j] + (dep + dmu) / fracture_strain(pn, q))
        pn = max(pn, -q[I_T] * (1.0 - dmg[j]))
    p[j] = pn


@njit(cache=True)
def _sound_speed(kind, q, mu, mumax, rho):
    if kind == HJC_KIND:
        K = max(q[I_KE], unloading_modulus(mumax, q))
        mb = mu - q[I_MULOCK]
        if mb > 0:
            K = max(K, q[I_K1] + 2 * q[I_K2] * mb + 3 * q[I_K3] * mb * mb)
        return math.sqrt((K + 4.0 * q[I_G] / 3.0) / rho)
    return math.sqrt((q[2] + 4.0 * q[1] / 3.0) / rho)


@njit(cache=True, nogil=True)
def _cycle(kind, q, rho0, V, r, u, mass, sr, p, mumax, mup, dmg, eps, a_end, cfl, cq, cl):
    """Lagrangian expansion until the wall node reaches a_end.

    Returns (time-averaged wall stress over the second half, steps).
    """
    n = r.size - 1
    rho = np.empty(n)
    sig_r = np.empty(n)
    sig_t = np.empty(n)
    qv = np.zeros(n)
    for j in range(n):
        rho[j] = mass[j] / ((r[j + 1] ** 3 - r[j] ** 3) / 3.0)
    a_start = r[0]
    steps = 0
    acc_w, acc_t = 0.0, 0.0
    while r[0] < a_end:
        dt = 1e300
        for j in range(n):
            dr = r[j + 1] - r[j]
            c = _sound_speed(kind, q, rho[j] / rho0 - 1.0, mumax[j], rho[j])
            dt = min(dt, cfl * dr / (c + 2.0 * (cq * cq) * abs(min(u[j + 1] - u[j], 0.0)) + 1e-30))
        dt = min(dt, (a_end - r[0]) / V + 1e-15)
        for j in range(n):
            sig_r[j] = -(p[j] + qv[j]) + sr[j]
            sig_t[j] = -(p[j] + qv[j]) - 0.5 * sr[j]
        for i in range(1, n):
            dl, dr_ = r[i] - r[i - 1], r[i + 1] - r[i]
            rbar = (rho[i - 1] * dl + rho[i] * dr_) / (dl + dr_)
            grad = (sig_r[i] - sig_r[i - 1]) / (0.5 * (dl + dr_))
            hoop = (sig_r[i] - sig_t[i] + sig_r[i - 1] - sig_t[i - 1]) / r[i]
            u[i] += dt * (grad + hoop) / rbar
        u[0] = V
        u[n] = 0.0
        for i in range(n + 1):
            r[i] += dt * u[i]
        for j in range(n):
            vol = (r[j + 1] ** 3 - r[j] ** 3) / 3.0
            rho_new = mass[j] / vol
            dr = r[j + 1] - r[j]
            du = u[j + 1] - u[j]
            de_r = du / dr * dt
            de_v = math.log(rho[j] / rho_new)  # exact volume change; the hoop strain follows from it
            rate = abs(de_r - de_v / 3.0) / dt
            rho[j] = rho_new
            _stress_update(kind, q, j, rho_new / rho0 - 1.0, de_r, de_v, rate, sr, p, mumax, mup, dmg, eps)
            if du < 0.0:
                c = _sound_speed(kind, q, rho_new / rho0 - 1.0, mumax[j], rho_new)
                qv[j] = rho_new * (cq * cq * du * du + cl * c * abs(du))
            else:
                qv[j] = 0.0
        steps += 1
        if r[0] > 0.5 * (a_start + a_end):
            acc_w += dt * ((p[0] + qv[0]) - sr[0])
            acc_t += dt
    return acc_w / max(acc_t, 1e-300), steps


# ------------------------------------------------------------- the driver
def _initial_mesh(mesh: Mesh, xi_max, a0):
    x = np.geomspace(1.0, xi_max, mesh.zones + 1)
    return a0 * x


def _remap(r_old, a_old, fields_cell, u_node, r_new, a_new):
    """Fields as functions of xi = r/a, interpolated onto the new mesh."""
    xo = r_old / a_old
    xn = r_new / a_new
    co = 0.5 * (xo[1:] + xo[:-1])
    cn = 0.5 * (xn[1:] + xn[:-1])
    cells = [np.interp(cn, co, f) for f in fields_cell]
    return cells, np.interp(xn, xo, u_node)


FIELDS = ("rho", "s_r", "p", "mu_max", "mu_p", "D", "eps_p")


def expand(model, V, radius=0.07, mesh: Mesh = Mesh(), controls: Controls = Controls(), start=None) -> Result:
    """Steady radial stress on a cavity wall expanding at V in ``model``.

    ``start``: the ``profile`` of an earlier result (e.g. at a nearby
    velocity) to begin from, which saves cycles; velocities are scaled by V.
    """
    if not V > 0:
        raise ValueError(f"cavity wall velocity V = {V} is not allowed: V > 0 m/s")
    kind, q, rho0, c = material_of(model)
    k = controls.cycle_ratio
    xi_max = mesh.xi_max or k * min(mesh.margin * max(c / V, 2.0), mesh.cap)
    a0 = radius / k
    r = _initial_mesh(mesh, xi_max, a0)
    n = mesh.zones
    u = np.zeros(n + 1)
    u[0] = V
    rho = np.full(n, rho0)
    sr, p, mumax, mup, dmg, eps = (np.zeros(n) for _ in range(6))
    if start is not None:
        xc = 0.5 * (r[1:] + r[:-1]) / a0
        ahead = {f: 0.0 for f in FIELDS}
        ahead["rho"] = rho0  # undisturbed beyond the old profile
        rho, sr, p, mumax, mup, dmg, eps = (np.interp(xc, start["xi"], start[f], right=ahead[f]) for f in FIELDS)
        u = np.interp(r / a0, start["xi_node"], start["u_over_V"] * V, right=0.0)
        u[0] = V
    res = Result(float("nan"))
    for cycle in range(controls.max_cycles):
        mass = rho * (r[1:] ** 3 - r[:-1] ** 3) / 3.0
        w, steps = _cycle(kind, q, rho0, V, r, u, mass, sr, p, mumax, mup, dmg, eps, radius, controls.cfl,
                          controls.q_quad, controls.q_lin)
        res.steps += steps
        res.history.append(w)
        rho = mass / ((r[1:] ** 3 - r[:-1] ** 3) / 3.0)
        if cycle > 0 and abs(w - res.history[-2]) <= controls.tol * abs(w):
            res.converged = True
            break
        r_new = _initial_mesh(mesh, xi_max, a0)
        (rho, sr, p, mumax, mup, dmg, eps), u = _remap(r, r[0], (rho, sr, p, mumax, mup, dmg, eps), u, r_new, a0)
        u = u.copy()
        u[0] = V
        r = r_new
    res.wall_stress = res.history[-1]
    res.cycles = len(res.history)
    res.profile = {"xi": 0.5 * (r[1:] + r[:-1]) / r[0], "rho": rho, "p": p, "s_r": sr, "D": dmg, "mu_max": mumax,
                   "mu_p": mup, "eps_p": eps, "xi_node": r / r[0], "u_over_V": u / V}
    return res


def stress_table(model, velocities, radius=0.07, mesh: Mesh = Mesh(), controls: Controls = Controls(), workers=2,
                 starts=None):
    """Steady wall stress at each velocity (Pa).

    Velocities are dealt to ``workers`` threads (the kernel releases the
    GIL); each thread walks its share from fast to slow, starting every run
    from the previous converged profile, or from ``starts[v]`` (a profile
    per velocity) when given.
    """
    from concurrent.futures import ThreadPoolExecutor
    vs = sorted((float(v) for v in velocities), reverse=True)
    chains = [vs[i::workers] for i in range(workers)]

    def walk(chain):
        out, prev = {}, None
        for v in chain:
            res = expand(model, v, radius, mesh, controls, start=starts.get(v, prev) if starts else prev)
            out[v], prev = res, res.profile
        return out

    with ThreadPoolExecutor(max_workers=workers) as pool:
        done = {}
        for part in pool.map(walk, chains):
            done.update(part)
    results = [done[float(v)] for v in velocities]
    return np.array([r.wall_stress for r in results]), results


def single_expansion(model, V, a0, a_end, xi_max=50.0, zones=400, controls: Controls = Controls()):
    """One Lagrangian expansion of a cavity of initial radius a0 to a_end (no remap).

    Returns the wall stress (compression positive) averaged over the second
    half of the run; used to check the solver against exact small-strain
    solutions for a finite initial cavity.
    """
    kind, q, rho0, _ = material_of(model)
    r = a0 * np.geomspace(1.0, xi_max, zones + 1)
    u = np.zeros(zones + 1)
    u[0] = V
    mass = rho0 * (r[1:] ** 3 - r[:-1] ** 3) / 3.0
    state = [np.zeros(zones) for _ in range(6)]
    w, _ = _cycle(kind, q, rho0, V, r, u, mass, *state, a_end, controls.cfl, controls.q_quad, controls.q_lin)
    return w
