"""Tasks of users' shots at every level: validation per level, the HJC scaling rule, accuracy against cost, the sweep
(the levels' context is built by ``shots.records``)."""
from __future__ import annotations

import math
import time

import numpy as np
import pandas as pd

from ..analytic.dop import penetration_depth
from ..analytic.resistance import Target
from ..cavity.level import cavity_settings, cavity_trajectory, sigma_table
from ..concrete import material as concrete, triaxial
from ..figures.hjc_scaling import hjc_scaling_figure
from ..figures.validation_levels import KEYS, validation_figure
from ..nose.geometry import make_nose
from ..nose.nstar import nstar
from ..paper import reference
from ..pipeline.config import machine_name
from ..pipeline.io import load_json, read_inference, read_rows, task, write_csv, write_rows
from ..shots.ladder import UserShot, output_fields, predict_rows, run
from ..shots.records import context_from_files
from ..studies import laboratory


def _optional(inputs, name):
    """A rule's named input, or None where the rule does not declare it."""
    return getattr(inputs, name) if name in inputs.keys() else None


def _committed(params, name):
    """The path of a committed record a rule passes as a study input param (pipeline.study_input), or None."""
    record = getattr(params, name, None)
    if record is None:
        return None
    if record["sha256"] == "missing":
        raise FileNotFoundError(f"{record['path']} is missing: snakemake -c2 {record['path']}")
    return record["path"]


def _predict_level(inputs, outputs, params, level, profile="full"):
    ctx = context_from_files(params.cfg, inputs.reference, _optional(inputs, "cal_cavity"),
                             _optional(inputs, "cal_fe") or _committed(params, "cal_fe"), profile, params.law)
    fields, rows = read_rows(inputs.shots)
    good, problems = predict_rows(rows, params.law, level, ctx,
                                  progress=lambda i, n: print(f"{level}: {i}/{n} shots", flush=True))
    for p in problems:
        print(f"skipped {p}")
    if problems:
        raise ValueError(f"{len(problems)} development shots could not be run at level {level}: {problems}")
    write_rows(outputs.csv, output_fields(fields, level), good)


@task
def validation_level(inputs, outputs, params):
    """Every development shot at the trajectory or cavity level (the cavity level with its DO1 calibration)."""
    _predict_level(inputs, outputs, params, params.level)


@task
def validation_fe(inputs, outputs, params):
    """Every development shot at the fe level of a mesh profile (its DO1 failure strain, its mesh scaled to the shot)."""
    _predict_level(inputs, outputs, params, "fe", params.profile)


def _validation_shots(inputs):
    """The development shots with every level's prediction and relative error (rel_err_KEY of laboratory.ROWS)."""
    frames = {"analytic": pd.read_csv(inputs.analytic), "trajectory": pd.read_csv(inputs.trajectory),
              "cavity": pd.read_csv(inputs.cavity), "fe": pd.read_csv(inputs.fe)}
    base = frames["analytic"][KEYS].copy()
    for level, f in frames.items():
        if list(f.shot_id) != list(base.shot_id):
            raise ValueError(f"the {level} predictions do not list the shots of the analytic ones")
        base[f"dop_{level}_m"] = f.dop_pred_m.to_numpy()
        base[f"rel_err_{level}"] = f.dop_pred_m.to_numpy() / base.dop_m.to_numpy() - 1
    for level, name in (("cavity", "laboratory"), ("fe", "fe_laboratory")):
        path = _optional(inputs, name)
        if path is None:
            continue
        lab = pd.read_csv(path)
        for key, prefix in ((f"{level}_laboratory", "series:"), (f"{level}_laboratory_fc_group", "fc_group:")):
            held = lab[lab.fold.str.startswith(prefix)].set_index("shot_id")
            if held.index.duplicated().any():
                raise ValueError(f"{path}: a shot is held out by two {prefix} folds")
            if not set(held.index) <= set(base.shot_id):
                raise ValueError(f"{path}: held-out shots that are not development shots")
            base[f"dop_{key}_m"] = base.shot_id.map(held.dop_pred_m)
            base[f"rel_err_{key}"] = base[f"dop_{key}_m"] / base.dop_m - 1
            base[f"series_{key}"] = base.shot_id.map(held.series)
        if base[f"rel_err_{level}_laboratory"].isna().any():
            raise ValueError(f"{path}: leave-one-series-out folds do not hold out every development shot")
    return base, frames


