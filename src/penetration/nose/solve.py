"""Noses by constraint: one free parameter of a nose solved so that its length or its N* takes a given value.

A nose kind's keys are given as for ``make_nose`` with one left out (or named by ``solve=KEY``), together with
one constraint: ``nose_length`` (m, tip to shank) or ``nstar`` (Eq 5). The free parameter is scanned over its
allowed range (a log grid where the key is a size or a CRH, a linear one for radii below the shank's and for the
cone angle), every change of sign of ``quantity - target`` between two buildable noses is refined by Brent's
method, and the smallest root is taken; the others are reported, never dropped. A target that no value in the
range reaches is refused with the range the kind can reach.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..errors import ParameterError
from ..units import NUMBER_FORM, parse_number
from .geometry import NOSES, PSI_MAX, SIZE
from .nstar import nstar

CONSTRAINTS = {"nose_length": "the nose's length, tip to shank (m)", "nstar": "the nose shape factor N* (Eq 5)"}
SCAN_POINTS = 241
REL_TOL = 1e-12


def _quantity(name, nose):
    return nose.length if name == "nose_length" else nstar(nose)


def _grid(kind, key, params):
    """Values of the free parameter ``key`` to scan, within what the nose's own checks allow (the checks refuse
    the rest: those points are skipped)."""
    a = params.get("radius")
    if key == "radius":
        raise ParameterError(kind, "solve", key, "a key other than radius (the shank radius is given)")
    if a is None or not (SIZE[0] <= a <= SIZE[1]):
        raise ParameterError(kind, "radius", a, f"{SIZE[0]:g} <= radius <= {SIZE[1]:g} m (the shank radius)")
    if key == "psi":
        return np.geomspace(0.5, PSI_MAX, SCAN_POINTS)
    if key == "tip_radius":
        return np.linspace(0.0, a, SCAN_POINTS + 1)[:-1]
    if key in ("a1", "a2"):
        return np.linspace(0.0, a, SCAN_POINTS + 2)[1:-1]
    if key == "alpha":
        return np.linspace(0.0, 0.5 * math.pi, SCAN_POINTS + 2)[1:-1]
    return a * np.geomspace(1e-4, 1e4, SCAN_POINTS)   # S1, S2, length, tip_length


@dataclass(frozen=True)
class Solution:
    """The solved parameter of a nose by constraint."""
    key: str
    value: float
    constraint: str
    target: float
    achieved: float
    other_values: tuple = ()

    def describe(self) -> str:
        text = (f"{self.key} = {self.value:.10g} solved for {self.constraint} = {self.target:.10g} "
                f"(reached {self.achieved:.10g})")
        if self.other_values:
            text += "; other solutions " + ", ".join(f"{self.key} = {v:.10g}" for v in self.other_values) + \
                    f" (the smallest {self.key} is taken)"
        return text


def split_constraint(kind, params: dict):
    """(the nose's own keys, (constraint name, target) or None, the key named by solve= or None) of ``params``."""
    own = dict(params)
    given = [c for c in CONSTRAINTS if c in own]
    solve_key = own.pop("solve", None)
    if not given:
        if solve_key is not None:
            raise ParameterError(kind, "solve", solve_key, f"only with a constraint: {' or '.join(CONSTRAINTS)}")
        return own, None, None
    if len(given) > 1:
        raise ParameterError(kind, given[1], own[given[1]], f"one constraint at a time ({given[0]} is given already)")
    name = given[0]
    text = own.pop(name)
    try:
        target = float(parse_number(text)) if isinstance(text, str) else float(text)
    except ValueError:
        raise ParameterError(kind, name, text, f"a number: {NUMBER_FORM}") from None
    if not (math.isfinite(target) and target > 0):
        raise ParameterError(kind, name, text, f"{name} > 0 ({CONSTRAINTS[name]})")
    return own, (name, target), solve_key


def solve_nose(kind, params: dict):
    """(the nose, its Solution or None): ``params`` as make_nose's, with at most one constraint of CONSTRAINTS
    (and ``solve=KEY`` where no key is left out)."""
    if kind not in NOSES:
        raise ParameterError("nose", "kind", kind, f"one of {sorted(NOSES)}")
    cls = NOSES[kind]
    own, constraint, solve_key = split_constraint(kind, params)
    if constraint is None:
        return cls.from_keywords(**own), None
    name, target = constraint
    fields = [f for f in dataclasses.fields(cls)]
    names = [f.name for f in fields]
    fixed = _parsed(kind, names, own) if kind not in ("flat", "table") else own   # every given key checked first
    free = [f.name for f in fields if f.default is dataclasses.MISSING and f.name not in own]
    if solve_key is not None:
        if solve_key not in names or solve_key == "radius":
            raise ParameterError(kind, "solve", solve_key, f"a key of the {kind} nose other than radius: "
                                 f"{[n for n in names if n != 'radius']}")
        if solve_key in own:
            raise ParameterError(kind, "solve", solve_key, f"a key not also given ({solve_key}={own[solve_key]} is)")
        free = [k for k in free if k != solve_key]
        if free:
            raise ParameterError(kind, free[0], None, f"required beside solve={solve_key}: give all of {free}")
        free = [solve_key]
    if kind in ("flat", "table") or not free:
        raise ParameterError(kind, name, target, f"a {kind} nose with one key left out (or named by solve=KEY) to "
                             f"solve for; keys {names}" if kind not in ("flat", "table")
                             else f"not for a {kind} nose (it has no free parameter)")
    if len(free) > 1:
        raise ParameterError(kind, free[1], None, f"required: {name} fixes one key, {free[0]}; give all of {free[1:]}")
    key = free[0]
    if name == "nose_length" and kind in ("cone", "minimum_nstar") and key == "length":
        nose = cls.from_keywords(**own, length=target)
        return nose, Solution(key, target, name, target, nose.length)
    grid = _grid(kind, key, fixed)

    def value(v):
        try:
            return _quantity(name, cls(**fixed, **{key: float(v)})) - target
        except (ParameterError, ValueError, ZeroDivisionError):
            return math.nan

    f = np.array([value(v) for v in grid])
    ok = np.isfinite(f)
    if not ok.any():
        raise ParameterError(kind, key, None, f"a value for which the given keys {fixed} make a {kind} nose: none "
                             f"in {grid[0]:.4g}..{grid[-1]:.4g}")
    exact = ok & (np.abs(np.where(ok, f, 0.0)) <= REL_TOL * target)   # a grid point on the target (a range's end)
    roots = [float(v) for v in grid[exact]]
    for i in range(len(grid) - 1):
        if ok[i] and ok[i + 1] and not (exact[i] or exact[i + 1]):
            if f[i] * f[i + 1] < 0:
                root = float(brentq(value, grid[i], grid[i + 1], xtol=1e-300, rtol=4 * np.finfo(float).eps))
                if abs(value(root)) <= 1e-9 * max(target, 1.0):   # not a jump over an unbuildable gap
                    roots.append(root)
    if not roots:
        reach = f[ok] + target
        raise ParameterError(kind, name, target, f"{name} between {reach.min():.6g} and {reach.max():.6g}, what the "
                             f"{kind} nose with the given keys reaches as {key} runs over {grid[ok][0]:.4g}.."
                             f"{grid[ok][-1]:.4g}")
    roots = sorted(set(roots))
    roots = [r for i, r in enumerate(roots) if i == 0 or r > roots[i - 1] * (1 + 1e-9)]   # one root found twice
    nose = cls(**fixed, **{key: roots[0]})
    return nose, Solution(key, roots[0], name, target, _quantity(name, nose), tuple(roots[1:]))


def _parsed(kind, names, own):
    """The given keys as numbers (None for none), each a key of the kind."""
    out = {}
    for k, v in own.items():
        if k not in names:
            raise ParameterError(kind, k, v, f"a key among {names} or a constraint ({', '.join(CONSTRAINTS)}, solve)")
        if v is None or (isinstance(v, str) and v == "none"):
            if k == "radius":
                raise ParameterError(kind, k, v, f"{SIZE[0]:g} <= radius <= {SIZE[1]:g} m (the shank radius)")
            out[k] = None
            continue
        try:
            if isinstance(v, bool) or not isinstance(v, (int, float, str)):
                raise ValueError
            out[k] = float(parse_number(v)) if isinstance(v, str) else float(v)
        except ValueError:
            raise ParameterError(kind, k, v, f"a number in SI units: {NUMBER_FORM}") from None
    return out

