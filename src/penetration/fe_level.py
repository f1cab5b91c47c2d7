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


# ------------------------------------------------------------------ cost before a run
BYTES_PER_ELEMENT = 400        # the solver's element and node arrays, about (14 + 8) floats an element and 12 a node
DEPTH_FROM_ALLOWANCE = 0.875   # the FE depth is about 1.4 Eq 9 depths: 1.4 / DEPTH_ALLOWANCE of the domain's estimate
TIME_FACTOR = 2.1              # time to rest over depth / striking velocity (Forrestal's model: 2.0-2.2 over the ladder)
LOAD_FACTOR = 1.0              # an element-step over the run against one of the probe's: 1.3 overestimated three shots by
                               # 1.32-1.84 times (workflow/benchmarks/fe_estimate.py on a 2-core EPYC)


@dataclasses.dataclass(frozen=True)
class CostEstimate:
    """What a shot will cost before it runs: elements x steps, and the time on this machine."""
    elements: int                  # of the whole mesh
    window_elements: int           # computed at each step once the projectile is in (the moving window)
    steps: int                     # expected: time to rest over the stable time step
    time_to_rest_s: float          # expected
    ns_per_element_step: float     # measured on this machine just now (0: not measured, the run was refused first)
    seconds: float
    memory_bytes: float

    def describe(self) -> str:
        per = f"{self.ns_per_element_step:.0f} ns per element-step measured now" if self.ns_per_element_step else \
            "not measured"
        return (f"estimated cost: {self.elements} elements ({self.window_elements} computed per step) x {self.steps} "
                f"steps to rest at about {self.time_to_rest_s * 1e3:.3g} ms = {self.seconds / 60:.2g} min on this "
                f"machine ({per}; {self.memory_bytes / 2**20:.0f} MiB)")


def _available_memory():
    import os
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return math.inf


def estimate_cost(nose, mass, velocity, material, settings: Settings, target: TargetSpec, expected_depth,
                  max_seconds=math.inf, probe_time=4e-5) -> CostEstimate:
    """Elements x steps of a shot from its mesh and expected depth, and the time they take on this machine.

    The mesh's element count comes from its node coordinates alone (no arrays are allocated); a shot whose mesh
    would not fit in the memory available now raises ParameterError. Otherwise the model is built and advanced for
    ``probe_time`` of simulated time three times (the first warms the kernels): the faster of the other two gives the
    wall time of an element-step now, on this machine, busy or not, and the last the stable time step. The time to rest is TIME_FACTOR times the
    expected depth (DEPTH_FROM_ALLOWANCE of the domain's) over the striking velocity; the elements computed per step
    are the moving window's rows at mid-depth. Without the probe (``max_seconds`` already exceeded at 5 ns per
    element-step, an optimistic bound) the estimate is returned unmeasured."""
    import time
    from .fe.mesh import node_lines
    from .fe.shot import body_outline, mesh_spec, model_for
    from .fe.contact import Projectile
    from .fe.solver import run
    from .errors import ParameterError
    h = settings.element_size
    r, z = node_lines(mesh_spec(nose, settings, target, expected_depth))
    nr, nz = len(r) - 1, len(z) - 1
    elements = nr * nz
    memory = BYTES_PER_ELEMENT * elements
    available = _available_memory()
    if memory > 0.8 * available:
        raise ParameterError("fe shot", "mesh", f"{elements} elements",
                             f"a mesh within 80 % of the memory available now ({available / 2**30:.1f} GiB at about "
                             f"{BYTES_PER_ELEMENT} bytes an element: at most {int(0.8 * available / BYTES_PER_ELEMENT)} "
                             "elements); a coarser profile or a smaller shot")
    d_mid = 0.5 * DEPTH_FROM_ALLOWANCE * expected_depth
    if settings.window_ahead is None:
        rows = nz
    else:
        behind = settings.body_length + (settings.window_tail if settings.window_tail is not None else d_mid)
        rows = int(((z[1:] > d_mid - behind) & (z[:-1] < d_mid + settings.window_ahead)).sum())
    window = max(1, rows) * nr
    t_rest = TIME_FACTOR * DEPTH_FROM_ALLOWANCE * expected_depth / velocity
    # the explicit step of the core's elements (square, size h) at the target's dilatational wave speed
    c = math.sqrt((material.Ke + 4 * material.G / 3) / material.rho0) if hasattr(material, "Ke") else 4000.0
    dt_guess = settings.controls.dt_factor * h / c
    bound = t_rest / dt_guess * window * 5e-9
    if bound > max_seconds:
        return CostEstimate(elements, window, int(t_rest / dt_guess), t_rest, 0.0, bound, memory)
    model = model_for(nose, settings, target, material, expected_depth)
    zeta, rho = body_outline(nose, settings.body_length)
    proj = Projectile(zeta, rho, mass, 0.0, velocity, 0.0)
    per = []
    for chunk in range(3):
        model.controls = dataclasses.replace(model.controls, end_time=model.t + probe_time, output_interval=probe_time)
        s0, t0 = model.steps, time.perf_counter()
        run(model, proj)
        wall, steps, computed = time.perf_counter() - t0, model.steps - s0, (model.j1 - model.j0) * model.nr
        per.append(1e9 * wall / max(1, steps * computed))
    ns = min(per[1:])
    n_steps = int(t_rest / model.dt)
    seconds = n_steps * window * ns * 1e-9 * LOAD_FACTOR
    return CostEstimate(elements, window, n_steps, t_rest, ns, seconds, memory)