@task
def validation_levels(inputs, outputs, params):
    """Every level on the development shots, each scored out of its calibration's sample (laboratory.summary_rows):
    the shots table, the summary with the residual's slopes, the wall times and the figure."""
    shots, frames = _validation_shots(inputs)
    write_csv(shots, outputs.csv)
    timing = []
    for level in laboratory.LEVELS:
        if "wall_time_s" in frames[level]:
            w = frames[level].wall_time_s.to_numpy()
            timing.append({"level": level, "profile": params.profile, "shots": len(w), "total_wall_time_s": float(w.sum()),
                           "median_wall_time_per_shot_s": float(np.median(w)), "max_wall_time_per_shot_s": float(w.max())})
    summary = laboratory.summary_rows(shots, params.law)
    write_csv(summary, outputs.summary)
    write_csv(pd.DataFrame(timing), outputs.timing)
    validation_figure(shots, summary, outputs.png, params.dpi, params.law, params.profile)


@task
def hjc_scaling(inputs, outputs, params):
    """The HJC set the cavity and fe levels use at each concrete strength of the development shots and of the
    published sets (and at the rule's ends and Table 1's 48 MPa), with the fib Model Code 2010 values the rule
    scales by; the normalised strength of the rule beside triaxial criteria; the figure against the published sets."""
    refs = reference.load_reference(inputs.reference)
    base = concrete.configured(refs, params.cfg["concrete"])
    shots = pd.read_csv(inputs.shots)
    sets = pd.read_csv(inputs.sets)
    lo, hi = concrete.FC_RULE_RANGE
    fcs = sorted({*(shots.fc_MPa.to_numpy() * 1e6), *(f for f in sets.fc_MPa.to_numpy() * 1e6 if lo <= f <= hi),
                  lo, hi, base.fc})
    rows = []
    for fc in fcs:
        m = concrete.hjc_for_strength(float(fc), base)
        K = m.pc / m.muc
        E = 9 * K * m.G / (3 * K + m.G)
        E_code, T_code = concrete.elastic_modulus_mc2010(fc), concrete.tensile_strength_mc2010(fc)
        rows.append({"fc_MPa": fc / 1e6, "table1": bool(fc == base.fc), "pc_Pa": m.pc, "muc": m.muc, "G_Pa": m.G,
                     "K_Pa": K, "E_Pa": E, "poisson": (3 * K - 2 * m.G) / (2 * (3 * K + m.G)), "T_Pa": m.T,
                     "E_mc2010_Pa": E_code, "E_over_mc2010": E / E_code, "T_mc2010_Pa": T_code,
                     "T_over_mc2010": m.T / T_code})
    write_csv(pd.DataFrame(rows), outputs.csv)
    criteria = criteria_rows(base)
    write_csv(criteria, outputs.criteria)
    fc = np.linspace(lo, hi, 200)
    scaled = [concrete.hjc_for_strength(f, base) for f in fc]
    r = fc / base.fc
    curves = pd.DataFrame({"fc_MPa": fc / 1e6, "G": [m.G / 1e9 for m in scaled], "T": [m.T / 1e6 for m in scaled],
                           "pc": [m.pc / 1e6 for m in scaled], "G_former": base.G / 1e9 * np.sqrt(r),
                           "T_former": base.T / 1e6 * r ** (2 / 3)})
    for p in (1.0, 2.0, 5.0):
        sets[f"q_star_p{p:g}"] = [triaxial.hjc(p, s.A, s.B, s.N, s.smax) for s in sets.itertuples()]
    hjc_scaling_figure(curves, sets, criteria, outputs.png, params.dpi)


P_STARS = (0.5, 1.0, 2.0, 5.0, 10.0)
CRITERIA_FC_MPA = (25.0, 35.0, 48.0, 70.0, 100.0, 110.0)


