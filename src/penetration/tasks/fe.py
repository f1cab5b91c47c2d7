"""Tasks of the finite-element stage: failure-strain calibration per element size, one shot per job, collections.

Every FE output lives under a mesh profile (``full``: the default mesh of the
level; ``ci``: a coarser one that the CI runs within its time limit), both
configured in ``fe.profiles``.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

from ..concrete import material as concrete
from ..fe import state as fe_state
from ..fe.level import (calibrate_failure_strain, calibrate_strength_scale, domain_of, run_spec, scene_concrete,
                        scene_settings, scene_spec, scene_target)
from ..fe.mesh import MeshSpec, body_outline, build
from ..fe.shot import Settings, TargetSpec, binned, lowpass, progress_to, run_shot
from ..fe.solver import Unstable
from ..paper import reference
from ..pipeline.dispatch import code_closure
from ..pipeline.io import load_json, read_inference, task, write_csv, write_json
from ..shots.fields import expected_depth
from .common import calibration_row, do1_shot, realisation_factor, scene_from_inputs

FE = ("fe",)


def trial_sources():
    """The source files a calibration trial depends on: the FE calibrations' module and every module it runs on."""
    return code_closure("fe.level")


class TrialMemo(dict):
    """The finished trials of a calibration (its parameter ``key``'s value -> its run's record), appended to a JSON-lines file as each ends, so
    that an interrupted calibration resumes where it stopped. The file's name carries a digest of everything a
    trial depends on (the shot, the material, the mesh and run settings, the target, and the sources of the FE
    modules), so that a change to any of them starts afresh."""

    def __init__(self, folder, *definition, key="fs"):
        super().__init__()
        h = hashlib.sha256(repr(definition).encode())
        for f in trial_sources():
            h.update(f.read_bytes())
        self.path = Path(folder) / f"trials_{h.hexdigest()[:16]}.jsonl"
        if self.path.is_file():
            for line in self.path.read_text().splitlines():
                try:
                    rec = json.loads(line)
                except json.JSONDecodeError:
                    continue   # a line cut short by a kill
                super().__setitem__(repr(rec[key]), rec)

    def __setitem__(self, key, rec):
        super().__setitem__(key, rec)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with open(self.path, "a") as fh:
            fh.write(json.dumps(rec) + "\n")
            fh.flush()


def _calibrate_on_do1(outputs, spec, depth, memo_definition, key, fit, head, where, data_target):
    """The frame the DO1 calibrations share: the finished trials kept beside the output (an interrupted calibration
    resumes), the fit ``fit(memo, log)`` of ``spec`` on the measured ``depth``, and the record: ``head`` (what is
    fitted), the mesh, ``where`` (the profile and what else the value is bound to), DO1's data on ``data_target``,
    the wall time and the fit (the value, its residual, the runs)."""
    t0 = time.perf_counter()
    memo = TrialMemo(Path(outputs.json).parent / "trials", *memo_definition, key=key)
    if memo:
        print(f"{len(memo)} finished trials of this calibration found in {memo.path}: not run again", flush=True)
    result = fit(memo, lambda line: print(line, flush=True))
    h = spec.settings.element_size
    write_json({**head, "element_size": h, "elements_across_radius": spec.nose.radius / h, **where,
                "data": {"measured_depth": depth, "vs": spec.velocity, "mass": spec.mass, "nose": "table4_do1",
                         "target": data_target},
                "wall_time_s": time.perf_counter() - t0, **result}, outputs.json)


@task
def calibrate_fe_do1(inputs, outputs, params):
    """Failure strain fs making the FE DO1 depth equal the measured 5.1 m, at one element size."""
    refs = reference.load_reference(inputs.reference)
    cfg = params.cfg
    nose = read_inference(inputs.do1)["nose"]
    mass, vs, depth = do1_shot(refs, params.shot)
    rho, fc = refs["table1.rho"].si, refs["table1.fc"].si
    spec = run_spec(nose, mass, vs, concrete.configured(refs, params.hjc),
                    Settings.from_config(cfg, params.profile, float(params.size)),
                    TargetSpec("semi_infinite", cfg["target_radius"]), expected_depth(nose, mass, vs, fc, rho))
    _calibrate_on_do1(
        outputs, spec, depth,
        (spec.nose, spec.mass, spec.velocity, depth, spec.material, spec.settings, spec.target, spec.expected_depth),
        "fs", lambda memo, log: calibrate_failure_strain(spec, depth, tuple(cfg["fs_bracket"]), cfg["calibration_tol_m"],
                                                         log=log, memo=memo),
        {"calibration": "fe_do1", "fitted_quantity": "failure strain fs: erosion of an element once its equivalent "
         "plastic strain reaches fs (the paper's calibrated 0.38 belongs to its own 3-D mesh; fs is bound to the "
         "element size)"},
        {"profile": params.profile}, "semi_infinite")


