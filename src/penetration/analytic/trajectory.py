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
from functools import cached_property

import numpy as np

from ..errors import ParameterError
from ..nose.nstar import cumulative_nstar
from .resistance import NoseSurface, Target, crater_coefficient, forrestal_stress, nose_force, nose_surface


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


@dataclass(frozen=True)
class Shot:
    """What an effect is built from: the nose, the shot, the target's law and the listed effect names.

    ``target`` (Eq 7's S fc and rho) is needed only by the Eq 7 effects and
    ``sigma_n`` (a tabulated normal-stress law) only by ``cavity``; an effect
    that needs one that is missing is an error, never a placeholder.
    """
    names: frozenset
    nose: object
    nstar: float
    mass: float
    vs: float
    target: Target | None = None
    mu: float = 0.0
    ramp_depth: float | None = None
    sigma_n: object = None

    @property
    def start(self):
        """Depth where the tunnel law starts: 4a after a crater, else the surface."""
        return 4 * self.nose.radius if "crater" in self.names else 0.0

    @property
    def embed(self):
        return "nose_entry" in self.names

    @property
    def friction(self):
        return self.mu if "friction" in self.names else 0.0

    @cached_property
    def wetted(self):
        return wetted(self.nose, self.nstar, self.embed)

    def needs(self, what, by):
        if getattr(self, what) is None:
            law = "a target (rho, fc, S)" if what == "target" else "a sigma_n(v) table"
            raise ParameterError("scene", "effects", by, f"{by} needs {law}, which this level does not give")
        return getattr(self, what)


# Effect name -> builder(shot) returning (force objects, break depths). Registered in
# the order their forces are summed; assembly loops over this registry.
EFFECTS = {}
# Effects that cannot be listed together with the key effect.
EXCLUDES = {"crater": {"nose_entry", "free_surface_ramp"}, "cavity": {"static", "inertial", "free_surface_ramp"}}


def effect(name):
    """Register the builder of a trajectory effect under ``name``."""
    def wrap(fn):
        EFFECTS[name] = fn
        return fn
    return wrap


@effect("crater")
def _crater(shot):
    """F = c z up to z = 4a (Eq 8); c from continuity with the tunnel force at 4a."""
    a = shot.nose.radius
    if "cavity" in shot.names:
        surface = nose_surface(shot.nose)
        sigma = shot.needs("sigma_n", "crater")
        c = cavity_crater_coefficient(shot.mass, a, shot.vs, lambda v: nose_force(surface, v, sigma, shot.friction))
    else:
        c = crater_coefficient(shot.mass, a, shot.nstar, shot.needs("target", "crater"), shot.vs)
    return (Crater(float(c), 4 * a),), (4 * a,)


@effect("nose_entry")
def _nose_entry(shot):
    """No force of its own: the other effects load only the wetted nose until it is embedded."""
    return (), (shot.start + shot.nose.length,)


@effect("static")
def _static(shot):
    return (Static(shot.needs("target", "static").R, shot.wetted, shot.start),), ()


@effect("inertial")
def _inertial(shot):
    return (Inertial(shot.needs("target", "inertial").rho, shot.wetted, shot.start),), ()


@effect("friction")
def _friction(shot):
    """Beside Eq 7's terms, mu times their normal stress; at the cavity level it is folded into ``cavity``."""
    if "cavity" in shot.names or shot.mu <= 0:
        return (), ()
    law = forrestal_stress(shot.needs("target", "friction"))
    return (SurfaceLoad(nose_surface(shot.nose), law, shot.mu, shot.embed, shot.start, normal=False),), ()


@effect("free_surface_ramp")
def _free_surface_ramp(shot):
    depth = 4 * shot.nose.radius if shot.ramp_depth is None else shot.ramp_depth
    ramp = FreeSurfaceRamp(shot.needs("target", "free_surface_ramp").R, shot.wetted, depth, shot.start)
    return (ramp,), (shot.start + depth,)


@effect("cavity")
def _cavity(shot):
    """The tabulated sigma_n(v_n) over the (wetted) nose, friction included when listed."""
    sigma = shot.needs("sigma_n", "cavity")
    return (SurfaceLoad(nose_surface(shot.nose), sigma, shot.friction, shot.embed, shot.start),), ()


def assemble(names, nose, nstar, mass, target: Target | None, vs, mu=0.0, ramp_depth=None, sigma_n=None) -> Assembly:
    """Effect objects for the listed effect names (see the module docstring and EFFECTS).

    ``cavity`` integrates the tabulated ``sigma_n(v_n)`` of the cavity-expansion
    level over the nose and replaces ``static`` and ``inertial``; ``target``
    may be None when no listed effect needs Eq 7's target.
    """
    listed = set(names)
    unknown = sorted(listed - set(EFFECTS))
    if unknown:
        raise ParameterError("scene", "effects", unknown, f"names among {list(EFFECTS)}")
    for key, clash in EXCLUDES.items():
        if key in listed and clash & listed:
            raise ParameterError("scene", "effects", list(names), f"{key} is not allowed with {sorted(clash & listed)}")
    shot = Shot(frozenset(listed), nose, nstar, mass, vs, target, mu, ramp_depth, sigma_n)
    forces, breaks = [], []
    for name, build in EFFECTS.items():
        if name in listed:
            f, b = build(shot)
            forces += f
            breaks += b
    return Assembly(tuple(forces), tuple(sorted(set(breaks))))


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

    from scipy.integrate import solve_ivp   # here: importing it costs a Snakefile's parse, which reads this module, 0.7 s

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
            # the rest event: the velocity is zero there by definition (the dense output at the event's time
            # leaves a round-off residue of either sign, 1e-14 m/s, that differs between hosts)
            state[1] = 0.0
            ys[1, -1] = 0.0
            break
        if sol.status == 0:
            raise RuntimeError(f"projectile still moving after {t_max} s (v = {state[1]:.3g} m/s)")
    t = np.concatenate([p[0] for p in pieces])
    z, v = (np.concatenate([p[1][i] for p in pieces]) for i in (0, 1))
    v = np.maximum(v, 0.0)
    decel = np.array([force(zi, vi) for zi, vi in zip(z, v)]) / mass
    return Trajectory(t, z, v, decel, float(state[2]), float(state[0]), float(t0), nfev)