def criteria_rows(base):
    """q* at each p* of P_STARS and fc of CRITERIA_FC_MPA: the rule's HJC surface (fc-invariant), Ottosen's MC90
    criterion and Attard & Setunge's (with the confinement it needs and whether that lies beyond its tests)."""
    rows = []
    for fc in CRITERIA_FC_MPA:
        m = concrete.hjc_for_strength(fc * 1e6, base)
        for p in P_STARS:
            q_as, s3 = triaxial.attard_setunge(p, fc * 1e6)
            rows.append({"fc_MPa": fc, "p_star": p, "q_star_rule": triaxial.hjc(p, m.A, m.B, m.N, m.smax),
                         "q_star_ottosen_mc90": triaxial.ottosen_mc90(p, fc * 1e6), "q_star_attard_setunge": q_as,
                         "attard_setunge_confinement_MPa": s3 / 1e6,
                         "attard_setunge_extrapolated": bool(s3 > triaxial.ATTARD_SETUNGE_MAX_CONFINEMENT)})
    return pd.DataFrame(rows)


def _timed(fn, repeat=3):
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def cell_deviation(table, reference, column, reference_column):
    """|table[column] / reference[reference_column] - 1| per Table 3 cell, the cells matched by (velocity_ms,
    nose), not by row position (the FE tables list the noses in another order than figures/table3.csv);
    every cell of either table must have its partner."""
    keys = ["velocity_ms", "nose"]
    pair = table[keys + [column]].rename(columns={column: "x"}).merge(
        reference[keys + [reference_column]].rename(columns={reference_column: "x_reference"}), on=keys, how="outer",
        validate="one_to_one", indicator=True)
    if (pair._merge != "both").any():
        raise ValueError(f"Table 3 cells without a partner: {pair.loc[pair._merge != 'both', keys].to_dict('records')}")
    return np.abs(pair.x.to_numpy() / pair.x_reference.to_numpy() - 1)


