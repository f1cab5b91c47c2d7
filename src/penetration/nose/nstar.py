"""Nose shape factor N* (paper Eq 5) for any nose profile.

N* = (2/a^2) int_0^b y y'^3 / (1 + y'^2) dx. With tan(beta) = y' the
integrand y y'^3/(1+y'^2) dx equals y sin^2(beta) dy, so N* is computed as
(2/a^2) int y sin^2(beta) dy along each segment's own parameter. This form is
finite where y' is infinite and includes flat faces, which contribute
(r_outer^2 - r_inner^2)/a^2 (a flat nose has N* = 1). Friction is excluded,
as in the paper.
"""
from __future__ import annotations

import numpy as np

from .geometry import gauss_panels


def _segment_integral(seg, ta=None, tb=None):
    t, w = gauss_panels(seg, ta, tb)
    _, y = seg.point(t)
    _, yd = seg.derivative(t)
    return float(np.sum(w * y * np.sin(seg.angle(t)) ** 2 * yd))


def nstar_parts(nose) -> tuple[float, ...]:
    """N* contributed by each segment of the nose, tip first (paper Eq 10)."""
    scale = 2.0 / nose.radius**2
    return tuple(scale * _segment_integral(seg) for seg in nose.segments)


def nstar(nose) -> float:
    """Nose shape factor N*, paper Eq 5 (flat faces included)."""
    return float(sum(nstar_parts(nose)))


def cumulative_nstar(nose, n: int = 200):
    """Cumulative N* from the tip, as in the paper's Figs 3a and 5.

    Returns (x, y, N) at n points per segment: N[i] is the Eq 5 integral from
    the tip to the i-th point (a flat tip shows as a jump at x = 0).
    """
    scale = 2.0 / nose.radius**2
    xs, ys, ns, total = [], [], [], 0.0
    for seg in nose.segments:
        t = np.linspace(seg.t0, seg.t1, n)
        inc = [0.0] + [_segment_integral(seg, t[i], t[i + 1]) for i in range(n - 1)]
        x, y = seg.point(t)
        xs.append(x)
        ys.append(y)
        ns.append(total + scale * np.cumsum(inc))
        total = ns[-1][-1]
    return np.concatenate(xs), np.concatenate(ys), np.concatenate(ns)


def shape_rate(nose, x):
    """k = dN*/dx = (2/a^2) y y'^3 / (1 + y'^2) at axial positions x (1/m).

    Finite on every non-vertical segment; a flat face is a jump in N*, not a
    rate, and is left out.
    """
    y = nose.radius_at(x)
    beta = nose.angle(x)
    return 2.0 / nose.radius**2 * y * np.sin(beta) ** 2 * np.tan(beta)
