"""Named calibrations and inferences that use the closed-form DOP.

Each returns the fitted quantity, the data it was fitted to and the
residuals, for the task layer to write to the outputs. Nothing here is
used silently: a scene asks for a calibration by name.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq, least_squares

from .dop import penetration_depth
from .resistance import Target


def calibrate_strength(mass, radius, nstar, rho, fc, vs, depth):
    """S such that Eq 9 gives ``depth`` for this one shot (root of a monotone function).

    Eq 9's depth falls monotonically as S grows; S is bracketed in
    [1e-3, 1e3].
    """
    f = lambda S: float(penetration_depth(mass, radius, nstar, Target(rho, fc, S), vs)) - depth
    lo, hi = 1e-3, 1e3
    if f(lo) < 0 or f(hi) > 0:
        raise ValueError(f"no S in [{lo}, {hi}] gives depth {depth} m")
    S = brentq(f, lo, hi, xtol=1e-14, rtol=1e-14)
    return {"S": S, "R": S * fc, "residual_m": f(S), "relative_residual": f(S) / depth}


def fit_strength(cells, rho, fc, S0=10.0):
    """Least-squares S over shots; cells: dicts with mass, radius, nstar, vs, depth.

    Minimises the relative depth residuals; returns S and per-cell residuals.
    """
    m, a, n, v, d = (np.array([c[k] for c in cells], float) for k in ("mass", "radius", "nstar", "vs", "depth"))
    res = lambda p: penetration_depth(m, a, n, Target(rho, fc, p[0]), v) / d - 1.0
    sol = least_squares(res, [S0], bounds=([1e-3], [1e3]), xtol=1e-15, ftol=1e-15, gtol=1e-15)
    r = res(sol.x)
    return {"S": float(sol.x[0]), "R": float(sol.x[0] * fc), "relative_residuals": r.tolist(),
            "rms": float(np.sqrt(np.mean(r**2))), "max_abs": float(np.max(np.abs(r)))}


def cell_strength(cell, rho, fc, bracket=(1e-2, 1e3)):
    """S that makes Eq 9 give one cell's depth alone (cell: mass, radius, nstar, vs, depth)."""
    f = lambda S: float(penetration_depth(cell["mass"], cell["radius"], cell["nstar"], Target(rho, fc, S),
                                          cell["vs"])) - cell["depth"]
    return brentq(f, *bracket, xtol=1e-14)


def fit_nstar_and_strength(cells, rho, fc, starts=(0.02, 0.06, 0.1, 0.3), log=False):
    """Least-squares (N*, S) of Eq 9 to cells of one nose (absolute depth residuals, m; with ``log``, residuals in
    ln depth, so that each velocity weighs by its relative error).

    N* is free here: the question is whether any (N*, S) reproduces the
    row, whatever the nose. Several starting N* guard against a local minimum.
    """
    m, a, v, d = (np.array([c[k] for c in cells], float) for k in ("mass", "radius", "vs", "depth"))
    if log:
        res = lambda p: np.log(penetration_depth(m, a, p[0], Target(rho, fc, p[1]), v) / d)
    else:
        res = lambda p: penetration_depth(m, a, p[0], Target(rho, fc, p[1]), v) - d
    best = min((least_squares(res, [n0, 6.7], bounds=([1e-4, 1e-2], [2.0, 1e2]), xtol=1e-15, ftol=1e-15,
                              gtol=1e-15) for n0 in starts), key=lambda s: s.cost)
    r = res(best.x)
    if log:
        return {"nstar": float(best.x[0]), "S": float(best.x[1]), "ln_residuals": r.tolist(),
                "rms_ln_residual": float(np.sqrt(np.mean(r**2))), "max_abs_ln_residual": float(np.max(np.abs(r)))}
    return {"nstar": float(best.x[0]), "S": float(best.x[1]), "residuals_m": r.tolist(),
            "max_abs_residual_m": float(np.max(np.abs(r)))}


def diameter_interval(mass, nstar, target: Target, vs, lo, hi):
    """Diameters d for which lo < Pd/d <= hi at striking velocity vs.

    Pd/d decreases monotonically with d at fixed mass, so each bound is one
    root; the search runs over d in [1 mm, 10 m].
    """
    g = lambda d, level: float(penetration_depth(mass, 0.5 * d, nstar, target, vs)) / d - level
    dmin, dmax = 1e-3, 10.0
    return brentq(lambda d: g(d, hi), dmin, dmax, xtol=1e-12), brentq(lambda d: g(d, lo), dmin, dmax, xtol=1e-12)


def infer_diameter(mass, nstar, target: Target, axes):
    """Diameter consistent with every axis range (vs, lo, hi) of Pd/d.

    Returns the intersection of the intervals and its midpoint (the chosen
    value); raises if the ranges do not intersect.
    """
    intervals = [diameter_interval(mass, nstar, target, vs, lo, hi) for vs, lo, hi in axes]
    lo = max(i[0] for i in intervals)
    hi = min(i[1] for i in intervals)
    if not lo < hi:
        raise ValueError(f"the axis ranges admit no common diameter: {intervals}")
    return {"diameter": 0.5 * (lo + hi), "interval": [lo, hi], "per_axis": [list(i) for i in intervals],
            "half_width_relative": 0.5 * (hi - lo) / (0.5 * (lo + hi))}


def resistance_shares(nstar, target: Target, v):
    """Static and inertial shares of the Eq 7 resistance at velocity v (Fig 1)."""
    v = np.asarray(v, float)
    inertial = nstar * target.rho * v * v
    total = target.R + inertial
    return target.R / total, inertial / total