@task
def accuracy_cost(inputs, outputs, params):
    """Accuracy against cost over the ladder: each level's error against the DO1 shot and against the paper's
    simulated Table 3 column, and its own convergence study, beside its wall time per shot.

    Errors go to outputs.csv (machine-independent), wall times to outputs.timing: in-process timers for the
    short ones (the closed form and the cavity table, measured here; the trajectory tolerance sweep's) and
    the rules' benchmark records of the FE shot jobs.
    """
    refs = reference.load_reference(inputs.reference)
    measured = refs["table2.dop"].si
    rows, timing = [], []
    t3 = pd.read_csv(inputs.table3)
    dev = lambda pred: np.abs(pred / t3.paper_sim_m.to_numpy() - 1)
    do1 = load_json(inputs.cal_do1)
    # closed form: the stated S (no calibration) and the S calibrated on DO1
    nose = read_inference(inputs.do1)["nose"]
    data = do1["data"]
    n = nstar(nose)
    stated = Target(data["rho"], data["fc"], do1["S_stated_li_chen"])
    d_stated = float(penetration_depth(data["mass"], nose.radius, n, stated, data["vs"]))
    vs = np.full(100_000, data["vs"])
    per_shot = _timed(lambda: penetration_depth(data["mass"], nose.radius, n, stated, vs))[0] / vs.size
    for setting, cal, depth, pred in (("S stated (Li & Chen)", False, d_stated, t3.analytic_stated_S_m),
                                      ("S calibrated on DO1", True, measured + do1["residual_m"], t3.analytic_m)):
        rows.append({"level": "analytic", "setting": setting, "calibrated_on_do1": cal, "do1_depth_m": depth,
                     "do1_rel_error": depth / measured - 1, "table3_mean_abs_rel_dev": float(dev(pred).mean()),
                     "table3_max_abs_rel_dev": float(dev(pred).max()), "self_rel_error": np.nan, "self_reference": ""})
        timing.append({"level": "analytic", "setting": setting, "wall_time_per_shot_s": per_shot,
                       "timer": "in-process, Eq 9 vectorised over 1e5 shots"})
    # trajectory: the tolerance sweep (its error against the closed form of the same model)
    tr, tr_t = pd.read_csv(inputs.trajectory), pd.read_csv(inputs.trajectory_timing)
    tr = tr.merge(tr_t, on=["method", "rtol"])
    for r in tr[tr.method == "DOP853"].itertuples():
        rows.append({"level": "trajectory", "setting": f"DOP853 rtol {r.rtol:g}", "calibrated_on_do1": True,
                     "do1_depth_m": np.nan, "do1_rel_error": np.nan, "table3_mean_abs_rel_dev": np.nan,
                     "table3_max_abs_rel_dev": np.nan, "self_rel_error": r.rel_error, "self_reference": "Eq 9 (closed form)"})
        timing.append({"level": "trajectory", "setting": f"DOP853 rtol {r.rtol:g}", "wall_time_per_shot_s": r.wall_time_s,
                       "timer": "in-process (trajectory tolerance sweep)"})
    # cavity: the calibrated level at its configured mesh, and the zones study of the cavity solver
    cal = load_json(inputs.cal_cavity)
    cfg = params.cfg["cavity"]
    mesh, controls = cavity_settings(cfg)
    material = concrete.configured(refs, params.cfg["concrete"], strength_scale=cal["strength_scale"])
    t_table, (table, _) = _timed(lambda: sigma_table(material, cfg["velocities"], nose.radius, mesh, controls), repeat=1)
    t_shot, _ = _timed(lambda: cavity_trajectory(nose, data["mass"], data["vs"], table, tuple(cal["data"]["effects"]),
                                                 rtol=cfg["rtol"]))
    zones = pd.read_csv(inputs.cavity_study)
    zones = zones[zones.study == "zones"].merge(pd.read_csv(inputs.cavity_study_timing), on=["study", "setting"])
    expansions = len(cfg["velocities"]) + len(cfg["quasi_static_from"])
    if cfg["zones"] not in set(zones.setting.astype(int)):
        raise ValueError(f"the cavity solver study has no run at the configured {cfg['zones']} zones")
    for z in zones.itertuples():
        default = int(z.setting) == cfg["zones"]
        rows.append({"level": "cavity", "setting": f"{int(z.setting)} zones", "calibrated_on_do1": True,
                     "do1_depth_m": measured + cal["residual_m"] if default else np.nan,
                     "do1_rel_error": cal["relative_residual"] if default else np.nan,
                     "table3_mean_abs_rel_dev": float(dev(t3.cavity_m).mean()) if default else np.nan,
                     "table3_max_abs_rel_dev": float(dev(t3.cavity_m).max()) if default else np.nan,
                     "self_rel_error": z.rel_error_vs_finest, "self_reference": f"{int(zones.setting.max())} zones"})
        ratio = z.wall_time_s / float(zones.wall_time_s[zones.setting == cfg["zones"]].iloc[0])
        timing.append({"level": "cavity", "setting": f"{int(z.setting)} zones", "wall_time_per_shot_s": (t_table + t_shot) * ratio,
                       "timer": (f"in-process: one sigma_n table of {expansions} expansions and one trajectory (a shot on a "
                                 f"new concrete) at {cfg['zones']} zones" + ("" if default else ", times the solver study's "
                                 "ratio of expansion times at this zone count"))})
    # fe: Table 3 at every mesh profile built, each with the failure strain calibrated on DO1 at its mesh
    tables = {p: pd.read_csv(f) for p, f in zip(params.fe_profiles, inputs.fe_tables)}
    finest = min(params.fe_profiles, key=lambda p: tables[p].element_size_m.iloc[0])
    finest_across = load_json(inputs.fe_calibrations[params.fe_profiles.index(finest)])["elements_across_radius"]
    for p, cal_path in zip(params.fe_profiles, inputs.fe_calibrations):
        t, c = tables[p], load_json(cal_path)
        fe_dev = cell_deviation(t, t3, "fe_m", "paper_sim_m")
        self_err = cell_deviation(t, tables[finest], "fe_m", "fe_m").mean() if p != finest else 0.0
        setting = f"{c['elements_across_radius']:.3g} elements across ({p})"
        rows.append({"level": "fe", "setting": setting, "calibrated_on_do1": True, "do1_depth_m": measured + c["residual_m"],
                     "do1_rel_error": c["relative_residual"], "table3_mean_abs_rel_dev": float(fe_dev.mean()),
                     "table3_max_abs_rel_dev": float(fe_dev.max()), "self_rel_error": self_err,
                     "self_reference": f"{finest_across:.3g} elements across ({finest}), mean over Table 3"})
        walls = [float(pd.read_csv(f, sep="\t").s.iloc[0]) for f in inputs.fe_benchmarks if f"/fe_shot_{p}_" in f]
        timing.append({"level": "fe", "setting": setting, "wall_time_per_shot_s": float(np.mean(walls)),
                       "timer": f"the benchmark records of the {len(walls)} Table 3 shot jobs (mean; one thread each, "
                                "two jobs side by side; process start, kernel loading and outputs included)"})
    write_csv(pd.DataFrame(rows), outputs.csv)
    write_csv(pd.DataFrame(timing).assign(machine=machine_name()), outputs.timing)