@task
def calibrate_fe_strength_do1(inputs, outputs, params):
    """Strength scale (a factor on the whole HJC strength surface) making the DO1 depth on an erosion-free scene's
    target equal the measured 5.1 m, at one mesh: the scene's concrete (its material switches) and target (its
    pilot hole), DO1's nose, mass and striking velocity."""
    refs = reference.load_reference(inputs.reference)
    sc = scene_from_inputs(inputs, FE)
    cfg = params.cfg
    target = scene_target(sc, cfg)
    if target.formulation != "erosion_free":
        raise ValueError(f"{sc.name}: a strength-scale calibration needs an erosion_free target (fe.formulation), "
                         f"not {target.formulation}")
    nose = read_inference(inputs.do1)["nose"]
    mass, vs, depth = do1_shot(refs, params.shot)
    material, switches = scene_concrete(sc, refs, params.hjc)
    settings = scene_settings(sc, cfg, params.profile)
    spec = run_spec(nose, mass, vs, material(1.0), settings, target,
                    expected_depth(nose, mass, vs, refs["table1.fc"].si, refs["table1.rho"].si), sc.friction)
    _calibrate_on_do1(
        outputs, spec, depth,
        (spec.nose, spec.mass, spec.velocity, depth, switches, spec.settings, spec.target, spec.expected_depth),
        "strength_scale", lambda memo, log: calibrate_strength_scale(spec, depth, material, tuple(params.bracket),
                                                                     cfg["calibration_tol_m"], log=log, memo=memo),
        {"calibration": "fe_strength_do1", "fitted_quantity": "HJC strength_scale: a factor on the whole strength "
         "surface of Table 1's concrete, on the erosion-free target (no failure strain to calibrate); bound to the "
         "mesh, the pilot hole and the domain it was fitted on"},
        {"profile": params.profile, "scene": sc.name, "domain": domain_of(settings)}, dataclasses.asdict(target))


def scene_shot(inputs, params, velocity_factor=1.0, domain=None):
    """Run one shot of an FE scene (params.nose at params.velocity x velocity_factor; ``domain``: 'window' or 'whole',
    None: the scene's fe.domain); returns (summary, result, spec, scene)."""
    refs = reference.load_reference(inputs.reference)
    sc = scene_from_inputs(inputs, FE, size=getattr(params, "size", None))
    cfg = params.cfg
    v = float(params.velocity)
    expected = expected_depth(sc.noses[params.nose], sc.mass, v, sc.target.fc, sc.target.rho)
    calibrated = "calibrated" in (sc.fe.get("erosion_strain"), sc.fe.get("strength_scale"))
    cal = load_json(inputs.cal) if calibrated else None
    spec, notes = scene_spec(sc, params.nose, v, refs, params.hjc, cfg, params.profile, expected, cal, velocity_factor,
                             domain)
    with progress_to(lambda line: print(line, flush=True)):
        r = run_shot(spec, keep_model=True)
    summary = {"scene": sc.name, "nose": params.nose, "velocity": v, "mass": sc.mass, "profile": params.profile,
               "element_size": spec.settings.element_size, "failure_strain": notes["failure_strain"],
               "failure_strain_provenance": notes["failure_strain_provenance"],
               "target": dataclasses.asdict(spec.target), "domain": domain_of(spec.settings),
               "material_switches": notes["material_switches"], "friction": spec.friction, "expected_depth_m": expected, "cutoff_hz": spec.settings.cutoff_hz, **r.summary()}
    if sc.fe.get("strength_scale") == "calibrated":
        summary.update(strength_scale=notes["strength_scale"], strength_scale_provenance=notes["strength_scale_provenance"])
    if sc.size is not None:
        summary.update(size=sc.provenance["size"], efmin=spec.material.efmin, rate_law=spec.material.rate_law,
                       size_calibration=sc.size_calibration)
    return summary, r, spec, sc


