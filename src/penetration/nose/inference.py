"""Explicit inference of nose geometry the paper does not state.

The paper never gives the double ogive's dimensions. Two rules recover them
from what it does state; each returns the chosen nose, the assumptions it
rests on, the family of solutions it chose from and the residuals, so that a
later stage can read the geometry from a result file and a reader can see
how much hangs on the choice.

Construction shared by both rules (paper Figs 4 and 6): a base ogive of CRH
psi_base tangent to the shank; D, the front end of the base ogive, at
fraction xi_d of the base ogive's own length; a straight cone from C to D
(with a corner at D); a tip ogive through the nose tip, tangent to the cone
at C. C sits at fraction xi_c of the base ogive's length, measured in the
base ogive's own axis, whose tip lies ``length - base.length`` behind the
tip of the longer double ogive; a1 is the radius at C.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, least_squares

from ..errors import ParameterError
from .geometry import DoubleOgive, Ogive
from .nstar import nstar, shape_rate

# Decimals an inferred nose parameter is rounded to: well above round-off, so that the BLAS kernels and vector
# maths of the CPU do not choose the nose (a root of well-posed equations; a minimiser of a flat minimum).
ROOT_DIGITS = 12
MINIMISER_DIGITS = 6

# How the paper's Fig 3b "k" may be normalised: factor turning dN*/dx (1/m)
# into the plotted number, given the nose.
K_CONVENTIONS = {
    "dN/dx_m": lambda nose: 1.0,
    "dN/d(x/b)": lambda nose: nose.length,
    "dN/d(x/d)": lambda nose: 2.0 * nose.radius,
    "dN/d(x/a)": lambda nose: nose.radius,
    "integrand_no_factor2": lambda nose: 0.5 * nose.radius,
}


class InferenceError(ValueError):
    """The stated data admit no nose of the assumed construction."""


def plotted_k(nose, x, convention):
    """The Fig 3b quantity k at x under a normalisation convention."""
    return shape_rate(nose, x) * K_CONVENTIONS[convention](nose)


def k_band(nose, threshold, convention):
    """Fractions (x/b) bounding the region where plotted k > threshold.

    Returns (lo, hi, peak_x_over_b, peak_k); lo, hi are None if the peak is
    below the threshold. Ends are refined by root finding.
    """
    b = nose.length
    xs = np.linspace(0.0, b, 4001)[1:-1]
    k = plotted_k(nose, xs, convention)
    i = int(np.argmax(k))
    f = lambda x: float(plotted_k(nose, np.array([x]), convention)[0])
    xp = _golden_max(f, xs[max(i - 1, 0)], xs[min(i + 1, xs.size - 1)])
    kp = f(xp)
    if kp <= threshold:
        return None, None, xp / b, kp
    lo = brentq(lambda x: f(x) - threshold, xs[0], xp, xtol=1e-14 * b)
    hi = brentq(lambda x: f(x) - threshold, xp, xs[-1], xtol=1e-14 * b)
    return lo / b, hi / b, xp / b, kp


def _golden_max(f, a, b, tol=1e-13):
    g = 0.5 * (math.sqrt(5) - 1)
    c, d = b - g * (b - a), a + g * (b - a)
    while abs(b - a) > tol * max(1.0, abs(a)):
        if f(c) > f(d):
            b, d = d, c
            c = b - g * (b - a)
        else:
            a, c = c, d
            d = a + g * (b - a)
    return 0.5 * (a + b)


def _radius_at(ogive, xi):
    """Radius of a tangent ogive at the fraction xi of its length from the tip, in scalar maths (the same on every
    CPU, unlike numpy's vector arccos in ``ogive.y``)."""
    return ogive.radius - ogive.S + math.sqrt(ogive.S ** 2 - ((1.0 - xi) * ogive.length) ** 2)


def banded_double_ogive(radius, psi_base, length, xi_c, xi_d, a1):
    """Double ogive of the Fig 4 construction (see module docstring).

    Raises InferenceError when no convex tip ogive tangent at C reaches the
    tip, or when the points are out of order.
    """
    base = Ogive(psi_base, radius)
    shift = length - base.length
    if shift < 0:
        raise InferenceError(f"length {length} is shorter than the base ogive {base.length}")
    xD = shift + xi_d * base.length
    xC = shift + xi_c * base.length
    yD = _radius_at(base, xi_d)
    if not (0 < xC < xD and 0 < a1 < yD):
        raise InferenceError(f"need 0 < x_C < x_D and 0 < a1 < a2: x_C={xC:.4g}, x_D={xD:.4g}, a1={a1:.4g}, a2={yD:.4g}")
    alpha = math.atan((yD - a1) / (xD - xC))
    reach_min = a1 * (1 - math.sin(alpha)) / math.cos(alpha)
    reach_max = a1 / math.tan(alpha)
    if not (reach_min < xC < reach_max):
        raise InferenceError(f"no convex tip ogive tangent at C reaches the tip: x_C={xC:.4g} outside ({reach_min:.4g}, {reach_max:.4g})")

    def reach(log_s1):
        s1 = math.exp(log_s1)
        phi0 = math.asin(math.cos(alpha) - a1 / s1)
        return s1 * (math.cos(phi0) - math.sin(alpha)) - xC

    lo = math.log(a1 / math.cos(alpha))
    hi = lo + 1.0
    while reach(hi) < 0:
        hi += 1.0
    s1 = math.exp(brentq(reach, lo, hi, xtol=1e-14))
    try:
        return DoubleOgive(radius, S1=s1, S2=base.S, a1=a1, a2=yD, alpha=alpha)
    except ParameterError as err:
        raise InferenceError(str(err)) from None


def describe(nose, density=None):
    """Flat dict of a double ogive's parameters and derived sizes (SI)."""
    xC, xD = nose.joints
    out = {"radius": nose.radius, "S1": nose.S1, "S2": nose.S2, "a1": nose.a1, "a2": nose.a2,
           "alpha": nose.cone_angle, "length": nose.length, "x_C": xC, "x_D": xD,
           "region1_length": xC, "region2_length": xD - xC, "region3_length": nose.length - xD,
           "nstar": nstar(nose), "volume": nose.volume()}
    if density is not None:
        out["mass"] = nose.mass(density)
    return out


@dataclass(frozen=True)
class Fig4Rule:
    """Inputs of the Figs 4/5/7 design rule (shape only; lengths in radii)."""
    psi_base: float = 3.0
    psi_length: float = 5.0
    threshold: float = 0.027
    convention: str = "integrand_no_factor2"
    family_points: int = 121


def infer_fig4(rule: Fig4Rule):
    """Figs 4/5/7 double ogive between CRH 3 and CRH 5 (unit shank radius).

    C and D are the ends of the band where the base ogive's plotted k
    exceeds the threshold; the radius a1 at C is free (a one-parameter
    family); the chosen member has the least N*, following the paper's aim
    to "minimise the increase in N* as far as possible".
    """
    base = Ogive(rule.psi_base, 1.0)
    length = Ogive(rule.psi_length, 1.0).length
    lo, hi, xpk, kpk = k_band(base, rule.threshold, rule.convention)
    if lo is None:
        raise InferenceError(f"k never exceeds {rule.threshold} under convention {rule.convention}")
    lo, hi = round(lo, ROOT_DIGITS), round(hi, ROOT_DIGITS)   # threshold crossings: roots, see ROOT_DIGITS
    a2 = _radius_at(base, hi)
    family = []
    for a1 in np.linspace(0.0, a2, rule.family_points)[1:-1]:
        try:
            nose = banded_double_ogive(1.0, rule.psi_base, length, lo, hi, float(a1))
        except InferenceError:
            continue
        family.append(describe(nose))
    if not family:
        raise InferenceError("no member of the Fig 4 family exists")
    ns = np.array([m["nstar"] for m in family])
    i = int(np.argmin(ns))
    if i in (0, len(family) - 1):
        raise InferenceError("least N* lies at the edge of the family: no interior minimum")
    f = lambda a1: nstar(banded_double_ogive(1.0, rule.psi_base, length, lo, hi, a1))
    # N* is flat at its minimum: the minimiser is found only to ~1e-8, and its last digits differ between CPUs
    # (numpy's vector maths); it is quantised to MINIMISER_DIGITS decimals (N* changes by ~1e-13 or less)
    a1_best = round(_golden_min(f, family[i - 1]["a1"], family[i + 1]["a1"]), MINIMISER_DIGITS)
    chosen = banded_double_ogive(1.0, rule.psi_base, length, lo, hi, a1_best)
    return {
        "rule": "fig4_design",
        "nose": chosen,
        "band": {"xi_c": lo, "xi_d": hi, "k_peak_x_over_b": xpk, "k_peak": kpk},
        "family": family,
        "family_parameter": "a1 (radius at C, shank radii)",
        "choice": "least N* over the family",
        "assumptions": [
            f"base ogive CRH {rule.psi_base} (Fig 4: region 3 follows the pre-optimisation ogive ODG)",
            f"nose length of CRH {rule.psi_length} (Fig 4: tip A is the CRH {rule.psi_length} tip; Fig 7: head length similar to CRH 5)",
            f"cone from C to D over the band where k > {rule.threshold}, k read as '{rule.convention}' (Fig 3b finding)",
            "tip ogive through the tip and tangent to the cone at C; corner at D",
            f"a1 chosen for least N*, rounded to {MINIMISER_DIGITS} decimals of the shank radius (a flat minimum)",
        ],
    }


def _golden_min(f, a, b):
    return _golden_max(lambda x: -f(x), a, b, tol=1e-10)


@dataclass(frozen=True)
class Table4Rule:
    """Inputs of the Table 4 (experiment DO1) inference."""
    radius: float
    density: float
    psi_base: float
    psi_length: float
    nstar_target: float
    mass_target: float
    middle_fraction: float = 1.0 / 3.0
    family_points: int = 41


def _table4_residual(rule, length, unknowns, extra):
    """Residual function of the Table 4 targets (relative N*, mass) plus ``extra``."""
    def residual(p):
        xi_c, xi_d, a1 = unknowns(p)
        try:
            nose = banded_double_ogive(rule.radius, rule.psi_base, length, xi_c, xi_d, a1)
        except InferenceError:
            return np.full(3, 1.0)
        return np.array([nstar(nose) / rule.nstar_target - 1.0,
                         nose.mass(rule.density) / rule.mass_target - 1.0,
                         extra(nose)])
    return residual


def infer_table4(rule: Table4Rule):
    """Double ogive of experiment DO1 from Table 4's N* and nose mass.

    Fig 4 construction on a CRH psi_base base ogive with the nose length of
    CRH psi_length. Unknowns xi_c, xi_d and a1; equations N* = target, mass
    = target, and region 2 (the cone) = middle_fraction of the nose length,
    the paper's stated upper bound. Without the third equation the solutions
    form a one-parameter family in xi_d, which is traced and returned.
    """
    length = Ogive(rule.psi_length, rule.radius).length
    base_length = Ogive(rule.psi_base, rule.radius).length
    shift_frac = (length - base_length) / base_length
    middle = lambda nose: (nose.joints[1] - nose.joints[0]) / length - rule.middle_fraction
    res = _table4_residual(rule, length, lambda p: (p[0], p[1], p[2] * rule.radius), middle)
    roots = []
    for xi_c in np.linspace(-shift_frac + 0.02, 0.8, 5):
        for xi_d in np.linspace(0.3, 0.97, 5):
            for a1 in np.linspace(0.1, 0.9, 4):
                if xi_d <= xi_c:
                    continue
                r = least_squares(res, [xi_c, xi_d, a1], bounds=([-shift_frac, 0.0, 0.0], [1.0, 1.0, 1.0]),
                                  xtol=1e-15, ftol=1e-15, gtol=1e-15)
                if np.max(np.abs(r.fun)) < 1e-9 and not any(np.allclose(r.x, q, atol=1e-6) for q in roots):
                    roots.append(r.x)
    if not roots:
        raise InferenceError("no double ogive of the assumed construction meets Table 4's N*, mass and middle length")
    roots.sort(key=lambda q: q[1])
    # the least-squares root is the same to round-off on every machine, but its last bits depend on the BLAS
    # kernels of the CPU (OpenBLAS's AVX-512 and AVX2 ones differ in the 16th digit), and the FE level's erosion
    # amplifies any difference in the nose: the root is quantised to ROOT_DIGITS decimals, far above round-off
    xi_c, xi_d, a1n = (round(float(v), ROOT_DIGITS) for v in roots[0])
    chosen = banded_double_ogive(rule.radius, rule.psi_base, length, xi_c, xi_d, a1n * rule.radius)
    family = _trace_table4_family(rule, length, shift_frac, (xi_c, a1n), xi_d)
    return {
        "rule": "table4_do1",
        "nose": chosen,
        "solution": {"xi_c": xi_c, "xi_d": xi_d, "a1_over_radius": a1n},
        "quantum": 10.0 ** -ROOT_DIGITS,
        "roots": [list(map(float, q)) for q in roots],
        "unique": len(roots) == 1,
        "residual": {"nstar": nstar(chosen) / rule.nstar_target - 1.0,
                     "mass": chosen.mass(rule.density) / rule.mass_target - 1.0,
                     "middle_fraction": middle(chosen)},
        "family": family,
        "family_parameter": "xi_d (D along the base ogive, fraction of its length), N* and mass held at the targets",
        "choice": f"region 2 length = {rule.middle_fraction:.4g} of the nose length; "
                  + ("unique root" if len(roots) == 1 else f"{len(roots)} roots, the one with smallest xi_d taken"),
        "assumptions": [
            f"base ogive CRH {rule.psi_base} tangent to the shank (the Fig 4 design rule)",
            f"nose length of CRH {rule.psi_length} (Table 2: 'equivalent to a CRH 4.5 ogive nose')",
            f"shank radius {rule.radius} m (Table 2 diameter), steel density {rule.density} kg/m^3 (Table 1)",
            f"targets N* = {rule.nstar_target}, nose mass = {rule.mass_target} kg (Table 4)",
            "tip ogive tangent to the cone at C; corner at D",
            f"region 2 = {rule.middle_fraction:.4g} of the nose length (the paper's upper bound) selects one member",
            f"the root rounded to {ROOT_DIGITS} decimals, so that no CPU's round-off chooses the nose",
        ],
    }


def _trace_table4_family(rule, length, shift_frac, start, xi_d0):
    """Members meeting N* and mass for a sweep of xi_d, by continuation."""
    members = []
    for direction in (-1, 1):
        guess = np.array(start, float)
        for xi_d in xi_d0 + direction * np.linspace(0.0, 0.12, rule.family_points // 2 + 1)[1:]:
            if not 0.0 < xi_d < 1.0:
                break
            res = _table4_residual(rule, length, lambda p, xd=xi_d: (p[0], xd, p[1] * rule.radius), lambda nose: 0.0)
            r = least_squares(lambda p: res(p)[:2], guess, bounds=([-shift_frac, 0.0], [xi_d, 1.0]),
                              xtol=1e-15, ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(r.fun)) > 1e-8:
                break
            guess = r.x
            nose = banded_double_ogive(rule.radius, rule.psi_base, length, r.x[0], xi_d, r.x[1] * rule.radius)
            members.append({"xi_d": float(xi_d), "xi_c": float(r.x[0]), **describe(nose, rule.density)})
    members.sort(key=lambda m: m["xi_d"])
    return members
