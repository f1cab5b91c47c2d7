"""Tasks of the HJC and cavity stages: EOS paths, DO1 calibration, sigma_n tables, cavity-level scenes."""
from __future__ import annotations

import math
import time

import numpy as np
import pandas as pd

from ..analytic.resistance import nose_surface
from ..cavity.level import SigmaTable, calibrate_parameter, cavity_settings, cavity_trajectory, sigma_table
from ..concrete import material as concrete
from ..concrete.effects import MATERIAL_EFFECTS
from ..concrete.hjc import LOCKS, PointState, drive
from ..concrete.size import fracture_factor, with_rate_law
from ..nose.nstar import nstar
from ..paper import reference
from ..pipeline.io import load_json, read_inference, task, write_csv, write_json
from .common import CAVITY, calibration_row, do1_shot, projectile, scene_from_inputs


def read_sigma_table(path, material="calibrated"):
    t = pd.read_csv(path)
    t = t[t.material == material].sort_values("velocity")
    return SigmaTable(t.velocity.to_numpy(), t.sigma_n.to_numpy(), t.extrapolated.to_numpy())


def calibrated_context(inputs, params):
    """Reference values, cavity config, mesh, controls and the DO1-calibrated strength scale of a rule."""
    cfg = params.cfg
    mesh, controls = cavity_settings(cfg)
    return reference.load_reference(inputs.reference), cfg, mesh, controls, load_json(inputs.cal)["strength_scale"]


@task
def hjc_eos_paths(inputs, outputs, params):
    """Hydrostatic load-unload paths of the HJC equation of state (Fig 10 data)."""
    refs = reference.load_reference(inputs.reference)
    rows = []
    for lock in LOCKS:
        mat = concrete.table1(refs, lock=lock)
        virgin = _hydro_path(mat, PointState.new(), params.mu_top, params.steps)
        rows.append(pd.DataFrame({"lock": lock, "path": "loading", "mu": virgin["mu"], "p": virgin["p"]}))
        for mu_max in params.unload_from:
            st = PointState.new()
            _hydro_path(mat, st, mu_max, params.steps)
            back = _hydro_path(mat, st, params.unload_to, params.steps)
            rows.append(pd.DataFrame({"lock": lock, "path": f"unload from {mu_max:g}", "mu": back["mu"],
                                      "p": back["p"]}))
    write_csv(pd.concat(rows, ignore_index=True), outputs.csv)


def _hydro_path(mat, state, mu_target, steps):
    """Drive a point hydrostatically from its current volume to mu_target."""
    de = (-math.log(1 + mu_target) - state.strain[:3].sum()) / steps / 3
    out, _ = drive(mat, np.tile([de, de, de, 0, 0, 0], (steps, 1)), state=state)
    return out


@task
def calibrate_cavity_do1(inputs, outputs, params):
    """HJC strength scale that makes the cavity-level DO1 trajectory reach the measured depth."""
    refs = reference.load_reference(inputs.reference)
    cfg = params.cfg
    mesh, controls = cavity_settings(cfg)
    nose = read_inference(inputs.do1)["nose"]
    mass, vs, depth = do1_shot(refs, params.shot)
    t0 = time.perf_counter()
    fit = calibrate_parameter(concrete.configured(refs, params.hjc), "strength_scale", nose, mass, vs, depth,
                              cfg["velocities"], nose.radius, tuple(cfg["effects"]), 0.0, mesh, controls)
    write_json({"calibration": "cavity_do1", "fitted_quantity": "HJC strength_scale: factor on the whole strength "
                "surface, a lumped factor for whatever makes the target weaker than Table 1's laboratory set in "
                "this model (not an in-situ strength; the counterpart of the paper's calibrated erosion strain fs: "
                "both weaken the target)",
                "data": {"measured_depth": depth, "vs": vs, "mass": mass, "nose": "table4_do1",
                         "effects": cfg["effects"]},
                "wall_time_s": time.perf_counter() - t0, **fit}, outputs.json)


