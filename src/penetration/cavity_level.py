"""The cavity-expansion level: HJC sigma_n(v) table driving the rigid trajectory.

sigma_n(v_n) comes from the dynamic spherical cavity expansion in HJC
concrete (``penetration.cavity``); the trajectory engine integrates it over
the nose surface (``cavity`` effect). Below the slowest computed velocity
the table is extended to v = 0 by a straight line in v^2 through its two
slowest points, above the fastest by a straight line through its two
fastest points; both extensions are flagged in the table output.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.optimize import brentq

from .cavity import Controls, Mesh, stress_table
from .hjc import HJC
from .nstar import nstar
from .resistance import Target
from .trajectory import assemble, integrate


@dataclasses.dataclass(frozen=True)
class SigmaTable:
    """Wall stress against cavity velocity, with v = 0 added by extrapolation."""
    v: np.ndarray
    sigma: np.ndarray
    extrapolated: np.ndarray

    def __call__(self, vn):
        vn = np.asarray(vn, float)
        inside = np.interp(vn, self.v, self.sigma)
        slope = (self.sigma[-1] - self.sigma[-2]) / (self.v[-1] - self.v[-2])
        return np.where(vn > self.v[-1], self.sigma[-1] + slope * (vn - self.v[-1]), inside)


def sigma_table(material: HJC, velocities, radius, mesh: Mesh = Mesh(), controls: Controls = Controls()):
    """Cavity-expansion table for ``material`` and the per-velocity solver results."""
    v = np.sort(np.asarray(velocities, float))
    s, results = stress_table(material, v, radius, mesh, controls)
    v1, v2, s1, s2 = v[0], v[1], s[0], s[1]
    s0 = s1 - (s2 - s1) * v1**2 / (v2**2 - v1**2)
    return SigmaTable(np.concatenate(([0.0], v)), np.concatenate(([s0], s)),
                      np.concatenate(([True], np.zeros(v.size, bool)))), results


def cavity_trajectory(nose, mass, vs, table: SigmaTable, effects=("crater", "cavity"), mu=0.0, rtol=1e-7):
    """Rigid trajectory with the tabulated normal stress over the nose."""
    dummy = Target(1.0, 1.0, 1.0)  # unused by the cavity effects
    asm = assemble(effects, nose, nstar(nose), mass, dummy, vs, mu=mu, sigma_n=table)
    return integrate(asm, mass, vs, rtol=rtol)


def calibrate_strength_scale(material: HJC, nose, mass, vs, depth, velocities, radius, effects=("crater", "cavity"),
                             mu=0.0, mesh: Mesh = Mesh(), controls: Controls = Controls(), bracket=(0.05, 2.0)):
    """strength_scale that makes the cavity-level trajectory reach ``depth``.

    Depth falls as the strength grows, so the root in log(scale) is
    bracketed; every evaluation computes a new sigma_n table.
    """
    evaluations, seen = [], {}

    def miss(log_scale):
        if log_scale not in seen:
            mat = dataclasses.replace(material, strength_scale=math.exp(log_scale))
            table, _ = sigma_table(mat, velocities, radius, mesh, controls)
            d = cavity_trajectory(nose, mass, vs, table, effects, mu).depth
            evaluations.append((math.exp(log_scale), d))
            seen[log_scale] = d - depth
        return seen[log_scale]

    lo, hi = (math.log(b) for b in bracket)
    if miss(lo) < 0 or miss(hi) > 0:
        raise ValueError(f"no strength_scale in {bracket} gives {depth} m: {evaluations}")
    x = brentq(miss, lo, hi, xtol=1e-4)
    scale = math.exp(x)
    final = miss(x)
    return {"strength_scale": scale, "residual_m": final, "relative_residual": final / depth,
            "evaluations": evaluations}