SWEEP_LENGTH_KEYS = ("length", "tip_radius")  # nose keys given in shank radii; the others (psi) are dimensionless


def sweep_grid(sw):
    """The sweep's shots in order: every nose at the first velocity, then every nose at the next, and so on (the
    first n shots of the grid span the noses before the velocities)."""
    a = sw["radius"]
    noses = {name: make_nose(spec["kind"], radius=a, **{k: v * a if k in SWEEP_LENGTH_KEYS else v
                                                          for k, v in spec.items() if k != "kind"})
             for name, spec in sw["noses"].items()}
    return [(name, nose, float(v)) for v in sw["velocities"] for name, nose in noses.items()]


@task
def sweep_level(inputs, outputs, params):
    """The first n shots of the sweep's grid at one level (its cost is the rule's benchmark record)."""
    sw = params.cfg["sweep"]
    grid = sweep_grid(sw)
    n = int(params.n)
    if n > len(grid):
        raise ValueError(f"sweep.sizes.{params.level}: {n} shots, the grid has {len(grid)}")
    ctx = context_from_files(params.cfg, inputs.reference, _optional(inputs, "cal_cavity"), _optional(inputs, "cal_fe"),
                             sw["fe_profile"])
    rows = []
    for k, (name, nose, v) in enumerate(grid[:n]):
        shot = UserShot(nose, sw["mass"], v, sw["fc"], sw["density"], sw["length"], name)
        r = run(shot, params.level, ctx)
        rows.append({"nose": name, "nstar": nstar(nose), "velocity_ms": v, **r.record()})
        print(f"{params.level}: {k + 1}/{n} shots ({name} at {v:g} m/s: {r.depth_m:.4g} m)", flush=True)
    write_csv(pd.DataFrame(rows), outputs.csv)



@task
def validation_nose_pairs(inputs, outputs, params):
    """Each level's error on the contrast between two noses, scored on the development shots' measured nose pairs
    (studies.nose_pairs) from the levels' predictions of validation_levels (their primary scoring)."""
    from ..studies import nose_pairs
    shots = pd.read_csv(inputs.shots)
    levels = pd.read_csv(inputs.summary)
    levels = levels[levels.primary.astype(str) == "True"]
    predictions = {(r.level, r.calibration): f"dop_{r.predictions}_m" for r in levels.itertuples()}
    table = nose_pairs.pairs(shots, {f"{lv}|{cal}": col for (lv, cal), col in predictions.items()})
    table[["level", "calibration"]] = table.level.str.split("|", n=1, expand=True)
    summary = nose_pairs.summary(table.assign(level=table.level + "|" + table.calibration))
    summary[["level", "calibration"]] = summary.level.str.split("|", n=1, expand=True)
    first = ["level", "calibration"]
    write_csv(table[first + [c for c in table.columns if c not in first]], outputs.csv)
    write_csv(summary[first + [c for c in summary.columns if c not in first]], outputs.summary)