@task
def fe_shot(inputs, outputs, params):
    """One nose at one velocity of an FE scene: depth, deceleration, audit, histories and the final fields.

    A shot of the erosion-free target that stops (an element losing its shape inside the target, or another
    fe.solver.Unstable) is a result of the grid-convergence study it belongs to: its record says so (status
    "stopped", the diagnostic, no depth) and its tables are empty. An eroding shot that stops fails the job."""
    t0 = time.perf_counter()
    try:
        summary, r, spec, sc = scene_shot(inputs, params)
    except Unstable as stop:
        sc = scene_from_inputs(inputs, FE, size=getattr(params, "size", None))
        if sc.fe.get("formulation") != "erosion_free":
            raise
        print(f"stopped: {stop}", flush=True)
        _stopped_shot(outputs, params, sc, stop, time.perf_counter() - t0)
        return
    settings = spec.settings
    cfg = params.cfg
    h = r.histories
    # depth and velocity sampled on the deceleration bins (impulse-conserving bin sums of the contact force)
    tb, raw = binned(h["t"], h["contact_force"], sc.mass, settings.bin_width)
    hist = pd.DataFrame({"t": tb, "depth": np.interp(tb, h["t"], h["depth"]), "velocity": np.interp(tb, h["t"], h["velocity"]),
                         "deceleration_raw": raw, "deceleration": lowpass(raw, settings.bin_width, settings.cutoff_hz)})
    summary["peak_deceleration_by_cutoff"] = {f"{fc:g}": float(lowpass(raw, settings.bin_width, fc).max())
                                              for fc in cfg["cutoffs_hz"]}
    summary["peak_deceleration_unfiltered_bins"] = float(raw.max()) if raw.size else 0.0
    m = r.model
    rc, zc = m.centroids()
    conn = m.conn
    g = m.grid
    fields = pd.DataFrame({"r0": g.R.ravel()[conn].mean(axis=1), "z0": g.Z.ravel()[conn].mean(axis=1), "r": rc, "z": zc,
                           "damage": m.E[fe_state.DMG], "eps_p": m.E[fe_state.EPSP], "state": m.alive})
    core = fields.r0 < 0.6
    write_csv(hist, outputs.histories)
    write_csv(fields[core & (fields.z0 < r.depth + 1.0)], outputs.fields)
    write_csv(pd.DataFrame(r.audit), outputs.audit)
    write_json(summary, outputs.json)


def stopped_summary(params, sc, stop, wall):
    """The summary of an erosion-free shot that stopped: what it was, where and when it stopped, no depth."""
    cfg = params.cfg
    settings = scene_settings(sc, cfg, params.profile)
    nan = float("nan")
    return {"scene": sc.name, "nose": params.nose, "velocity": float(params.velocity), "mass": sc.mass,
            "profile": params.profile, "element_size": settings.element_size,
            "target": dataclasses.asdict(TargetSpec.from_scene(sc.fe, cfg["target_radius"], cfg["block_depth"])),
            "domain": domain_of(settings), "friction": getattr(sc, "friction", 0.0),
            "status": "stopped", "diagnostic": str(stop), "depth_m": nan, "wall_time_s": wall, "steps": nan,
            "elements": nan, "energy_error_max": nan, "eroded_mass_kg": 0.0, "ejected_mass_kg": nan,
            "crater_debris_mass_kg": nan, "wall_debris_mass_kg": nan, "remap_energy_j": nan}


def _stopped_shot(outputs, params, sc, stop, wall):
    """The record of an erosion-free shot that stopped: its summary (stopped_summary) and empty tables."""
    summary = stopped_summary(params, sc, stop, wall)
    write_csv(pd.DataFrame(columns=["t", "depth", "velocity", "deceleration_raw", "deceleration"]), outputs.histories)
    write_csv(pd.DataFrame(columns=["r0", "z0", "r", "z", "damage", "eps_p", "state"]), outputs.fields)
    write_csv(pd.DataFrame(columns=["t"]), outputs.audit)
    write_json(summary, outputs.json)


@task
def fe_ensemble_shot(inputs, outputs, params):
    """A realisation of a shot's erosion chaos: the shot at v (1 + member x velocity_step) (the Table 3 ensemble's
    shots and the rear face's two targets).

    The element erosion makes the FE depth chaotic (a change of the striking
    velocity far below any physical effect moves it by a few tenths of a per
    cent); the members measure that spread. The velocity change itself moves
    the depth by at most 2 x member x velocity_step of it (DOP grows at most as v^2).
    """
    realised_shot(inputs, outputs, params, "ensemble member", "fe_ensemble.velocity_step")


@task
def fe_realisation(inputs, outputs, params):
    """A realisation of any FE scene's shot (config fe_realisations): the shot at v (1 + member x velocity_step),
    member >= 1 (member 0 is the scene's own shot); its summary with the member, the factor and the final velocity."""
    realised_shot(inputs, outputs, params, "realisation member", "fe_realisations.velocity_step")


