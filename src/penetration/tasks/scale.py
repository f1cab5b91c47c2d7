"""Tasks of the scale effect (``scale``): a level's one factor calibrated on the laboratory shots with each variant
of the effect (concrete.size) and without it, by the protocol of validation.laboratory, each fold scored on the shots
it held out, and DO1 (140 mm) predicted by the fold of all laboratory shots: a test no fit has seen."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..analytic.empirical import EMPIRICAL_DEPTHS, NDRC_NOSE_FACTORS
from ..concrete.size import SizeEffect, resistance_factor
from ..figures.scale import similarity_figure
from ..nose.geometry import Ogive
from ..paper import reference
from ..pipeline.config import scale_grid
from ..pipeline.io import load_json, read_inference, read_rows, task, write_csv
from ..shots.ladder import UserShot, run
from ..shots.records import context_from_files, with_scale_effect
from ..studies.laboratory import FITTED, Protocol
from ..studies.fe_results import CONTRASTS
from ..studies.scale import do1_gap, split_summary
from .common import PLAIN, do1_shot, scene_from_inputs
from .laboratory import calibrate_on_laboratory, grid_runs_from, grid_runs_from_table, write_grid_piece


def variant_columns(name, effect: SizeEffect | None):
    """The columns that say which variant a row belongs to."""
    if effect is None:
        return {"variant": name, "mechanisms": "none", "beyond": "", "aggregate_m": np.nan, "lambda0": np.nan,
                "transitional_size_m": np.nan}
    uses_fracture = "fracture" in effect.mechanisms
    return {"variant": name, "mechanisms": "+".join(effect.mechanisms),
            "beyond": effect.beyond if "rate" in effect.mechanisms else "",
            "aggregate_m": effect.aggregate if uses_fracture else np.nan,
            "lambda0": effect.lambda0 if uses_fracture else np.nan,
            "transitional_size_m": effect.transitional_size if uses_fracture else np.nan}


@task
def scale_validation(inputs, outputs, params):
    """The scale effect's variants at one level: the calibrations (csv), the held-out predictions, the summary of
    each variant (the two series' fitted factors and their ratio, the pooled leave-one-series-out errors) and DO1."""
    cfg, level = params.cfg, params.level
    lab, study = cfg["validation"]["laboratory"], cfg["scale_effect"]
    profile = study["fe_profile"]
    protocols = {name: Protocol.from_config(lab, scale_grid(cfg, level, name)) for name in study["levels"][level]}
    _, rows = read_rows(inputs.shots)
    refs = reference.load_reference(inputs.reference)
    mass, vs, depth = do1_shot(refs, params.shot)
    nose = read_inference(inputs.do1)["nose"]
    fits, predictions, do1 = [], [], []
    for name in study["levels"][level]:
        effect = SizeEffect.from_spec(study["variants"][name])
        ctx = context_from_files(cfg, inputs.reference, profile=profile)
        ctx.size = effect
        print(f"{level}, variant {name}: calibrating on {len(rows)} laboratory shots", flush=True)
        pieces = (params.grids or {}).get(name)
        column = FITTED[level][1]
        own = protocols[name]
        if isinstance(pieces, dict):   # the variant without the effect: the laboratory calibration's own grid
            grid_runs = lambda rs, p=pieces, g=own.grid: grid_runs_from_table(p["table"], p["timing"], rs, g, column)
        elif pieces is not None:       # the grid in committed pieces, one per value
            grid_runs = lambda rs, paths=pieces, g=own.grid: grid_runs_from(paths, rs, g, column)
        else:
            grid_runs = None
        f, p, _, timing = calibrate_on_laboratory(level, ctx, rows, own, params.shots_path,
                                                  lambda m: print("  " + m, flush=True), grid_runs)
        cols = variant_columns(name, effect)
        fits.append(f.assign(**cols, grid_wall_time_s=float(timing.wall_time_s.iloc[0])))
        predictions.append(p.assign(level=level, **cols))
        value = float(f.loc[f.fold == "all", "value"].iloc[0])
        setattr(ctx, FITTED[level][0], value)
        shot = UserShot(nose, mass, vs, refs["table2.fc"].si, ctx.base.rho0, label="DO1",
                        length=refs["table2.length"].si if level == "fe" else None)
        r = run(shot, level, ctx)
        do1.append({"level": level, **cols, "calibration": "laboratory (fold all)", "parameter": FITTED[level][1],
                    "value": value, "dop_pred_m": r.depth_m, "dop_m": depth, "rel_error": r.depth_m / depth - 1,
                    "status": r.status})
        print(f"  DO1: {r.depth_m:.4g} m against the measured {depth:.4g} m", flush=True)
    fits, predictions, do1 = pd.concat(fits), pd.concat(predictions), pd.DataFrame(do1)
    write_csv(fits, outputs.csv)
    write_csv(predictions, outputs.predictions)
    write_csv(split_summary(fits, predictions, do1, list(lab["series"])), outputs.summary)
    write_csv(do1, outputs.do1)


def calibrated_context(cfg, reference_path, calibrations, level, name, where):
    """The levels' context with variant ``name`` of the scale effect and ``level``'s factor as scale_validation
    fitted it on all laboratory shots (``calibrations``: its calibration tables), the fe level at the study's mesh
    profile (scale_effect.fe_profile); ``where`` names the config entry that asks for it in the error when there is
    none."""
    profile = cfg["scale_effect"]["fe_profile"] if level == "fe" else "full"
    ctx = with_scale_effect(context_from_files(cfg, reference_path, profile=profile), cfg, calibrations, level, name,
                            where)
    return ctx, float(getattr(ctx, FITTED[level][0]))


def similar_shots(spec, refs):
    """The similarity figure's shots: an ogive of the spec's CRH at each calibre, the mass DO1's M/d^3 times d^3 and
    the length (read by the fe level only) DO1's L/d times d."""
    per_volume = refs["table2.mass"].si / refs["table2.diameter"].si ** 3
    per_calibre = refs["table2.length"].si / refs["table2.diameter"].si
    return [UserShot(Ogive(spec["crh"], d / 2), per_volume * d ** 3, spec["velocity"], spec["fc"], spec["density"],
                     label=f"{d * 1e3:g} mm", length=per_calibre * d) for d in spec["calibres"]]


@task
def scale_similarity(inputs, outputs, params):
    """Depth over calibre against calibre under geometric similarity at each level, with each variant's factor
    calibrated on the laboratory shots (scale_validation, fold all), and the empirical formulas' size laws."""
    cfg = params.cfg
    spec = cfg["scale_effect"]["similarity"]
    refs = reference.load_reference(inputs.reference)
    shots = similar_shots(spec, refs)
    calibrations = pd.concat([pd.read_csv(p) for p in inputs.calibrations])
    rows = []
    for level, variants in spec["levels"].items():
        for name in variants:
            ctx, value = calibrated_context(cfg, inputs.reference, calibrations, level, name,
                                            f"scale_effect.similarity.levels.{level}")
            for s in shots:
                r = run(s, level, ctx)
                d = 2 * s.nose.radius
                rows.append({"kind": "level", "level": level, **variant_columns(name, ctx.size),
                             "parameter": FITTED[level][1], "value": value, "calibre_m": d,
                             "mass_kg": s.mass, "velocity_ms": s.velocity, "depth_m": r.depth_m,
                             "depth_over_calibre": r.depth_m / d, "status": r.status})
        print(f"{level}: {len(variants)} variants at {len(shots)} calibres", flush=True)
    for name, depth in EMPIRICAL_DEPTHS.items():
        args = ((NDRC_NOSE_FACTORS[spec["ndrc_nose"]],) if name == "ndrc" else ())
        for s in shots:
            d = 2 * s.nose.radius
            x = float(depth(s.mass, d, s.fc, s.velocity, *args))
            rows.append({"kind": "empirical", "level": name, "variant": "", "calibre_m": d, "mass_kg": s.mass,
                         "velocity_ms": s.velocity, "depth_m": x, "depth_over_calibre": x / d, "status": "formula"})
    table = pd.DataFrame(rows)
    write_csv(table, outputs.csv)
    similarity_figure(table, spec, outputs.png, params.dpi)


@task
def scale_table3(inputs, outputs, params):
    """Table 3 (its three noses at its four velocities, all at 140 mm) at each level with each variant's factor
    calibrated on the laboratory shots: the depths and the nose contrasts, and each contrast's change from the
    variant without the effect (points): all shots share one calibre, so the effect can move a contrast only
    through the depths' nonlinearity in the resistance and through the velocity in the rate factor."""
    cfg = params.cfg
    study = cfg["scale_effect"]
    sc = scene_from_inputs(inputs, PLAIN)
    calibrations = pd.concat([pd.read_csv(p) for p in inputs.calibrations])
    rows = []
    for level in sorted(set(calibrations.level)):
        for name in study["similarity"]["levels"].get(level, []):
            ctx, _ = calibrated_context(cfg, inputs.reference, calibrations, level, name,
                                        f"scale_effect.similarity.levels.{level}")
            for v in sc.velocities:
                depth = {n: run(UserShot(nose, sc.mass, float(v), sc.target.fc, sc.target.rho, label=n), level,
                                ctx).depth_m for n, nose in sc.noses.items()}
                for contrast, (num, den) in CONTRASTS.items():
                    rows.append({"level": level, **variant_columns(name, ctx.size), "velocity_ms": float(v),
                                 "contrast": contrast, "ratio": depth[num] / depth[den],
                                 f"depth_{num}_m": depth[num], f"depth_{den}_m": depth[den]})
    table = pd.DataFrame(rows)
    base = table[table.variant == "none"].set_index(["level", "velocity_ms", "contrast"]).ratio
    key = pd.MultiIndex.from_frame(table[["level", "velocity_ms", "contrast"]])
    table["change_points"] = 100 * (table.ratio.to_numpy() - base.reindex(key).to_numpy())
    write_csv(table, outputs.csv)


@task
def scale_fe_grid_value(inputs, outputs, params):
    """Every laboratory shot at the fe level of a mesh profile with one failure strain of the grid and one variant
    of the scale effect (a piece, committed, as the laboratory calibration's own grid: fe_laboratory_grid_value)."""
    write_grid_piece(inputs, outputs, params, SizeEffect.from_spec(params.cfg["scale_effect"]["variants"][params.variant]))


@task
def scale_cavity_grid_value(inputs, outputs, params):
    """Every laboratory shot at the cavity level with one strength scale of the grid and one variant of the scale
    effect (a piece, committed: a variant's grid takes about half an hour, so the study runs over sessions)."""
    write_grid_piece(inputs, outputs, params, SizeEffect.from_spec(params.cfg["scale_effect"]["variants"][params.variant]),
                     level="cavity")


# the DO1 calibration of each level as the paper build records it: (the record's key of the value, what it is)
DO1_FACTOR = {"analytic": ("S_ratio_to_stated", "factor on Li & Chen's S"),
              "cavity": ("strength_scale", "HJC strength scale"),
              "fe": ("value", "failure strain fs (a larger fs: a tougher target)")}


@task
def scale_do1_gap(inputs, outputs, params):
    """How much calibre dependence DO1 asks of each level: the level's one factor fitted on each laboratory series
    alone (variant none of scale_validation) beside the factor its DO1 calibration needs, and the factor on the
    resistance that each mechanism of the scale effect gives at the two series' calibres and velocities (their
    medians) and at DO1's: a diagnosis from calibrations, no prediction."""
    cfg = params.cfg
    protocol = Protocol.from_config(cfg["validation"]["laboratory"])
    series = protocol.series
    shots = pd.read_csv(inputs.shots)
    shots["series"] = shots.source.map(protocol.series_of)
    points = {}
    for name in series:
        mine = shots[shots.series == name]
        if mine.diameter_m.nunique() != 1:
            raise ValueError(f"{inputs.shots}: series {name} has calibres {sorted(mine.diameter_m.unique())}; "
                             "the gap needs one calibre per series")
        points[name] = (float(mine.diameter_m.iloc[0]), float(mine.velocity_ms.median()))
    refs = reference.load_reference(inputs.reference)
    _, vs, _ = do1_shot(refs, params.shot)
    points["do1"] = (refs["table2.diameter"].si, vs)
    records = {"analytic": load_json(inputs.analytic), "cavity": load_json(inputs.cavity),
               "fe": pd.read_csv(inputs.fe).iloc[0].to_dict()}
    values = []
    for path in inputs.calibrations:
        fits = pd.read_csv(path)
        fits = fits[fits.variant == "none"]
        level = fits.level.iloc[0]
        key, quantity = DO1_FACTOR[level]
        by_series = {s: float(fits.loc[fits.fit_series == s, "value"].iloc[0]) for s in series}
        values.append({"kind": "level", "name": level, "quantity": quantity,
                       **{f"value_{s}": v for s, v in by_series.items()}, "value_do1": float(records[level][key]),
                       "do1_value_from": f"{level}'s calibration on DO1"})
    for name, spec in cfg["scale_effect"]["variants"].items():
        effect = SizeEffect.from_spec(spec)
        if effect is None:
            continue
        values.append({"kind": "mechanism", "name": name, "quantity": "factor on the resistance at V/d ("
                       + "+".join(effect.mechanisms) + ")",
                       **{f"value_{p}": float(resistance_factor(effect, d, v)) for p, (d, v) in points.items()},
                       "do1_value_from": "the published relation at DO1's calibre and velocity"})
    write_csv(do1_gap(values, points), outputs.csv)
