"""Tasks of the calibrations on laboratory series (``laboratory``): the cavity level's strength scale fitted on the
development shots by the protocol of the config's ``validation.laboratory`` section, each fold scored on the shots
it held out."""
from __future__ import annotations

import dataclasses
import time

import numpy as np
import pandas as pd

from ..paper import reference
from ..pipeline.config import machine_name
from ..pipeline.io import load_json, read_inference, read_rows, task, write_csv, write_json
from ..shots.ladder import UserShot, fe_spec, run, user_shot
from ..studies.fe_results import do1_test_tables, in_order
from ..studies.laboratory import FITTED, Protocol, errors_summary, fit_factor, interpolated_depths
from .common import do1_shot, realisation_factor
from .levels import context_from_files


def shot_groups(protocol: Protocol, rows):
    """(series, fc group) of every shot row."""
    series = [protocol.series_of(r["source"]) for r in rows]
    return series, [protocol.group_of(s, float(r["fc_MPa"])) for s, r in zip(series, rows)]


def _runs(shots, ctx, level, value, log=None):
    """Every shot's run at ``level`` with its factor at ``value`` (``log``: a line per shot)."""
    setattr(ctx, FITTED[level][0], value)
    out = []
    for k, s in enumerate(shots):
        out.append(run(s, level, ctx))
        if log is not None:
            r = out[-1]
            log(f"  {s.label}: {r.depth_m:.4g} m ({r.status}, {r.wall_time_s:.1f} s; {k + 1}/{len(shots)})")
    return out


def _depths(shots, ctx, level, value, log=None):
    """Every shot's depth and status at ``level`` with its factor at ``value``."""
    runs = _runs(shots, ctx, level, value, log)
    return np.array([r.depth_m for r in runs]), [r.status for r in runs]


def calibrate_on_laboratory(level, ctx, rows, protocol: Protocol, data_path, log=print, grid_runs=None):
    """The factor of ``level`` on the laboratory shots ``rows``: each shot's depth on the protocol's grid, the fit of
    every fold, and each fold's held-out shots computed at its fitted value. ``grid_runs(rows)``: the grid's runs
    made before (a list per grid value of (depths, statuses) in the order of ``rows``, and their wall time), else
    they are run here. Returns (fits, predictions, grid rows, timing) as data frames."""
    _, name, fitted = FITTED[level]
    shots = [user_shot(r) for r in rows]
    measured = np.array([float(r["dop_m"]) for r in rows])
    series, groups = shot_groups(protocol, rows)
    grid = np.asarray(protocol.grid, float)
    t0 = time.perf_counter()
    if grid_runs is None:
        columns = []
        for k, value in enumerate(grid):
            columns.append(_depths(shots, ctx, level, value, log if level == "fe" else None))
            log(f"{level} {name} {value:.4g}: {k + 1}/{grid.size} of the grid ({time.perf_counter() - t0:.0f} s)")
        grid_seconds = time.perf_counter() - t0
    else:
        columns, grid_seconds = grid_runs(rows)
        if len(columns) != grid.size or any(len(c[0]) != len(rows) for c in columns):
            raise ValueError(f"the grid's runs: {len(columns)} grid values for {grid.size}, each of {len(rows)} shots")
    depths = np.column_stack([c[0] for c in columns])
    statuses = np.array([c[1] for c in columns], dtype=object).T
    fits, predictions = [], []
    # the fe level's mesh: its element size at the reference radius, which every shot's mesh is scaled from
    mesh = {} if level != "fe" else {"element_size_m": ctx.fe_settings.element_size,
                                     "elements_across_radius": ctx.fe_reference_radius / ctx.fe_settings.element_size}
    for fold, fit_mask, held in protocol.folds(series, groups):
        f = fit_factor(grid, depths, measured, fit_mask)
        scored = np.flatnonzero(held)
        direct, direct_status = _depths([shots[i] for i in scored], ctx, level, f.value) if scored.size else (np.empty(0), [])
        interp = interpolated_depths(grid, depths[scored], f.value) if scored.size else np.empty(0)
        rel = direct / measured[scored] - 1
        for j, i in enumerate(scored):
            predictions.append({"fold": fold, "shot_id": rows[i]["shot_id"], "series": series[i], "fc_group": groups[i],
                                "fc_MPa": float(rows[i]["fc_MPa"]), "diameter_m": float(rows[i]["diameter_m"]),
                                "velocity_ms": float(rows[i]["velocity_ms"]), name: f.value,
                                "dop_m": measured[i], "dop_pred_m": direct[j], "status": direct_status[j],
                                "rel_error": rel[j],
                                "interpolation_error": interp[j] / direct[j] - 1})
        fits.append({"level": level, "fold": fold, "fitted_quantity": fitted, "parameter": name,
                     "value": f.value, **mesh, "fit_shots": f.shots, "fit_rms_log_error": f.rms_log_error,
                     "at_grid_edge": f.at_grid_edge,
                     "fit_series": ";".join(sorted({series[i] for i in np.flatnonzero(fit_mask)})),
                     **{f"held_out_{k}": v for k, v in errors_summary(rel).items()},
                     "objective": "least squares of ln(predicted/measured) over the fit's shots", "data": data_path})
        log(f"fold {fold}: {name} {f.value:.4g} on {f.shots} shots, {scored.size} held out")
    grid_rows = pd.DataFrame([{"shot_id": r["shot_id"], name: v, "dop_pred_m": depths[i, k], "status": statuses[i, k]}
                              for i, r in enumerate(rows) for k, v in enumerate(grid)])
    timing = pd.DataFrame([{"level": level, "stage": "grid", "shots": len(shots), "grid_values": grid.size,
                            "wall_time_s": grid_seconds, "wall_time_per_shot_s": grid_seconds / depths.size,
                            "machine": machine_name()}])
    return pd.DataFrame(fits), pd.DataFrame(predictions), grid_rows, timing


