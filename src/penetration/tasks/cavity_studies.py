"""Tasks of the cavity-level studies: ablation, solver sweep, calibration variants, DO1 family."""
from __future__ import annotations

import dataclasses
import time

import numpy as np
import pandas as pd

from ..analytic.resistance import nose_surface
from ..cavity.expansion import Controls, Mesh, expand
from ..cavity.level import (INTERPOLATIONS, calibrate_parameter, cavity_settings, cavity_trajectory,
                            quasi_static_stress, sigma_table)
from ..concrete import material as concrete
from ..concrete.effects import MATERIAL_EFFECTS
from ..nose.geometry import DoubleOgive
from ..paper import reference
from ..pipeline.io import load_json, read_inference, task, write_csv
from .cavity import calibrated_context, read_sigma_table
from .common import CAVITY, do1_shot, scene_from_inputs


@task
def cavity_ablation(inputs, outputs, params):
    """Each study variant (an HJC term, convention or effect changed) at the study's shots: DOP change and cost.

    Shots: the DO1 shot (its mass) and the study's (nose, velocity) pairs of
    the Table 3 scene (its mass). ``sigma_n_at_vs``: the cavity stress at
    the striking velocity; ``peak_nose_stress``: at the fastest normal
    velocity the nose samples (about 0.55 of the striking velocity for these
    ogives), the largest normal stress that enters the trajectory.
    """
    refs, cfg, mesh, controls, scale = calibrated_context(inputs, params)
    sc = scene_from_inputs(inputs, CAVITY)
    mass, vs, _ = do1_shot(refs, params.shot)
    shots = [("DO1", "double_ogive", mass, vs)] + [(f"{s['nose']} {s['velocity']:g}", s["nose"], sc.mass,
                                                    s["velocity"]) for s in params.study["shots"]]
    for label, nose_name, _, _ in shots:
        if nose_name not in sc.noses:
            raise ValueError(f"study cavity_ablation, shot {label!r}: nose {nose_name!r} not in the Table 3 scene; "
                             f"allowed: {sorted(sc.noses)}")
    rows, times = [], []
    for variant in params.study["variants"]:
        effects = tuple(variant.get("effects", cfg["effects"]))
        if variant.get("friction", 0.0) > 0 and "friction" not in effects:
            raise ValueError(f"study cavity_ablation, variant {variant['name']!r}: friction is set but effect friction "
                             f"is not listed in {list(effects)}; allowed: list friction or drop the coefficient")
        t0 = time.perf_counter()
        mat = concrete.configured(refs, params.hjc, strength_scale=scale, **variant.get("material", {}))
        table, _ = sigma_table(mat, cfg["velocities"], sc.radius, mesh, controls)
        t1 = time.perf_counter()
        for label, nose_name, m, v in shots:
            tr = cavity_trajectory(sc.noses[nose_name], m, v, table, effects, variant.get("friction", 0.0), cfg["rtol"])
            steepest = nose_surface(sc.noses[nose_name]).sin_beta.max()  # the fastest v_n is v * steepest
            rows.append({"variant": variant["name"], "shot": label, "nose": nose_name, "velocity": v,
                         "sigma_n_at_vs": float(table(v)), "peak_nose_stress": float(table(v * steepest)),
                         "dop": tr.depth})
        times.append({"variant": variant["name"], "table_time_s": t1 - t0,
                      "trajectory_time_s": (time.perf_counter() - t1) / len(shots)})
    frame = pd.DataFrame(rows)
    base = frame[frame.variant == frame.variant.iloc[0]].set_index("shot")
    frame["dop_change_pct"] = 100 * (frame.dop / frame.shot.map(base.dop) - 1)
    frame["sigma_change_pct"] = 100 * (frame.sigma_n_at_vs / frame.shot.map(base.sigma_n_at_vs) - 1)
    frame["peak_stress_change_pct"] = 100 * (frame.peak_nose_stress / frame.shot.map(base.peak_nose_stress) - 1)
    write_csv(frame, outputs.csv)
    write_csv(pd.DataFrame(times), outputs.timing)