@task
def cavity_table(inputs, outputs, params):
    """sigma_n(v) of the calibrated HJC target (and the uncalibrated one) with solver statistics."""
    refs, cfg, mesh, controls, scale = calibrated_context(inputs, params)
    rows = []
    for label, s in (("calibrated", scale), ("table1", 1.0)):
        t0 = time.perf_counter()
        mat = concrete.configured(refs, params.hjc, strength_scale=s)
        table, results = sigma_table(mat, cfg["velocities"], projectile(refs, params.projectile)[1], mesh, controls)
        cost = time.perf_counter() - t0
        # the largest hoop stress (tension positive) in the converged field, in units of the tensile strength T
        hoop = lambda r: float(np.max(-r.profile["p"] - 0.5 * r.profile["s_r"])) / mat.T
        quasi = results[-2:]  # the rate-free runs behind the quasi-static v = 0 node
        stats = [(sum(r.cycles for r in quasi), all(r.converged for r in quasi), max(hoop(r) for r in quasi))]
        stats += [(r.cycles, r.converged, hoop(r)) for r in results[:-2]]
        for v, sig, ex, (cycles, converged, h) in zip(table.v, table.sigma, table.extrapolated, stats, strict=True):
            rows.append({"material": label, "strength_scale": s, "velocity": v, "sigma_n": sig, "extrapolated": bool(ex),
                         "cycles": cycles, "converged": bool(converged), "max_hoop_over_T": h})
        print(f"{label}: table of {len(results)} velocities in {cost:.2f} s")
    write_csv(pd.DataFrame(rows), outputs.csv)


@task
def scene_cavity(inputs, outputs, params):
    """A cavity-level scene: depth and histories of every nose and velocity.

    The material effects strain_rate, damage and strength_cap switch the HJC
    terms; a scene that turns any of them off (or picks another lock or
    tension convention) gets its own sigma_n table at the calibrated
    strength scale. So does a scene with the scale effect (size): the
    strength scale the scale effect's study fitted with its variant on the
    laboratory shots in place of DO1's, times Bazant's factor at the scene's
    calibre (its fracture mechanism), and MC2010's factor at each point's rate
    in the material (its rate mechanism), as at the ladder's cavity level.
    """
    sc = scene_from_inputs(inputs, CAVITY, size=getattr(params, "size", None))
    switches = concrete.material_switches(sc.effects, sc.material, params.hjc)
    if switches or sc.size is not None:
        refs, cfg, mesh, controls, scale = calibrated_context(inputs, params)
        if sc.size is not None:   # the strength scale fitted with the variant on the laboratory shots, not DO1's
            scale = sc.size_calibration * fracture_factor(sc.size, 2.0 * sc.radius)
        mat = with_rate_law(concrete.configured(refs, params.hjc, strength_scale=scale, **switches), sc.size)
        table, _ = sigma_table(mat, cfg["velocities"], sc.radius, mesh, controls)
        print(f"own sigma_n table for switches {switches}" + (f", scale effect {sc.provenance['size']}" if sc.size
                                                               else ""))
    else:
        table = read_sigma_table(inputs.sigma)
    effects = tuple(e for e in sc.effects if e not in MATERIAL_EFFECTS)
    rows, hist = [], []
    for name, nose in sc.noses.items():
        steepest = nose_surface(nose).sin_beta.max()
        for v in sc.velocities:
            tr = cavity_trajectory(nose, sc.mass, v, table, effects, sc.friction, params.rtol)
            rows.append({"scene": sc.name, "nose": name, "nstar": nstar(nose), "velocity": v, "cavity_dop": tr.depth,
                         "dop_over_d": tr.depth / (2 * nose.radius), "duration": tr.duration,
                         "peak_deceleration_m_s2": float(tr.deceleration.max()),
                         # largest normal stress on the nose (at impact, where the surface is steepest):
                         # beyond the projectile's yield strength the rigid-body assumption fails
                         "peak_nose_stress": float(table(v * steepest)),
                         "peak_normal_velocity": float(v * steepest),  # the fastest v_n the nose samples
                         "work_error": tr.work / (0.5 * sc.mass * v * v) - 1.0,
                         **({"size": sc.size_variant, "size_calibration": sc.size_calibration} if sc.size else {})})
            hist.append(pd.DataFrame({"nose": name, "velocity": v, "t": tr.t, "z": tr.z, "v": tr.v,
                                      "deceleration": tr.deceleration}))
    write_csv(pd.DataFrame(rows), outputs.dop)
    write_csv(pd.concat(hist, ignore_index=True), outputs.histories)


@task
def cavity_calibration_record(inputs, outputs, params):
    """The cavity level's DO1 calibration as a committed output (figures/calibration_cavity_do1.csv)."""
    write_csv(pd.DataFrame([calibration_row(load_json(inputs.cal), "strength_scale", str(inputs.cal))]), outputs.csv)
