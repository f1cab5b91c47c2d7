"""Rigid-projectile trajectory: m dv/dt = -sum(effect.force(z, v)).

The scene lists the effects; ``assemble`` turns the names into effect
objects and an effect that is not listed is never evaluated. The state is
integrated piecewise between the depths where some effect's force is not
smooth (crater end, nose fully embedded, end of the free-surface ramp), so
an explicit Runge-Kutta method keeps its order, and stops at v = 0.

Effects (force in N, resisting, z depth of the nose tip, v velocity):
- crater: F = c z for z < 4a (Eq 8), c from continuity with Eq 7 at 4a;
  the other resistance effects start at z = 4a;
- static: S fc times the loaded projected area (pi a^2 once embedded);
- inertial: rho V^2 times pi a^2 N*(wetted) (Eq 7);
- nose_entry: only the wetted part of the nose (x <= z) loads;
- friction: mu times the normal stress on the wetted surface, axially;
- free_surface_ramp: the static term grows linearly from 0 at the surface to
  full at ``ramp_depth`` (loss of confinement near the free face).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from .geometry import ParameterError
from .nstar import cumulative_nstar
from .resistance import NoseSurface, Target, crater_coefficient, forrestal_stress, nose_force, nose_surface

EFFECTS = ("crater", "nose_entry", "static", "inertial", "friction", "free_surface_ramp", "cavity")


@dataclass(frozen=True)
class Wetted:
    """Projected area and a^2 N* of the part of the nose with x <= z."""
    z: np.ndarray
    area: np.ndarray
    nstar_area: np.ndarray
    full_area: float
    full_nstar_area: float

    def at(self, z):
        if z >= self.z[-1]:
            return self.full_area, self.full_nstar_area
        return float(np.interp(z, self.z, self.area)), float(np.interp(z, self.z, self.nstar_area))


def wetted(nose, nstar, embed: bool, n=400) -> Wetted:
    full = math.pi * nose.radius**2
    if not embed:
        return Wetted(np.array([0.0]), np.array([full]), np.array([full * nstar]), full, full * nstar)
    x, y, cum = cumulative_nstar(nose, n)
    keep = np.concatenate((np.diff(x) > 0, [True]))  # last point of a vertical face
    return Wetted(x[keep], math.pi * y[keep] ** 2, full * cum[keep], full, full * nstar)


@dataclass(frozen=True)
class Crater:
    c: float
    depth: float

    def force(self, z, v):
        return self.c * z if z < self.depth else 0.0


@dataclass(frozen=True)
class Static:
    R: float
    wet: Wetted
    start: float = 0.0

    def force(self, z, v):
        return self.R * self.wet.at(z - self.start)[0] if z >= self.start else 0.0


@dataclass(frozen=True)
class Inertial:
    rho: float
    wet: Wetted
    start: float = 0.0

    def force(self, z, v):
        return self.rho * v * v * self.wet.at(z - self.start)[1] if z >= self.start else 0.0


@dataclass(frozen=True)
class SurfaceLoad:
    """sigma_n(v_n) integrated over the (wetted) nose surface, Eq 2.

    With ``normal`` it is the whole surface force (the cavity level's
    tabulated law, friction coefficient ``mu`` included); without, only the
    friction share mu sigma_n (the ``friction`` effect beside Eq 7's terms).
    """
    surface: NoseSurface
    sigma_n: object
    mu: float
    embed: bool
    start: float = 0.0
    normal: bool = True

    def force(self, z, v):
        if z < self.start:
            return 0.0
        depth = z - self.start if self.embed else None
        return nose_force(self.surface, v, self.sigma_n, self.mu, depth, self.normal)


@dataclass(frozen=True)
class FreeSurfaceRamp:
    """Negative correction: -R A(z) (1 - z/depth) for z < depth."""
    R: float
    wet: Wetted
    depth: float
    start: float = 0.0

    def force(self, z, v):
        if z < self.start or z >= self.start + self.depth:
            return 0.0
        s = z - self.start
        return -self.R * self.wet.at(s)[0] * (1.0 - s / self.depth)


def cavity_crater_coefficient(mass, radius, vs, full_force):
    """c of the crater law F = c z for a general force law F(V) on the embedded nose.

    Continuity at z = 4a: c 4a = F(V1) with V1^2 = vs^2 - 16 a^2 c / m (Eq 8's
    construction); if even F(0) stops the shot inside the crater, c = F(0)/4a.
    """
    from scipy.optimize import brentq
    g = lambda v1: v1 * v1 - vs * vs + 4 * radius * full_force(v1) / mass
    if g(0.0) >= 0:
        return full_force(0.0) / (4 * radius)
    v1 = brentq(g, 0.0, vs, xtol=1e-12)
    return full_force(v1) / (4 * radius)


@dataclass(frozen=True)
class Assembly:
    """The effects of a scene and the depths where the force is not smooth."""
    effects: tuple
    breaks: tuple = field(default=())


def assemble(names, nose, nstar, mass, target: Target, vs, mu=0.0, ramp_depth=None, sigma_n=None) -> Assembly:
    """Effect objects for the listed effect names (see module docstring).

    ``cavity`` integrates the tabulated ``sigma_n(v_n)`` of the cavity-expansion
    level over the nose (friction included when ``friction`` is listed) and
    replaces ``static`` and ``inertial``.
    """
    unknown = [n for n in names if n not in EFFECTS]
    if unknown:
        raise ParameterError("scene", "effects", unknown, f"names among {list(EFFECTS)}")
    if "crater" in names and ({"nose_entry", "free_surface_ramp"} & set(names)):
        raise ParameterError("scene", "effects", list(names),
                             "crater replaces the entry model: not together with nose_entry or free_surface_ramp")
    a = nose.radius
    embed = "nose_entry" in names
    if "cavity" in names:
        return _assemble_cavity(names, nose, mass, vs, mu, sigma_n, embed)
    wet = wetted(nose, nstar, embed)
    start, effects, breaks = 0.0, [], []
    if "crater" in names:
        start = 4 * a
        effects.append(Crater(float(crater_coefficient(mass, a, nstar, target, vs)), start))
        breaks.append(start)
    if embed:
        breaks.append(start + nose.length)
    if "static" in names:
        effects.append(Static(target.R, wet, start))
    if "inertial" in names:
        effects.append(Inertial(target.rho, wet, start))
    if "friction" in names and mu > 0:
        effects.append(SurfaceLoad(nose_surface(nose), forrestal_stress(target), mu, embed, start, normal=False))
    if "free_surface_ramp" in names:
        depth = 4 * a if ramp_depth is None else ramp_depth
        effects.append(FreeSurfaceRamp(target.R, wet, depth, start))
        breaks.append(start + depth)
    return Assembly(tuple(effects), tuple(sorted(set(breaks))))


def _assemble_cavity(names, nose, mass, vs, mu, sigma_n, embed):
    if sigma_n is None:
        raise ParameterError("scene", "level", "cavity", "a sigma_n(v) table for the cavity effect")
    if {"static", "inertial", "free_surface_ramp"} & set(names):
        raise ParameterError("scene", "effects", list(names), "cavity replaces static, inertial and the ramp")
    surface = nose_surface(nose)
    friction = mu if "friction" in names else 0.0
    effects, breaks, start = [], [], 0.0
    if "crater" in names:
        start = 4 * nose.radius
        full = lambda v: nose_force(surface, v, sigma_n, friction)
        effects.append(Crater(float(cavity_crater_coefficient(mass, nose.radius, vs, full)), start))
        breaks.append(start)
    if embed:
        breaks.append(start + nose.length)
    effects.append(SurfaceLoad(surface, sigma_n, friction, embed, start))
    return Assembly(tuple(effects), tuple(sorted(set(breaks))))


@dataclass(frozen=True)
class Trajectory:
    t: np.ndarray
    z: np.ndarray
    v: np.ndarray
    deceleration: np.ndarray
    work: float
    depth: float
    duration: float
    evaluations: int


def integrate(assembly: Assembly, mass, vs, rtol=1e-8, samples=200, method="DOP853", t_max=10.0):
    """Integrate from impact (z = 0, v = vs) until the projectile stops.

    Returns sampled histories (``samples`` points per smooth piece), the final
    depth, the duration, and the work of the resisting force (integrated as
    an extra state, for the energy check W = m vs^2 / 2).
    """
    effects = assembly.effects
    if vs <= 0 or mass <= 0:
        raise ParameterError("shot", "vs" if vs <= 0 else "mass", vs if vs <= 0 else mass, "> 0")

    def force(z, v):
        return sum(e.force(z, v) for e in effects)

    def rhs(t, s):
        f = force(s[0], s[1])
        return (s[1], -f / mass, f * s[1])

    stop = lambda t, s: s[1]
    stop.terminal, stop.direction = True, -1
    state, t0, pieces, nfev = np.array([0.0, float(vs), 0.0]), 0.0, [], 0
    for end in list(assembly.breaks) + [math.inf]:
        if state[1] <= 0:
            break
        events = [stop]
        if math.isfinite(end):
            reach = lambda t, s, e=end: s[0] - e
            reach.terminal, reach.direction = True, 1
            events.append(reach)
        sol = solve_ivp(rhs, (t0, t_max), state, method=method, rtol=rtol, atol=[1e-12, 1e-9, 1e-9],
                        events=events, dense_output=True)
        nfev += sol.nfev
        t1 = sol.t[-1]
        ts = np.linspace(t0, t1, samples)
        ys = sol.sol(ts)
        pieces.append((ts, ys))
        state, t0 = sol.y[:, -1].copy(), t1
        if sol.status == 1 and sol.t_events[0].size:
            state[1] = 0.0
            break
        if sol.status == 0:
            raise RuntimeError(f"projectile still moving after {t_max} s (v = {state[1]:.3g} m/s)")
    t = np.concatenate([p[0] for p in pieces])
    z, v = (np.concatenate([p[1][i] for p in pieces]) for i in (0, 1))
    v = np.maximum(v, 0.0)
    decel = np.array([force(zi, vi) for zi, vi in zip(z, v)]) / mass
    return Trajectory(t, z, v, decel, float(state[2]), float(state[0]), float(t0), nfev)