@task
def cavity_solver_sweep(inputs, outputs, params):
    """Zone-count and time-step studies of the cavity solver; sigma_n table density and interpolation
    (DO1 depth against the densest PCHIP table); trajectory rtol at the cavity level."""
    study = params.study
    refs, cfg, mesh, ctl, scale = calibrated_context(inputs, params)
    mat = concrete.configured(refs, params.hjc, strength_scale=scale)
    nose = read_inference(inputs.do1)["nose"]
    mass, vs, _ = do1_shot(refs, params.shot)
    v_cav = study["velocity"]
    rows = []
    expand(mat, v_cav, nose.radius, Mesh(zones=min(study["zones"])), Controls())  # compile before timing
    for name, runs in (("zones", [dict(zones=z) for z in study["zones"]]), ("cfl", [dict(cfl=c) for c in study["cfls"]])):
        for run in runs:
            run_mesh = Mesh(zones=run.get("zones", cfg["zones"]), cap=cfg["cap"])
            run_ctl = dataclasses.replace(ctl, cfl=run.get("cfl", cfg["cfl"]))
            t0 = time.perf_counter()
            res = expand(mat, v_cav, nose.radius, run_mesh, run_ctl)
            rows.append({"study": name, "setting": list(run.values())[0], "value": res.wall_stress,
                         "wall_time_s": time.perf_counter() - t0})
    rate_free = dataclasses.replace(mat, rate=False)
    for pair in study["quasi_static"]["pairs"]:  # the v = 0 node: rate-free runs extrapolated in v^2
        t0 = time.perf_counter()
        s_pair = [expand(rate_free, v, nose.radius, mesh, ctl).wall_stress for v in pair]
        rows.append({"study": "quasi_static_pair", "setting": min(pair), "value": quasi_static_stress(pair, s_pair),
                     "wall_time_s": time.perf_counter() - t0})
    for v in study["quasi_static"]["direct"]:  # a single slow expansion
        t0 = time.perf_counter()
        rows.append({"study": "quasi_static_direct", "setting": v,
                     "value": expand(rate_free, v, nose.radius, mesh, ctl).wall_stress,
                     "wall_time_s": time.perf_counter() - t0})
    lo, hi = study["table_span"]
    for n in study["table_nodes"]:
        t0 = time.perf_counter()
        dense, _ = sigma_table(mat, np.linspace(lo, hi, n), nose.radius, mesh, ctl)
        cost = time.perf_counter() - t0
        for interp in INTERPOLATIONS:
            tab = dataclasses.replace(dense, interpolation=interp)
            d = cavity_trajectory(nose, mass, vs, tab, tuple(cfg["effects"]), 0.0, cfg["rtol"]).depth
            rows.append({"study": f"table_nodes_{interp}", "setting": n, "value": d, "wall_time_s": cost})
    table = read_sigma_table(inputs.sigma)
    for rtol in study["rtols"]:
        t0 = time.perf_counter()
        tr = cavity_trajectory(nose, mass, vs, table, tuple(cfg["effects"]), 0.0, rtol)
        rows.append({"study": "trajectory_rtol", "setting": rtol, "value": tr.depth, "wall_time_s": time.perf_counter() - t0})
    frame = pd.DataFrame(rows)
    finest_table = frame[frame.study == f"table_nodes_{INTERPOLATIONS[0]}"].value.iloc[-1]
    slowest = frame[frame.study == "quasi_static_direct"].value.iloc[-1]  # the reference of both quasi-static studies
    for name, g in frame.groupby("study"):
        best = (finest_table if name.startswith("table_nodes") else slowest if name.startswith("quasi_static")
                else g.value.iloc[-1])
        frame.loc[g.index, "rel_error_vs_finest"] = (g.value - best).abs() / abs(best)
    write_csv(frame, outputs.csv)