def _calibrate(level, grid_key, inputs, outputs, params, profile="full", grid_runs=None):
    """The calibration of ``level`` on the laboratory shots: the protocol of validation.laboratory on its grid
    ``grid_key`` (its runs ``grid_runs(rows)`` where they were made before), the records written to ``outputs``."""
    lab = params.cfg["validation"]["laboratory"]
    _, rows = read_rows(inputs.shots)
    ctx = context_from_files(params.cfg, inputs.reference, profile=profile)
    frames = calibrate_on_laboratory(level, ctx, rows, Protocol.from_config(lab, lab[grid_key]), params.shots_path,
                                     lambda m: print(m, flush=True), grid_runs)
    for key, frame in zip(("csv", "predictions", "grid", "timing"), frames):
        write_csv(frame, getattr(outputs, key))


@task
def calibrate_cavity_laboratory(inputs, outputs, params):
    """The cavity level's strength scale on the laboratory shots (validation.laboratory's protocol and grid)."""
    _calibrate("cavity", "strength_scales", inputs, outputs, params)


@task
def fe_laboratory_grid_value(inputs, outputs, params):
    """Every laboratory shot at the fe level of a mesh profile with one failure strain of the calibration's grid
    (a piece of the calibration: committed, so that the grid, hours at the default mesh, runs over sessions).
    A committed piece is a record: the rule gives it no data and it is not rebuilt (delete it to recompute it)."""
    write_grid_piece(inputs, outputs, params)


def write_grid_piece(inputs, outputs, params, size=None, level="fe"):
    """A piece of a grid (fe_laboratory_grid_value's, or the scale effect's at the cavity or fe level with its
    ``size``): every laboratory shot at ``level`` with its factor at ``params.value`` (the fe level on the mesh of
    ``params.profile``), written to ``outputs.csv``."""
    if not inputs.data:
        raise ValueError(f"{outputs.csv} is a committed piece of the grid: delete it to recompute it")
    shots_path, reference_path = inputs.data
    _, rows = read_rows(shots_path)
    ctx = context_from_files(params.cfg, reference_path, profile=getattr(params, "profile", "full"))
    ctx.size = size
    runs = _runs([user_shot(r) for r in rows], ctx, level, float(params.value), lambda m: print(m, flush=True))
    write_csv(pd.DataFrame([{"shot_id": r["shot_id"], FITTED[level][1]: float(params.value), "dop_pred_m": res.depth_m,
                             "status": res.status, "wall_time_s": res.wall_time_s} for r, res in zip(rows, runs)]),
              outputs.csv)


