"""The finite-element level for shots: the calibration of the erosion strain on a measured depth.

The failure strain fs (erosion on the equivalent plastic strain) is a
numerical parameter bound to the mesh: it is calibrated per element size on
the DO1 shot and recorded with the size it belongs to. The depth falls as
fs grows; the FE depth carries a noise of a few tenths of a per cent (the
discrete erosion is chaotic: a 1e-12 change of the striking velocity moved
the coarse DO1 depth by 0.2 %), so the root is sought in log fs by a
bracketing secant (Illinois) that stops when the depth is within ``tol_m`` of
the target.
"""
from __future__ import annotations

import dataclasses
import math

from .dop import penetration_depth
from .fe.shot import Settings, TargetSpec, run_shot
from .nstar import nstar
from .resistance import Target, strength_factor


DEPTH_ALLOWANCE = 1.6  # the stated S = 72 fc^-0.5 gives 0.64-0.7 of the depths the FE level reaches


def expected_depth(nose, mass, velocity, fc, rho):
    """Domain depth estimate for a semi-infinite target: DEPTH_ALLOWANCE times Eq 9 with Li and Chen's S (a run
    that reaches the bottom is repeated on a domain twice as deep)."""
    return DEPTH_ALLOWANCE * float(penetration_depth(mass, nose.radius, nstar(nose),
                                                     Target(rho, fc, strength_factor(fc, "li_chen")), velocity))


def with_failure_strain(settings: Settings, fs):
    return dataclasses.replace(settings, controls=dataclasses.replace(settings.controls, erosion="plastic_strain",
                                                                       erosion_value=fs))


def calibrate_failure_strain(nose, mass, velocity, depth, material, settings: Settings, target: TargetSpec = TargetSpec(),
                             bracket=(0.2, 3.0), tol_m=0.02, max_runs=14, expected_depth=None, log=print, memo=None):
    """fs making the FE depth of the shot equal ``depth``; returns fs, the runs and the residual.

    ``memo``: a mapping of finished trials (fs -> the run's record) kept by the caller across interruptions; a trial
    found there is not run again (the iteration is deterministic, so an interrupted calibration resumes where it
    stopped). The caller keys it by everything a trial depends on."""
    runs = []

    def miss(log_fs):
        fs = math.exp(log_fs)
        key = repr(fs)
        if memo is not None and key in memo:
            rec = dict(memo[key])
            if log:
                log(f"fs {fs:.5f}: depth {rec['depth_m']:.4f} m ({rec['status']}; a finished trial, not run again)")
        else:
            # one attempt: a run that reaches the bottom of the domain is deeper than the target already
            r = run_shot(nose, mass, velocity, material, with_failure_strain(settings, fs), target,
                         expected_depth=expected_depth or 1.3 * depth, log=log, max_attempts=1)
            sm = r.summary()
            rec = {"fs": fs, "depth_m": r.depth, "wall_time_s": r.wall_time, "status": r.status,
                   "energy_error_max": sm["energy_error_max"], "peak_deceleration_m_s2": r.peak_deceleration,
                   "elements": r.elements, "steps": r.steps}
            if memo is not None:
                memo[key] = rec
            if log:
                log(f"fs {fs:.5f}: depth {r.depth:.4f} m ({r.status}, {r.wall_time:.1f} s)")
        runs.append(rec)
        return rec["depth_m"] - depth

    lo, hi = (math.log(b) for b in bracket)
    f_lo, f_hi = miss(lo), miss(hi)
    if f_lo < 0 or f_hi > 0:
        raise ValueError(f"no failure strain in {bracket} gives {depth} m: {runs}")
    side = 0
    for _ in range(max_runs - 2):
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        f = miss(x)
        if abs(f) <= tol_m:
            break
        if f > 0:
            lo, f_lo = x, f
            if side == 1:
                f_hi *= 0.5
            side = 1
        else:
            hi, f_hi = x, f
            if side == -1:
                f_lo *= 0.5
            side = -1
    best = min(runs, key=lambda r: abs(r["depth_m"] - depth))
    return {"fs": best["fs"], "residual_m": best["depth_m"] - depth, "relative_residual": (best["depth_m"] - depth) / depth,
            "runs": runs, "converged": abs(best["depth_m"] - depth) <= tol_m}
