"""The finite-element level for shots: a scene's run spec, the calibration of the erosion strain (eroding target) or
of a strength scale (erosion-free target) on a measured depth, and the cost of a shot before it runs.

The failure strain fs (erosion on the equivalent plastic strain) is a
numerical parameter bound to the mesh: it is calibrated per element size on
the DO1 shot and recorded with the size it belongs to. The depth falls as
fs grows; the FE depth carries a noise of a few tenths of a per cent (the
discrete erosion is chaotic: a 1e-12 change of the striking velocity moved
the coarse DO1 depth by 0.2 %), so the root is sought in log fs by a
bracketing secant (Illinois) that stops when the depth is within ``tol_m`` of
the target.

The depth that sizes a semi-infinite domain is the caller's (``shots.expected_depth``: the closed form, which this
level never imports, so that the two check each other).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..concrete import material as concrete
from ..concrete.size import regularised, with_rate_law
from ..errors import ParameterError
from .shot import RunSpec, Settings, TargetSpec, progress_to, run_shot


def _check_table1_target(scene, refs):
    for name in ("rho", "fc"):
        want = refs[f"table1.{name}"].si
        if not math.isclose(getattr(scene.target, name), want, rel_tol=1e-12):
            raise ValueError(f"{scene.name}: target.{name} = {getattr(scene.target, name)}; allowed at level fe: "
                             f"{want} (the HJC set of Table 1 exists for this concrete only)")


def run_spec(nose, mass, velocity, material, settings, target, expected_depth, friction=0.0, failure_strain=None):
    """The run spec of one FE shot, assembled here and nowhere else (a scene's shot, the DO1 calibrations, a user's
    shot): the rigid projectile (``nose``, ``mass``, striking ``velocity``, Coulomb ``friction``), the target's
    ``material``, the mesh and run ``settings`` (with element erosion at ``failure_strain`` where one is given), the
    ``target`` and the ``expected_depth`` that sizes a semi-infinite domain."""
    if failure_strain is not None:
        settings = settings.with_failure_strain(float(failure_strain))
    return RunSpec(nose, mass, velocity, material, settings, target, expected_depth, friction)


def scene_concrete(scene, refs, concrete_cfg):
    """(the concrete of an FE scene at a strength scale k, as a function of k (default 1: Table 1's strength); its
    material switches): concrete.configured with the scene's effects and named conventions."""
    switches = concrete.material_switches(scene.effects, scene.material, concrete_cfg)
    return (lambda k=1.0: concrete.configured(refs, concrete_cfg, strength_scale=k, **switches)), switches


def scene_target(scene, fe_cfg):
    """The target of an FE scene (its fe slice) with the ``fe`` config slice's radius and block depth."""
    return TargetSpec.from_scene(scene.fe, fe_cfg["target_radius"], fe_cfg["block_depth"])


def scene_spec(scene, nose, velocity, refs, concrete_cfg, fe_cfg, profile, expected_depth, calibration=None,
               velocity_factor=1.0, domain=None):
    """The run spec of one shot of an FE scene (``nose``: the name of one of its noses, at one of its ``velocity``
    values times ``velocity_factor``), built once: the scene's concrete (concrete.configured with the scene's
    effects), the profile's settings (scene_settings: the scene's domain unless ``domain`` names one), the scene's
    target and, where the scene asks for the calibrated erosion strain, the DO1 ``calibration`` (its JSON record, at
    the profile's element size); with the scene's scale effect (size), the failure strain the scale effect's study
    fitted with its variant on the laboratory shots, MC2010's rate factor at each element's rate in the material and
    the crack band at the mesh's element size (concrete.size). Returns (spec, notes) with notes
    the failure strain, its provenance and the material switches."""
    _check_table1_target(scene, refs)
    v = float(velocity)
    if not np.any(np.isclose(scene.velocities, v)):
        raise ValueError(f"{scene.name}: velocity {v} is not among the scene's {list(scene.velocities)}")
    material_at, switches = scene_concrete(scene, refs, concrete_cfg)
    settings = scene_settings(scene, fe_cfg, profile, domain)
    target = scene_target(scene, fe_cfg)
    scale, scale_provenance = 1.0, "none (Table 1's HJC as stated)"
    if scene.fe.get("strength_scale") == "calibrated":
        scale, scale_provenance = _strength_calibration(scene, calibration, settings, target, profile)
        calibration = None   # the record belongs to the strength scale, not to an erosion strain
    fs = scene.fe.get("erosion_strain")
    provenance = "none (no erosion: only the guards remove inverted elements)"
    if scene.size is not None:
        if fs != "calibrated" or profile != scene.size_profile:
            raise ValueError(f"{scene.name}: effect size at the fe level takes the failure strain the scale effect's "
                             f"study fitted on the laboratory shots at the {scene.size_profile} mesh; allowed: "
                             f"fe.erosion_strain 'calibrated' (given {fs!r}) and the {scene.size_profile} profile "
                             f"(given {profile})")
        fs = scene.size_calibration
        provenance = f"fitted on the laboratory shots with the scale effect ({scene.provenance['size']})"
    elif fs == "calibrated":
        if calibration is None:
            raise ValueError(f"{scene.name}: erosion_strain 'calibrated' needs the DO1 calibration at the {profile} mesh")
        if not math.isclose(calibration["element_size"], settings.element_size):
            raise ValueError(f"calibration at element size {calibration['element_size']} m used on a "
                             f"{settings.element_size} m mesh")
        fs, provenance = calibration["fs"], f"calibrated on DO1 at element size {calibration['element_size']} m"
    material = regularised(with_rate_law(material_at(scale), scene.size), scene.size, settings.element_size)
    spec = run_spec(scene.noses[nose], scene.mass, v * velocity_factor, material, settings, target,
                    expected_depth, scene.friction, fs)
    return spec, {"failure_strain": fs, "failure_strain_provenance": provenance, "material_switches": switches,
                  "strength_scale": scale, "strength_scale_provenance": scale_provenance}


DOMAINS = ("window", "whole")


def scene_settings(scene, fe_cfg, profile, domain=None):
    """The mesh and run settings of an FE scene at a profile: Settings.from_config of the ``fe`` config slice, with
    every row computed where the scene's ``fe.domain`` (or ``domain``, which overrides it) is ``whole``; ``window``
    (the default) keeps the config's moving window (fe.window_ahead / fe.window_tail)."""
    domain = domain or scene.fe.get("domain", "window")
    if domain not in DOMAINS:
        raise ValueError(f"{scene.name}: fe.domain = {domain!r}; allowed: {', '.join(DOMAINS)}")
    settings = Settings.from_config(fe_cfg, profile)
    return dataclasses.replace(settings, window_ahead=None, window_tail=None) if domain == "whole" else settings


def domain_of(settings):
    """'whole' where the settings compute every row, else 'window'."""
    return "whole" if settings.window_ahead is None and settings.window_tail is None else "window"


def _strength_calibration(scene, calibration, settings, target, profile):
    """The DO1 strength scale of an erosion-free scene (fe.strength_scale: calibrated) from its record, checked to
    belong to the scene's mesh and target: (scale, provenance)."""
    if target.formulation != "erosion_free":
        raise ValueError(f"{scene.name}: fe.strength_scale 'calibrated' on a {target.formulation} target; allowed on "
                         f"the erosion_free target only (an eroding target calibrates its erosion_strain)")
    if calibration is None:
        raise ValueError(f"{scene.name}: strength_scale 'calibrated' needs the DO1 calibration on its target at the "
                         f"{profile} mesh")
    if not math.isclose(calibration["element_size"], settings.element_size):
        raise ValueError(f"{scene.name}: strength-scale calibration at element size {calibration['element_size']} m "
                         f"used on a {settings.element_size} m mesh")
    want = {"formulation": target.formulation, "pilot_hole": target.pilot_hole, "domain": domain_of(settings)}
    got = {**{k: calibration["data"]["target"].get(k) for k in ("formulation", "pilot_hole")},
           "domain": calibration.get("domain", "window")}
    if got != want:
        raise ValueError(f"{scene.name}: strength-scale calibration on a target {got} used on {want}")
    return float(calibration["strength_scale"]), (f"calibrated on DO1 at element size {calibration['element_size']} m, "
                                                  f"{target.formulation} target, pilot hole {target.pilot_hole:g}")


def calibrate_on_depth(spec: RunSpec, depth, name, trial, bracket, tol_m=0.02, max_runs=14, log=None, memo=None):
    """The value x of the parameter ``name`` making the FE depth of the shot ``trial(spec, x)`` equal ``depth``, for a
    parameter the depth falls with (the failure strain, a strength scale); returns {name: x, the residual, the runs}.

    The root is sought in log x by a bracketing secant (Illinois) from ``bracket`` and stops when a depth is within
    ``tol_m`` of the target (the FE depth carries a noise of a few tenths of a per cent: the best run is kept).
    ``log``: a callable told each trial and the solver's progress (None: quiet). ``memo``: a mapping of finished
    trials (repr(x) -> the run's record) kept by the caller across interruptions; a trial found there is not run
    again (the iteration is deterministic, so an interrupted calibration resumes where it stopped). The caller keys
    it by everything a trial depends on."""
    runs = []

    def miss(log_x):
        x = math.exp(log_x)
        key = repr(x)
        if memo is not None and key in memo:
            rec = dict(memo[key])
            if log:
                log(f"{name} {x:.5f}: depth {rec['depth_m']:.4f} m ({rec['status']}; a finished trial, not run again)")
        else:
            # one attempt: a run that reaches the bottom of the domain is deeper than the target already
            with progress_to(log):
                r = run_shot(trial(spec, x), max_attempts=1)
            sm = r.summary()
            rec = {name: x, "depth_m": r.depth, "wall_time_s": r.wall_time, "status": r.status,
                   "energy_error_max": sm["energy_error_max"], "peak_deceleration_m_s2": r.peak_deceleration,
                   "elements": r.elements, "steps": r.steps}
            if memo is not None:
                memo[key] = rec
            if log:
                log(f"{name} {x:.5f}: depth {r.depth:.4f} m ({r.status}, {r.wall_time:.1f} s)")
        runs.append(rec)
        return rec["depth_m"] - depth

    lo, hi = (math.log(b) for b in bracket)
    f_lo, f_hi = miss(lo), miss(hi)
    if f_lo < 0 or f_hi > 0:
        raise ValueError(f"no {name} in {bracket} gives {depth} m: {runs}")
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
    return {name: best[name], "residual_m": best["depth_m"] - depth, "relative_residual": (best["depth_m"] - depth) / depth,
            "runs": runs, "converged": abs(best["depth_m"] - depth) <= tol_m}


def calibrate_failure_strain(spec: RunSpec, depth, bracket=(0.2, 3.0), tol_m=0.02, max_runs=14, log=None, memo=None):
    """fs making the FE depth of the eroding shot ``spec`` equal ``depth`` (calibrate_on_depth); returns fs, the runs
    and the residual."""
    return calibrate_on_depth(spec, depth, "fs", lambda s, fs: s.with_failure_strain(fs), bracket, tol_m, max_runs,
                              log, memo)


def calibrate_strength_scale(spec: RunSpec, depth, material, bracket=(0.3, 3.0), tol_m=0.02, max_runs=14, log=None,
                             memo=None):
    """The factor on the whole HJC strength surface making the FE depth of the shot ``spec`` (an erosion-free target:
    no failure strain to calibrate) equal ``depth``; ``material(scale)`` builds the scaled concrete
    (calibrate_on_depth). Returns strength_scale, the runs and the residual."""
    return calibrate_on_depth(spec, depth, "strength_scale", lambda s, k: dataclasses.replace(s, material=material(k)),
                              bracket, tol_m, max_runs, log, memo)


# ------------------------------------------------------------------ cost before a run
BYTES_PER_ELEMENT = 400        # the solver's element and node arrays, about (14 + 8) floats an element and 12 a node
DEPTH_FROM_ALLOWANCE = 0.875   # the FE depth is about 1.4 Eq 9 depths: 1.4 / shots.DEPTH_ALLOWANCE of the domain's estimate
TIME_FACTOR = 2.1              # time to rest over depth / striking velocity (Forrestal's model: 2.0-2.2 over the ladder)
UNPROBED_NS = 5.0              # ns per element-step below any measured (the bandwidth floor is 10-15): a lower bound
LOAD_FACTOR = 1.0              # an element-step over the run against one of the probe's: 1.3 overestimated three shots by
                               # 1.32-1.84 times (workflow/benchmarks/fe_estimate.py on a 2-core EPYC)


# A probe slower than this is a busy machine or a transient, not this kernel's rate: 5 times the slowest state
# workflow/benchmarks/fe_speed.py recorded on the 2-core machines (85 ns per element-step, the all-plastic state;
# figures/timing/fe_speed.csv). The probe is repeated up to MAX_PROBES times until two agree within PROBE_AGREE.
BUSY_NS = 400.0
RECORDED_NS = (28.9, 84.8)        # the recorded quiet range (elastic to all-plastic), figures/timing/fe_speed.csv
MAX_PROBES, PROBE_AGREE = 6, 0.25


def settled_rate(probe, max_probes=MAX_PROBES, agree=PROBE_AGREE):
    """ns per element-step from repeated probes (``probe()`` returns one; the first warms the kernels and is not
    used): probing stops when the two fastest agree within ``agree`` and are below BUSY_NS, or after ``max_probes``;
    the fastest is taken (a transient slows a probe down, never speeds it up). Returns (ns, probes used)."""
    probe()
    per = []
    while len(per) < max(2, max_probes - 1):
        per.append(probe())
        best = sorted(per)[:2]
        if len(best) == 2 and best[1] <= (1 + agree) * best[0] and best[0] <= BUSY_NS:
            break
    return min(per), len(per) + 1


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
    probes: int = 0

    @property
    def busy(self) -> bool:
        return self.ns_per_element_step > BUSY_NS

    def describe(self) -> str:
        head = (f"estimated cost: {self.elements} elements ({self.window_elements} computed per step) x {self.steps} "
                f"steps to rest at about {self.time_to_rest_s * 1e3:.3g} ms")
        if not self.ns_per_element_step:   # refused before the probe: a bound, never a time of this machine
            return (f"{head}: at least {self.seconds / 60:.2g} min (a lower bound at {UNPROBED_NS:g} ns per "
                    f"element-step; this machine was not probed; {self.memory_bytes / 2**20:.0f} MiB)")
        text = (f"{head} = {self.seconds / 60:.2g} min on this machine ({self.ns_per_element_step:.0f} ns per "
                f"element-step measured now, best of {self.probes - 1} probes; {self.memory_bytes / 2**20:.0f} MiB)")
        if self.busy:
            quiet = self.seconds * RECORDED_NS[1] / self.ns_per_element_step
            text += (f"; the machine looks busy: the recorded quiet rate is {RECORDED_NS[0]:g}-{RECORDED_NS[1]:g} ns "
                     f"(figures/timing/fe_speed.csv), at which it would take at most {quiet / 60:.2g} min")
        return text


def estimate_cost(spec: RunSpec, max_seconds=math.inf, probe_time=4e-5, available_memory=math.inf) -> CostEstimate:
    """Elements x steps of a shot from its mesh and expected depth, and the time they take on this machine.

    The mesh's element count comes from its node coordinates alone (no arrays are allocated); a shot whose mesh
    would not fit in ``available_memory`` (bytes; the caller reads what is free now) raises ParameterError. Otherwise the model is built and advanced for
    ``probe_time`` of simulated time several times (settled_rate: the first warms the kernels; the fastest of the
    others, once two agree, gives the wall time of an element-step now, on this machine; a rate beyond BUSY_NS is
    said to be a busy machine's), and the last the stable time step. The time to rest is TIME_FACTOR times the
    expected depth (DEPTH_FROM_ALLOWANCE of the domain's) over the striking velocity; the elements computed per step
    are the moving window's rows at mid-depth. Without the probe (``max_seconds`` already exceeded at 5 ns per
    element-step, an optimistic bound) the estimate is returned unmeasured."""
    import time

    from .contact import Projectile
    from .mesh import node_lines
    from .shot import body_outline, mesh_spec, model_for
    from .solver import run
    nose, settings, target, material = spec.nose, spec.settings, spec.target, spec.material
    expected_depth, velocity = spec.expected_depth, spec.velocity
    h = settings.element_size
    r, z = node_lines(mesh_spec(nose, settings, target, expected_depth))
    nr, nz = len(r) - 1, len(z) - 1
    elements = nr * nz
    memory = BYTES_PER_ELEMENT * elements
    available = available_memory
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
    bound = t_rest / dt_guess * window * UNPROBED_NS * 1e-9
    if bound > max_seconds:
        return CostEstimate(elements, window, int(t_rest / dt_guess), t_rest, 0.0, bound, memory)
    model = model_for(nose, settings, target, material, expected_depth)
    zeta, rho = body_outline(nose, settings.body_length)
    proj = Projectile(zeta, rho, spec.mass, 0.0, velocity, spec.friction)
    def probe():
        model.controls = dataclasses.replace(model.controls, end_time=model.t + probe_time, output_interval=probe_time)
        s0, t0 = model.steps, time.perf_counter()
        run(model, proj)
        wall, steps, computed = time.perf_counter() - t0, model.steps - s0, (model.j1 - model.j0) * model.nr
        return 1e9 * wall / max(1, steps * computed)
    ns, probes = settled_rate(probe)
    n_steps = int(t_rest / model.dt)
    seconds = n_steps * window * ns * 1e-9 * LOAD_FACTOR
    return CostEstimate(elements, window, n_steps, t_rest, ns, seconds, memory, probes)