def grid_runs_from(paths, rows, grid, column="fs"):
    """The grid's runs from its pieces (one CSV per grid value, in the grid's order; ``column`` the factor's):
    (depths, statuses) per value in the order of ``rows``, and their summed wall time."""
    columns, seconds = [], 0.0
    for path, value in zip(paths, grid):
        piece = pd.read_csv(path).set_index("shot_id")
        if not np.allclose(piece[column], value) or set(piece.index) != {r["shot_id"] for r in rows}:
            raise ValueError(f"{path}: not the runs of every laboratory shot at {column} = {value:g}")
        piece = piece.loc[[r["shot_id"] for r in rows]]
        columns.append((piece.dop_pred_m.to_numpy(), list(piece.status)))
        seconds += float(piece.wall_time_s.sum())
    return columns, seconds


def grid_runs_from_table(path, timing_path, rows, grid, column):
    """The grid's runs from a calibration's own grid table (``path``: shot_id, ``column``, dop_pred_m, status, every
    shot at every grid value, as calibrate_cavity_laboratory writes it) and its timing record's wall time."""
    table = pd.read_csv(path)
    columns = []
    for value in grid:
        piece = table[np.isclose(table[column], value)].set_index("shot_id")
        if set(piece.index) != {r["shot_id"] for r in rows}:
            raise ValueError(f"{path}: not the runs of every laboratory shot at {column} = {value:g}")
        piece = piece.loc[[r["shot_id"] for r in rows]]
        columns.append((piece.dop_pred_m.to_numpy(), list(piece.status)))
    return columns, float(pd.read_csv(timing_path).wall_time_s.iloc[0])


@task
def calibrate_fe_laboratory(inputs, outputs, params):
    """The fe level's failure strain at a mesh profile on the laboratory shots (the protocol of validation.laboratory,
    the grid of its failure_strains, run in pieces by fe_laboratory_grid_value), the mesh scaled to each shot as at
    the fe level of users' shots."""
    grid = params.cfg["validation"]["laboratory"]["failure_strains"]
    _calibrate("fe", "failure_strains", inputs, outputs, params, profile=params.profile,
               grid_runs=lambda rows: grid_runs_from([g["path"] for g in params.grid], rows, grid))


def _do1(inputs, params, fe_cal=None):
    """(DO1 as a user's shot, the levels' context with the laboratory calibrations, the measured depth): Table 2's
    concrete (its fc, and Table 1's density: the set the DO1 calibrations take); the fe level meshes the projectile's
    body too, so the shot carries DO1's length (Table 2) where an fe calibration ``fe_cal`` is given."""
    refs = reference.load_reference(inputs.reference)
    nose = read_inference(inputs.do1)["nose"]
    mass, vs, depth = do1_shot(refs, params.shot)
    ctx = context_from_files(params.cfg, inputs.reference, inputs.laboratory, fe_cal)
    shot = UserShot(nose, mass, vs, refs["table2.fc"].si, ctx.base.rho0, label="DO1",
                    length=refs["table2.length"].si if fe_cal else None)
    return shot, ctx, depth


@task
def do1_test(inputs, outputs, params):
    """DO1 as a test: the paper's measured shot (5.1 m) predicted at the analytic, trajectory and cavity levels with
    the calibrations fitted on the laboratory shots (none for the closed forms: Li & Chen's S) and at the fe level
    with its failure strain fitted on them (where the rule gives that record), its excess over each prediction
    recorded as a finding."""
    fe_cal = inputs.fe_laboratory if "fe_laboratory" in inputs.keys() else None
    shot, ctx, depth = _do1(inputs, params, fe_cal)
    rows = []
    for level in ("analytic", "trajectory", "cavity") + (("fe",) if fe_cal else ()):
        r = run(shot, level, ctx)
        calibration = "laboratory" if level in ("cavity", "fe") else f"none: S from {ctx.strength_law}"
        rows.append({"level": level, "calibration": calibration, "dop_pred_m": r.depth_m, "dop_m": depth,
                     "excess": depth / r.depth_m - 1,
                     "strength_scale": ctx.strength_scale if level == "cavity" else np.nan,
                     "failure_strain": ctx.failure_strain if level == "fe" else np.nan, "status": r.status})
        print(f"DO1 at the {level} level: {r.depth_m:.4g} m against the measured {depth:.4g} m", flush=True)
    write_csv(pd.DataFrame(rows), outputs.csv)


