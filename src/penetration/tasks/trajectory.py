"""Tasks of the trajectory stage: scenes at the analytic and trajectory levels, the tolerance sweep."""
from __future__ import annotations

import dataclasses
import time

import numpy as np
import pandas as pd

from ..analytic.dop import penetration_depth
from ..analytic.trajectory import assemble, integrate
from ..nose.geometry import with_radius
from ..nose.nstar import nstar
from ..pipeline.io import load_json, task, write_csv
from .common import PLAIN, scene_from_inputs


def _dop_rows(sc, radius_case="chosen"):
    """Eq 9's depth of every nose and velocity; with the scale effect, at each shot's own S (Scene.target_at: the
    law's S times the study's factor, size_calibration, times the effect's factor at the shot, size_factor)."""
    rows = []
    for name, nose in sc.noses.items():
        n = nstar(nose)
        if sc.size is None:
            d = penetration_depth(sc.mass, nose.radius, n, sc.target, sc.velocities)
            rows += [{"scene": sc.name, "nose": name, "radius_case": radius_case, "radius": nose.radius, "nstar": n,
                      "S": sc.target.S, "velocity": v, "dop": di, "dop_over_d": di / (2 * nose.radius)}
                     for v, di in zip(sc.velocities, d)]
            continue
        for v in sc.velocities:
            target = sc.target_at(nose.radius, v)
            di = float(penetration_depth(sc.mass, nose.radius, n, target, v))
            rows.append({"scene": sc.name, "nose": name, "radius_case": radius_case, "radius": nose.radius, "nstar": n,
                         "S": target.S, "velocity": v, "dop": di, "dop_over_d": di / (2 * nose.radius),
                         "size_factor": target.S / sc.target.S, "size_calibration": sc.size_calibration})
    return rows


def _histories(sc, radius_case, rtol):
    rows, finals = [], []
    for name, nose in sc.noses.items():
        n = nstar(nose)
        for v in sc.velocities:
            asm = assemble(sc.effects, nose, n, sc.mass, sc.target_at(nose.radius, v), v, sc.friction, sc.ramp_depth)
            tr = integrate(asm, sc.mass, v, rtol=rtol)
            rows.append(pd.DataFrame({"nose": name, "radius_case": radius_case, "velocity": v, "t": tr.t, "z": tr.z,
                                      "v": tr.v, "deceleration": tr.deceleration}))
            finals.append({"nose": name, "radius_case": radius_case, "velocity": v, "trajectory_dop": tr.depth,
                           "duration": tr.duration, "work_error": tr.work / (0.5 * sc.mass * v * v) - 1.0,
                           "peak_deceleration_m_s2": float(tr.deceleration.max())})
    return rows, finals


@task
def scene(inputs, outputs, params):
    """DOP of every nose and velocity of a scene; histories at trajectory level (with the scene's scale effect where
    it lists one)."""
    sc = scene_from_inputs(inputs, PLAIN, size=getattr(params, "size", None))
    variants = [("chosen", sc)]
    if "radius" in sc.provenance:
        lo, hi = load_json(inputs.diameter)["interval"]
        variants += [(case, dataclasses.replace(sc, radius=0.5 * d, noses={k: with_radius(n, 0.5 * d) for k, n in sc.noses.items()}))
                     for case, d in (("interval_low", lo), ("interval_high", hi))]
    rows, hist, finals = [], [], []
    for case, s in variants:
        rows += _dop_rows(s, case)
        if sc.level == "trajectory":
            h, f = _histories(s, case, params.rtol)
            hist += h
            finals += f
    table = pd.DataFrame(rows)
    if finals:
        table = table.merge(pd.DataFrame(finals), on=["nose", "radius_case", "velocity"], how="left")
    write_csv(table, outputs.dop)
    write_csv(pd.concat(hist, ignore_index=True) if hist else pd.DataFrame(columns=["nose"]), outputs.histories)


@task
def trajectory_tolerance_sweep(inputs, outputs, params):
    """Trajectory DOP error against Eq 9 and wall time, over tolerances and methods (DO1 scene)."""
    study = params.study
    sc = scene_from_inputs(inputs, PLAIN)
    nose = sc.noses["double_ogive"]
    n = nstar(nose)
    vs = float(sc.velocities[0])
    exact = float(penetration_depth(sc.mass, nose.radius, n, sc.target, vs))
    rows = []
    for method in study["methods"]:
        for rtol in study["rtols"]:
            times = []
            for _ in range(study["repeat"]):
                t0 = time.perf_counter()
                tr = integrate(assemble(sc.effects, nose, n, sc.mass, sc.target, vs), sc.mass, vs, rtol=rtol,
                               method=method)
                times.append(time.perf_counter() - t0)
            rows.append({"method": method, "rtol": rtol, "rel_error": abs(tr.depth - exact) / exact,
                         "wall_time_s": float(np.median(times)), "rhs_evaluations": tr.evaluations})
    write_csv(pd.DataFrame(rows), outputs.csv)