def realised_shot(inputs, outputs, params, what, step_key):
    """The shot of params at v (1 + member x velocity_step), member >= 1, written with the member, the factor, the
    striking and the final velocity; an erosion-free one that stops is recorded as fe_shot records it (a realisation
    without a depth), any other that stops fails. ``what``, ``step_key``: the names its errors give."""
    member = int(params.member)
    factor = realisation_factor(member, params.velocity_step, what, step_key)
    t0 = time.perf_counter()
    try:
        summary, r, spec, sc = scene_shot(inputs, params, factor)
        final = float(r.histories["velocity"][-1])
    except Unstable as stop:
        sc = scene_from_inputs(inputs, FE, size=getattr(params, "size", None))
        if sc.fe.get("formulation") != "erosion_free":
            raise
        print(f"stopped: {stop}", flush=True)
        summary, final = stopped_summary(params, sc, stop, time.perf_counter() - t0), float("nan")
    write_json({**summary, "member": member, "velocity_factor": factor, "striking_velocity": summary["velocity"] * factor,
                "final_velocity_m_s": final}, outputs.json)


@task
def fe_meshes(inputs, outputs, params):
    """Outlines of the three Table 3 projectiles and the target mesh lines near the nose, for Fig 13."""
    from ..nose.geometry import Ogive
    do1 = read_inference(inputs.do1)["nose"]
    cfg = params.cfg
    s = Settings.from_config(cfg, params.profile)
    h = s.element_size
    g = build(MeshSpec(h, s.core_calibers * do1.radius, 1.0, cfg["target_radius"], 2.0, s.grading))
    rows = []
    for name, nose in (("double_ogive", do1), ("crh45", Ogive(4.5, do1.radius)), ("crh3", Ogive(3.0, do1.radius))):
        zeta, rho = body_outline(nose, s.body_length)
        rows += [{"kind": "outline", "nose": name, "r": a, "z": -b, "nose_length_m": nose.length} for a, b in zip(rho, zeta)]
    rows += [{"kind": "mesh_r", "nose": "", "r": x, "z": math.nan, "nose_length_m": math.nan} for x in g.r]
    rows += [{"kind": "mesh_z", "nose": "", "r": math.nan, "z": x, "nose_length_m": math.nan} for x in g.z]
    write_csv(pd.DataFrame(rows).assign(element_size_m=h, target_elements=g.elements), outputs.csv)


@task
def fe_nose_pressure(inputs, outputs, params):
    """The rigid-projectile check: the largest normal pressure on each Table 3 nose at the sweep's highest velocity,
    over the entry (the nose plus two shank radii deep, then 0.5 ms), against an assumed steel yield strength."""
    refs = reference.load_reference(inputs.reference)
    cfg = params.cfg
    cal = load_json(inputs.cal)
    sc = scene_from_inputs(inputs, FE)
    v = float(max(sc.velocities))
    rows = {}
    for name in ("double_ogive", "crh45", "crh3"):
        nose = sc.noses[name]
        end = (nose.length + 2 * nose.radius) / v + 5e-4
        spec, _ = scene_spec(sc, name, v, refs, params.hjc, cfg, params.profile,
                             expected_depth(nose, sc.mass, v, sc.target.fc, sc.target.rho), cal)
        spec = spec.with_settings(spec.settings.with_controls(end_time=end))
        r = run_shot(spec)
        rows[name] = {"velocity": v, "time_s": end, "max_nose_pressure_pa": r.max_nose_pressure,
                      "over_steel_yield": r.max_nose_pressure / params.steel_yield}
        print(f"{name}: {r.max_nose_pressure / 1e6:.0f} MPa over the first {end * 1e3:.2f} ms at {v:.0f} m/s")
    write_json({"steel_yield_pa_assumed": params.steel_yield, "element_size_m": spec.settings.element_size,
                "sampling": "-sigma_nn of live elements within 2.5 elements of the nose surface, every output interval",
                "noses": rows}, outputs.json)


@task
def fe_calibration_record(inputs, outputs, params):
    """The fe level's DO1 calibration at a profile's mesh as a committed output (figures/fe/{profile}/calibration_fe_do1.csv):
    the failure strain, its mesh (element size, elements across the shank radius) and its residual."""
    cal = load_json(inputs.cal)
    row = calibration_row(cal, "fs", str(inputs.cal))
    row.update({"profile": cal["profile"], "element_size_m": cal["element_size"],
                "elements_across_radius": cal["elements_across_radius"], "converged": bool(cal["converged"]),
                "trials": len(cal["runs"])})
    write_csv(pd.DataFrame([row]), outputs.csv)
