"""Penetration resistance of a rigid nose in concrete (paper Eqs 1-8, 11).

Assumptions: rigid projectile, normal incidence, no yaw; the normal stress
on the nose depends only on the local normal velocity V sin(beta) (the
cavity-expansion approximation of Luk & Forrestal, Eq 4). The strength
factor S and the coefficient B = 1 follow Li & Chen (Eq 7).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ParameterError
from ..nose.geometry import gauss_panels
from ..units import MPA

STRENGTH_LAWS: dict[str, Callable[[float], float]] = {}


def strength_law(name):
    """Register an S(fc) relation under ``name`` (fc in Pa, S dimensionless)."""
    def wrap(fn):
        STRENGTH_LAWS[name] = fn
        return fn
    return wrap


@strength_law("li_chen")
def s_li_chen(fc):
    """S = 72.0 fc^-0.5 with fc in MPa (Li & Chen 2003; paper Eq 7)."""
    return 72.0 * (np.asarray(fc, float) / MPA) ** -0.5


@strength_law("forrestal")
def s_forrestal(fc):
    """S = 82.6 fc^-0.544 with fc in MPa (Frew et al. 1998)."""
    return 82.6 * (np.asarray(fc, float) / MPA) ** -0.544


def strength_factor(fc, law="li_chen"):
    """Dimensionless strength factor S for compressive strength fc (Pa)."""
    if law not in STRENGTH_LAWS:
        raise ParameterError("target", "strength_law", law, f"one of {sorted(STRENGTH_LAWS)}")
    return STRENGTH_LAWS[law](fc)


@dataclass(frozen=True)
class Target:
    """Concrete target: density rho, strength fc and strength factor S (None where no model uses it: level fe)."""
    rho: float
    fc: float
    S: float | None

    def __post_init__(self):
        for name in ("rho", "fc", "S") if self.S is not None else ("rho", "fc"):
            v = np.asarray(getattr(self, name), float)
            if not (np.all(np.isfinite(v)) and np.all(v > 0)):
                raise ParameterError("target", name, getattr(self, name), f"finite {name} > 0 (SI units)")

    @property
    def R(self):
        """Static resistance S fc (Pa)."""
        return self.S * self.fc


def tunnel_force(radius, nstar, target: Target, v):
    """Axial force in the tunnelling phase, Eq 7: pi a^2 (S fc + N* rho V^2)."""
    v = np.asarray(v, float)
    return math.pi * radius**2 * (target.R + nstar * target.rho * v * v)


def crater_velocity_squared(mass, radius, nstar, target: Target, vs):
    """V1^2 at the end of the crater (z = 4a), Forrestal's form (Eq 9 with a^3)."""
    vs = np.asarray(vs, float)
    a3 = 4.0 * math.pi * radius**3
    return (mass * vs * vs - a3 * target.R) / (mass + a3 * nstar * target.rho)


def crater_coefficient(mass, radius, nstar, target: Target, vs):
    """c of the crater law F = c z (Eq 8), from continuity with Eq 7 at z = 4a.

    c 4a = pi a^2 (S fc + N* rho V1^2). Stays positive when V1^2 < 0 (the
    shot stops inside the crater), so the crater law still applies there.
    Below the critical velocity sqrt(4 pi a^3 S fc / m) this is the
    algebraic continuation of the continuity condition to V1^2 < 0, the one
    behind Li & Chen's (2003) published shallow branch; the general crater
    law of the other levels (``trajectory.cavity_crater_coefficient``) takes
    c = F(0)/4a there instead. The two differ by the factor
    1 + 4 pi a^3 N* rho / m at most (DOP by its square root: 0.4 % for DO1,
    below 131 m/s) and agree above the critical velocity.
    """
    v1sq = crater_velocity_squared(mass, radius, nstar, target, vs)
    return 0.25 * math.pi * radius * (target.R + nstar * target.rho * v1sq)