# the targets of the fe level's DO1 test: the semi-infinite target of users' shots, and the experiment's block
DO1_TEST_TARGETS = ("semi_infinite", "block")


@task
def do1_test_fe_shot(inputs, outputs, params):
    """One realisation of DO1 as a test of the fe level (its failure strain fitted on the laboratory shots, the mesh
    of params.cfg's fe section), struck at v (1 + member x velocity_step): in the semi-infinite target of users'
    shots (member 0 is do1_test's own fe shot) or in the experiment's block (the fe section's block depth, the
    3.6 m x 3.6 m cross-section as a cylinder of equal area, free faces)."""
    from ..fe.shot import progress_to, run_shot
    from ..fe.spec import TargetSpec

    target = params.target
    factor = realisation_factor(params.member, params.velocity_step, "do1_test_fe member", "do1_test_fe.velocity_step",
                                least=0)
    if target not in DO1_TEST_TARGETS:
        raise ValueError(f"do1_test_fe.targets: {target!r}; allowed: one of {DO1_TEST_TARGETS}")
    shot, ctx, depth = _do1(inputs, params, inputs.fe_laboratory)
    spec, _ = fe_spec(shot, ctx)
    if target == "block":
        fe = params.cfg["fe"]
        spec = dataclasses.replace(spec, target=TargetSpec.from_scene({"target": "block"}, fe["target_radius"],
                                                                      fe["block_depth"]))
    spec = dataclasses.replace(spec, velocity=shot.velocity * factor)
    with progress_to(lambda line: print(line, flush=True)):
        r = run_shot(spec)
    write_json({"target": target, "member": int(params.member), "striking_velocity_ms": spec.velocity,
                "failure_strain": ctx.failure_strain, "failure_strain_source": ctx.failure_strain_source,
                "element_size_m": spec.settings.element_size, "target_spec": dataclasses.asdict(spec.target),
                "measured_depth_m": depth, "final_velocity_ms": float(r.histories["velocity"][-1]), **r.summary()},
               outputs.json)
    print(f"DO1 at the fe level, {target} target, member {params.member}: {r.depth:.4g} m ({r.status})", flush=True)


@task
def do1_test_fe(inputs, outputs, params):
    """DO1 as a test of the fe level over realisations in each target of params.targets, the first the reference
    (do1_test_fe_shot's records): the members and, per target, the depths' mean with its interval, the measured
    depth's excess over it and the target's effect against the first."""
    keep = ("target", "member", "striking_velocity_ms", "failure_strain", "element_size_m", "depth_m", "status",
            "time_to_rest_s", "final_velocity_ms", "wall_time_s", "energy_error_max", "measured_depth_m")
    targets = list(params.targets)
    members = pd.DataFrame([{k: s[k] for k in keep} for s in map(load_json, inputs.shots)])
    members = in_order(members, "target", targets).reset_index(drop=True)
    members["excess"] = members.measured_depth_m / members.depth_m - 1
    measured = members.measured_depth_m.unique()
    if measured.size != 1:
        raise ValueError(f"do1_test_fe records: measured_depth_m {list(measured)}; allowed: one value (DO1's)")
    write_csv(members, outputs.members)
    t = do1_test_tables(members, targets, float(measured[0]), float(params.confidence))
    write_csv(t, outputs.csv)
    for r in t.itertuples():
        print(f"DO1 at the fe level, {r.target}: mean {r.mean_m:.4g} m over {r.realisations} realisations "
              f"({r.min_m:.4g}-{r.max_m:.4g} m), DO1 {100 * r.excess:+.1f} % deeper", flush=True)
