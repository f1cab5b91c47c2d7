"""The cavity-expansion level: HJC sigma_n(v) table driving the rigid trajectory.

sigma_n(v_n) comes from the dynamic spherical cavity expansion in HJC
concrete (``penetration.cavity.expansion``); the trajectory engine integrates it over
the nose surface (``cavity`` effect). The v = 0 node is the quasi-static
cavity stress (rate term off, inertia removed by extrapolation in v^2 from
two slow velocities; flagged ``extrapolated`` in the table output);
above the fastest node the table continues as a straight line in v^2
through its two fastest points.

Between the nodes the table is a monotone cubic (PCHIP) in w = v^2: exact
for Forrestal's form sigma = A + B v^2, monotone like the wall stress, and
free of the bias of a straight line in v, which over-estimates the convex
sigma_n(v) between nodes (about 1.7 % at mid-interval of the 13-point
table, 0.5 % in the DO1 depth; see the table-density study of
``figures/accuracy_cavity.csv``).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from ..analytic.trajectory import assemble, integrate
from ..concrete.hjc import HJC
from ..nose.nstar import nstar
from .expansion import Controls, Mesh, stress_table

INTERPOLATIONS = ("pchip_v2", "linear_v")


def cavity_settings(cfg):
    """Mesh and solver controls of the cavity solver from the ``cavity`` config section."""
    return (Mesh(zones=cfg["zones"], cap=cfg["cap"]),
            Controls(cycle_ratio=cfg["cycle_ratio"], tol=cfg["tol"], cfl=cfg["cfl"],
                     quasi_static_from=tuple(cfg["quasi_static_from"])))


@dataclasses.dataclass(frozen=True)
class SigmaTable:
    """Wall stress against cavity velocity, with v = 0 added by extrapolation."""
    v: np.ndarray
    sigma: np.ndarray
    extrapolated: np.ndarray
    interpolation: str = "pchip_v2"  # or "linear_v": straight lines in v (kept for the table-density study)

    def __post_init__(self):
        if self.v.size < 2 or np.any(np.diff(self.v) <= 0) or self.v[0] < 0:
            raise ValueError(f"SigmaTable: velocities must be >= 0 and strictly increasing, got {self.v}")
        if self.interpolation not in INTERPOLATIONS:
            raise ValueError(f"SigmaTable: interpolation {self.interpolation!r} not in {INTERPOLATIONS}")
        w = self.v**2
        inside = (PchipInterpolator(w, self.sigma, extrapolate=False) if self.interpolation == "pchip_v2"
                  else lambda x: np.interp(np.sqrt(x), self.v, self.sigma))
        object.__setattr__(self, "_inside", inside)
        object.__setattr__(self, "_slope", (self.sigma[-1] - self.sigma[-2]) / (w[-1] - w[-2]))

    def __call__(self, vn):
        w = np.asarray(vn, float) ** 2
        beyond = self.sigma[-1] + self._slope * (w - self.v[-1] ** 2)
        return np.where(w > self.v[-1] ** 2, beyond, self._inside(np.minimum(w, self.v[-1] ** 2)))


def sigma_table(material: HJC, velocities, radius, mesh: Mesh = Mesh(), controls: Controls = Controls()):
    """Cavity-expansion table for ``material`` and the per-velocity solver results.

    The v = 0 node is the quasi-static cavity stress: the material with its
    rate term off, expanded at the two velocities ``controls.quasi_static_from``
    (each run started from the converged rate-dependent profile at that
    velocity when the table has one) and extrapolated to v = 0 as a straight
    line in v^2, which removes the inertial part (exact for Forrestal's
    A + B v^2; the quasi-static study of ``figures/accuracy_cavity.csv``
    compares pairs and direct slow expansions). Its results are the last two
    of ``results``.
    """
    v = np.sort(np.asarray(velocities, float))
    s, results = stress_table(material, v, radius, mesh, controls)
    slow = np.asarray(controls.quasi_static_from, float)
    if not (slow.size == 2 and 0 < slow[0] < slow[1]):
        raise ValueError(f"cavity quasi_static_from = {list(slow)} is not allowed: two velocities 0 < v1 < v2 (m/s)")
    profiles = {float(x): r.profile for x, r in zip(v, results)}
    s_qs, quasi = stress_table(dataclasses.replace(material, rate=False), slow, radius, mesh, controls,
                               starts={float(x): profiles[float(x)] for x in slow if float(x) in profiles})
    s0 = quasi_static_stress(slow, s_qs)
    return SigmaTable(np.concatenate(([0.0], v)), np.concatenate(([s0], s)),
                      np.concatenate(([True], np.zeros(v.size, bool)))), results + quasi


def quasi_static_stress(v, s):
    """Value at v = 0 of the straight line in v^2 through (v[0], s[0]) and (v[1], s[1])."""
    return s[0] - (s[1] - s[0]) * v[0] ** 2 / (v[1] ** 2 - v[0] ** 2)


def cavity_trajectory(nose, mass, vs, table: SigmaTable, effects=("crater", "cavity"), mu=0.0, rtol=1e-9):
    """Rigid trajectory with the tabulated normal stress over the nose."""
    asm = assemble(effects, nose, nstar(nose), mass, None, vs, mu=mu, sigma_n=table)
    return integrate(asm, mass, vs, rtol=rtol)


CALIBRATABLE = {"strength_scale": (0.05, 2.0), "erosion_strain": (0.02, 2.0)}


def calibrate_parameter(material: HJC, name, nose, mass, vs, depth, velocities, radius, effects=("crater", "cavity"),
                        mu=0.0, mesh: Mesh = Mesh(), controls: Controls = Controls(), bracket=None):
    """Value of the HJC parameter ``name`` that makes the cavity-level trajectory reach ``depth``.

    ``strength_scale`` (a factor on the strength surface) or ``erosion_strain``
    (plastic strain beyond which the target carries no deviatoric stress):
    the depth falls as either grows, so the root in log(value) is bracketed;
    every evaluation computes a new sigma_n table.
    """
    if name not in CALIBRATABLE:
        raise ValueError(f"calibration parameter {name!r} not in {sorted(CALIBRATABLE)}")
    bracket = bracket or CALIBRATABLE[name]
    evaluations, seen = [], {}

    def miss(log_value):
        if log_value not in seen:
            mat = dataclasses.replace(material, **{name: math.exp(log_value)})
            table, _ = sigma_table(mat, velocities, radius, mesh, controls)
            d = cavity_trajectory(nose, mass, vs, table, effects, mu).depth
            evaluations.append((math.exp(log_value), d))
            seen[log_value] = d - depth
        return seen[log_value]

    lo, hi = (math.log(b) for b in bracket)
    if miss(lo) < 0 or miss(hi) > 0:
        raise ValueError(f"no {name} in {bracket} gives {depth} m: {evaluations}")
    x = brentq(miss, lo, hi, xtol=1e-8)
    final = miss(x)
    return {name: math.exp(x), "residual_m": final, "relative_residual": final / depth, "evaluations": evaluations}