# ------------------------------------------------ differential-area force law
@dataclass(frozen=True)
class NoseSurface:
    """Quadrature of the nose surface for the differential-area force law (Eq 2).

    For each node: sin(beta) (normal velocity factor, Eq 3) and the weights
    of the normal-stress term (the projected area 2 pi y dy) and of the
    friction term (2 pi y dx). ``segments`` are kept to cut the surface at a
    depth while the nose enters the target.
    """
    sin_beta: np.ndarray
    w_normal: np.ndarray
    w_friction: np.ndarray
    segments: tuple
    length: float


def _nodes(segments, depth=math.inf):
    sb, wn, wf = [], [], []
    for seg in segments:
        x0, x1 = float(seg.point(seg.t0)[0]), float(seg.point(seg.t1)[0])
        if x0 > depth or (x0 == depth and x1 > x0):
            break
        tb = seg.t1 if x1 <= depth else float(seg.t_at_x(depth))
        t, w = gauss_panels(seg, seg.t0, tb)
        _, y = seg.point(t)
        xd, yd = seg.derivative(t)
        sb.append(np.sin(seg.angle(t)))
        wn.append(2 * math.pi * y * yd * w)
        wf.append(2 * math.pi * y * xd * w)
    if not sb:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    return np.concatenate(sb), np.concatenate(wn), np.concatenate(wf)


def nose_surface(nose) -> NoseSurface:
    """Gauss nodes and weights over every segment of a nose profile."""
    return NoseSurface(*_nodes(nose.segments), tuple(nose.segments), float(nose.length))


def nose_force(surface: NoseSurface, v, sigma_n, mu=0.0, depth=None, normal=True):
    """Axial force on the wetted nose, F = 2 pi int y sigma_n (dy + mu dx).

    sigma_n(vn) is the normal stress at normal velocity vn = V sin(beta)
    (Eq 4 form S fc + rho vn^2, or a tabulated cavity-expansion law);
    ``depth`` limits the load to the part of the nose with x <= depth (the
    nose entering the target), integrated exactly up to the cut; ``normal``
    False leaves out the normal-stress term (friction share only). Scalar v.
    """
    sb, wn, wf = surface.sin_beta, surface.w_normal, surface.w_friction
    if depth is not None and depth < surface.length:
        sb, wn, wf = _nodes(surface.segments, depth)
    return float(np.dot(sigma_n(v * sb), (wn if normal else 0.0) + mu * wf))


def forrestal_stress(target: Target):
    """sigma_n(vn) = S fc + rho vn^2 (Eq 4 with A = S, B = 1)."""
    return lambda vn: target.R + target.rho * vn * vn


def double_ogive_force_eq11(nose, v, target: Target, n=64):
    """Region-by-region force on a double ogive, paper Eq 11 (no friction).

    Region 1 (tip ogive, radius S1, normal angle phi from phi0 to phi1):
    int sigma(V cos phi) 2 pi S1 (S1 sin phi - c1) cos phi dphi, with the
    arc's radius y = S1 sin phi - c1; region 2 (cone of half-angle alpha):
    pi (a2^2 - a1^2) (S fc + rho (V sin alpha)^2); region 3 (base ogive,
    radius S2): as region 1 from the normal angle at D to pi/2. The paper
    writes y = S (sin phi - sin phi0) for an arc whose centre lies on the
    radius through the tip; for a general arc the offset c is -yc.
    """
    gx, gw = np.polynomial.legendre.leggauss(n)
    sig = forrestal_stress(target)
    total = 0.0
    for seg in (nose.segments[0], nose.segments[-1]):
        half, mid = 0.5 * (seg.phi1 - seg.phi0), 0.5 * (seg.phi1 + seg.phi0)
        phi = mid + half * gx
        y = seg.S * np.sin(phi) + seg.yc
        total += float(np.sum(gw * half * sig(v * np.cos(phi)) * 2 * math.pi * seg.S * y * np.cos(phi)))
    if len(nose.segments) == 3:
        total += math.pi * (nose.a2**2 - nose.a1**2) * sig(v * math.sin(nose.cone_angle))
    return total