@task
def cavity_calibration_variants(inputs, outputs, params):
    """Table 3 at the cavity level for each calibration variant (parameter, zone count, friction).

    Every variant calibrates its parameter on the DO1 shot (the variant of
    the calibration of record reads it from ``inputs.cal`` instead) and
    recomputes the twelve cells: the zone-count rows show the deviations
    from the paper's simulation column are not a mesh artefact; the
    erosion_strain, friction, lock and radial-cracking rows show how much
    they depend on which parameter is calibrated, on the unstated contact
    friction and on the HJC conventions. ``uncalibrated_do1_m``: the DO1
    depth of the same model with the parameter at its laboratory value.
    """
    recorded = load_json(inputs.cal)
    refs = reference.load_reference(inputs.reference)
    cfg = params.cfg
    sc = scene_from_inputs(inputs, CAVITY)
    _, controls = cavity_settings(cfg)
    effects = tuple(e for e in sc.effects if e not in MATERIAL_EFFECTS)
    mass, vs, depth = do1_shot(refs, params.shot)
    rows = []
    for variant in params.study["variants"]:
        name, zones, mu = variant["parameter"], variant["zones"], variant.get("friction", 0.0)
        material = variant.get("material", {})
        with_friction = ("friction",) if mu > 0 else ()
        mesh = Mesh(zones=zones, cap=cfg["cap"])
        t0 = time.perf_counter()
        laboratory = concrete.configured(refs, params.hjc, **material)
        if (name, zones, mu, material) == ("strength_scale", cfg["zones"], 0.0, {}):  # the calibration of record
            fit = {name: recorded["strength_scale"], "residual_m": recorded["residual_m"]}
        else:
            fit = calibrate_parameter(laboratory, name, sc.noses["double_ogive"], mass, vs, depth, cfg["velocities"],
                                      sc.radius, tuple(cfg["effects"]) + with_friction, mu, mesh, controls)
        # the same model with the parameter at its laboratory value (strength scale 1, no erosion)
        raw, _ = sigma_table(laboratory, cfg["velocities"], sc.radius, mesh, controls)
        uncalibrated = cavity_trajectory(sc.noses["double_ogive"], mass, vs, raw, effects + with_friction, mu,
                                         cfg["rtol"]).depth
        table, _ = sigma_table(concrete.configured(refs, params.hjc, **material, **{name: fit[name]}),
                               cfg["velocities"], sc.radius, mesh, controls)
        for nose_name, nose in sc.noses.items():
            for v in sc.velocities:
                d = cavity_trajectory(nose, sc.mass, v, table, effects + with_friction, mu, cfg["rtol"]).depth
                paper = refs[f"table3.sim.{v:g}.{nose_name}"].si
                rows.append({"variant": variant["name"], "calibrated": name, "value": fit[name],
                             "residual_m": fit["residual_m"], "uncalibrated_do1_m": uncalibrated, "zones": zones,
                             "friction": mu, "nose": nose_name, "velocity": v, "cavity_m": d, "paper_sim_m": paper,
                             "rel_dev_pct": 100 * (d / paper - 1)})
        print(f"{variant['name']}: {name} = {fit[name]:.6f} with {zones} zones and friction {mu} (DO1 shot {depth} m "
              f"at {vs} m/s; uncalibrated {uncalibrated:.3f} m), {time.perf_counter() - t0:.1f} s", flush=True)
    write_csv(pd.DataFrame(rows), outputs.csv)


@task
def do1_family_sensitivity(inputs, outputs, params):
    """Cavity-level DOP of every member of the inferred DO1 family (N* and mass fixed)."""
    refs = reference.load_reference(inputs.reference)
    mass, _, _ = do1_shot(refs, params.shot)
    fam = pd.read_csv(inputs.family)
    table = read_sigma_table(inputs.sigma)
    rows = []
    for r in fam.itertuples():
        nose = DoubleOgive(r.radius, S1=r.S1, S2=r.S2, a1=r.a1, a2=r.a2, alpha=r.alpha)
        for v in params.study["velocities"]:
            d = cavity_trajectory(nose, mass, v, table, tuple(params.cfg["effects"]), 0.0, params.cfg["rtol"]).depth
            rows.append({"xi_d": r.xi_d, "region2_fraction": r.region2_length / r.length, "S1": r.S1, "a1": r.a1,
                         "velocity": v, "cavity_dop": d})
    frame = pd.DataFrame(rows)
    spread = frame.groupby("velocity").cavity_dop.agg(lambda s: (s.max() - s.min()) / s.mean())
    frame["relative_spread_at_velocity"] = frame.velocity.map(spread)
    write_csv(frame, outputs.csv)
