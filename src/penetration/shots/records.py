"""The committed records a user's shot reads: the levels' context as the pipeline builds it (the config, the paper's
reference values and the DO1 or laboratory calibrations under a pipeline directory) and each level's validated
accuracy (the validation of the development shots). The command line and the pipeline's tasks build a shot's context
here; the physics of the levels is ``ladder``'s."""
from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from ..cavity.level import cavity_settings
from ..concrete import material as concrete
from ..concrete.size import SizeEffect
from ..errors import ParameterError
from ..fe.shot import Settings
from ..paper import reference
from ..pipeline.config import element_sizes, load_with
from ..pipeline.io import load_json, read_rows
from ..pipeline.records import RecordError, read_record
from ..pipeline.scenes import SIZE_LEVEL  # the level whose scale-effect calibration a level takes
from ..studies.laboratory import FITTED
from ..studies.scale import recommended_variant
from .ladder import Context

# this package's checkout (its workflow/schemas/), where it is one
PACKAGE_ROOT = Path(__file__).resolve().parents[3]
from .trust import ValidatedRange


def context_from_files(cfg, reference_path, cavity_cal=None, fe_cal=None, profile="full", strength_law=None) -> Context:
    """The levels' context from the config mapping (its concrete, cavity and validation sections), the reference CSV
    and the DO1 calibration files (None: that level is left without its calibration and refuses to run, saying how
    to build it). The base concrete is concrete.configured's, as at the cavity and fe levels. A mapping without an fe
    section leaves the fe level unconfigured (the trajectory and cavity levels do not read it)."""
    refs = reference.load_reference(reference_path)
    if "fe" in cfg and "element_size" not in cfg["fe"]["profiles"][profile]:   # the config file as written
        element_sizes(cfg, 0.5 * refs[cfg["projectile"]["diameter"]].si)
    mesh, controls = cavity_settings(cfg["cavity"])
    fe = {"fe_settings": Settings.from_config(cfg["fe"], profile), "fe_target_radius": cfg["fe"]["target_radius"]} if "fe" in cfg else {}
    ctx = Context(base=concrete.configured(refs, cfg["concrete"]),
                  strength_law=strength_law or cfg["validation"]["strength_law"],
                  cavity_velocities=tuple(cfg["cavity"]["velocities"]), cavity_mesh=mesh, cavity_controls=controls,
                  cavity_rtol=cfg["cavity"]["rtol"], **fe)
    if cavity_cal is not None:
        cal = _calibration(cavity_cal, "strength_scale")
        ctx.strength_scale = cal["strength_scale"]
        ctx.strength_scale_source = f"{cal['source']}, {cavity_cal}"
    if fe_cal is not None:
        if "fe" not in cfg:
            raise ValueError(f"{fe_cal}: an fe calibration needs the config's fe section (its mesh), which is missing")
        cal = _calibration(fe_cal, "fs")
        if not math.isclose(cal["element_size"], ctx.fe_settings.element_size):
            raise ValueError(f"{fe_cal}: calibrated at element size {cal['element_size']} m, the {profile} profile "
                             f"meshes at {ctx.fe_settings.element_size} m")
        ctx.failure_strain = cal["fs"]
        ctx.fe_reference_radius = cal["element_size"] * cal["elements_across_radius"]
        ctx.failure_strain_source = f"{cal['source']} at {cal['elements_across_radius']:.3g} elements across the radius, {fe_cal}"
    return ctx


# The committed records of the calibrations the command line's levels carry over, relative to the pipeline's
# directory: the DO1 calibrations (rules cavity_calibration_record and fe_calibration_record) and the cavity level's
# calibration on the laboratory shots (rule calibrate_cavity_laboratory, its fold ``all``)
CAVITY_CALIBRATION = "figures/calibration_cavity_do1.csv"
FE_CALIBRATION = "figures/fe/{profile}/calibration_fe_do1.csv"
CAVITY_LABORATORY = "figures/calibration_cavity_laboratory.csv"
FE_LABORATORY = "figures/fe/{profile}/calibration_fe_laboratory.csv"
CALIBRATIONS = ("laboratory", "do1")


def _calibration(path, key) -> dict:
    """A calibration as the levels read it: a rule's JSON (results/), a committed one-row DO1 record (figures/) whose
    ``value`` is the fitted ``key``, or a laboratory record (its fold ``all``); ``source`` says which it is. The
    committed records go through pipeline.records.read_record (an error names the file, row and column)."""
    if str(path).endswith(".json"):
        return {"source": "calibrated on DO1", **load_json(path)}
    rows = read_record(path, {"parameter": "text", "value": "number"},
                       {"fold": "text", "element_size_m": "number", "elements_across_radius": "number"},
                       what=f"a calibration of {key}")
    source = "fitted on the laboratory shots" if "fold" in rows[0] else "calibrated on DO1"
    if "fold" in rows[0]:
        rows = [r for r in rows if r["fold"] == "all"]
        if len(rows) != 1:
            raise RecordError(f"record {path}", "fold", f"{len(rows)} rows of fold all",
                              "exactly one row of fold 'all' (a laboratory calibration)")
    row = rows[0]
    if row["parameter"] != key:
        raise RecordError(f"record {path}", "parameter", row["parameter"], f"{key}: a calibration of {key}, not of "
                          f"{row['parameter']} (a record of another level's calibration)")
    if not row["value"] > 0:
        raise RecordError(f"record {path}", "value", row["value"], f"{key} > 0")
    out = {key: row["value"], "source": source}
    if row.get("element_size_m") is not None:
        if row.get("elements_across_radius") is None:
            raise RecordError(f"record {path}", "elements_across_radius", None, "a number beside element_size_m")
        out.update(element_size=row["element_size_m"], elements_across_radius=row["elements_across_radius"])
    elif key == "fs":
        raise RecordError(f"record {path}", "element_size_m", None, "the mesh's element size (an fe calibration)")
    return out


# The scale effect's study (rule scale_validation): each level's factor fitted on the laboratory shots with each
# variant of the effect (fold all: what a user's shot gets), and its validation (leave one series out; DO1)
SCALE_CALIBRATION = "figures/scale/calibration_{level}.csv"
SCALE_VALIDATION = "figures/scale/validation_{level}.csv"
NO_SIZE = "none"
AUTO_SIZE = "auto"


def scale_calibration_table(path) -> pd.DataFrame:
    """The scale effect's calibration record (rule scale_validation), read through the checked reader."""
    rows = read_record(path, {"level": "text", "fold": "text", "variant": "text", "value": "number"},
                       what="the scale effect's calibration, rule scale_validation")
    return pd.DataFrame(rows)


def scale_validation_rows(path) -> list:
    """The scale effect's validation record (rule scale_validation), read through the checked reader."""
    return read_record(path, {"level": "text", "variant": "text", "loso_median_abs_rel_err": "number",
                              "loso_p90_abs_rel_err": "number", "split_ratio": "number", "do1_rel_error": "number"},
                       {"do1_pred_m": "number", "loso_mean_rel_err": "number", "loso_within_10pct": "count",
                        "loso_shots": "count"},
                       what="the scale effect's validation, rule scale_validation")


CONFIG_SCHEMA = "workflow/schemas/config.schema.json"


def root_config(root) -> dict:
    """The pipeline config under ``root`` (workflow/config.yaml) read strictly (a key given twice, NaN or inf refused)
    and checked against the config schema under ``root`` (this package's where the root has none), so that a config
    the pipeline would refuse never answers a user's shot silently."""
    import json

    root = Path(root)
    schema_path = root / CONFIG_SCHEMA if (root / CONFIG_SCHEMA).is_file() else PACKAGE_ROOT / CONFIG_SCHEMA
    schema = json.loads(schema_path.read_text()) if schema_path.is_file() else {}
    return load_with(root / "workflow/config.yaml", schema)




def size_problem(cfg, root, level, variant, profile="full", strength_law=None):
    """Why a shot at ``level`` cannot run with ``variant`` of the scale effect (None: it can): a variant the config
    does not have, a level the study did not calibrate it at, another S law than the study's, another fe mesh than
    the study's, or a calibration not built under ``root``."""
    study = cfg["scale_effect"]
    at = SIZE_LEVEL[level]
    calibration = SCALE_CALIBRATION.format(level=at)
    if variant not in study["variants"]:
        return f"one of {[AUTO_SIZE, *sorted(study['variants'])]} (the config's scale_effect.variants)"
    if variant not in study["levels"].get(at, []):
        return (f"a variant the scale effect's study calibrates at the {at} level: "
                f"{study['levels'].get(at, [])} (workflow/config.yaml, scale_effect.levels)")
    law = cfg["validation"]["strength_law"]
    if at == "analytic" and strength_law not in (None, law):
        return f"--strength-law {law} with the scale effect (its factor on S was fitted on {law}'s S)"
    if level == "fe" and profile != study["fe_profile"]:
        return f"--profile {study['fe_profile']} with the scale effect (its failure strain was fitted at that mesh)"
    path = Path(root) / calibration
    if not path.is_file():
        return f"a calibrated variant: {calibration} is missing under {root} (snakemake -c2 {calibration})"
    table = scale_calibration_table(path)
    if not ((table.level == at) & (table.variant == variant) & (table.fold == "all")).any():
        return f"a variant {calibration} has (snakemake -c2 {calibration} rebuilds it with the config's variants)"
    return None


def chosen_size(root, level, size, profile="full", strength_law=None) -> tuple[str, str]:
    """(the variant of the scale effect a shot at ``level`` runs with, why): ``size`` itself, or for ``auto`` the
    variant that meets every goal of the committed validation at the level (studies.scale.recommended_variant)
    where it can run there (size_problem), else none."""
    if size != AUTO_SIZE:
        return size, "chosen (--size)"
    at = SIZE_LEVEL[level]
    validation = SCALE_VALIDATION.format(level=at)
    path = Path(root) / validation
    if not path.is_file():
        return NO_SIZE, f"no validation of the scale effect at the {at} level ({validation})"
    best = recommended_variant(scale_validation_rows(path))
    if best is None:
        return NO_SIZE, f"no variant meets the validation's goals at the {at} level ({validation})"
    problem = size_problem(root_config(root), root, level, best, profile, strength_law)
    if problem is not None:
        return NO_SIZE, f"{best} meets every goal at the {at} level ({validation}) but needs {problem}"
    return best, f"it meets every goal of the validation at the {at} level ({validation})"


def with_scale_effect(ctx: Context, cfg, calibrations, level, variant, where="--size") -> Context:
    """``ctx`` with ``variant`` of the config's scale_effect.variants and ``level``'s factor fitted with it on every
    laboratory shot (``calibrations``: the study's calibration table, its fold ``all``); ``where`` names the setting
    in the errors. The factor is a calibration on the laboratory shots, and the context's source says so."""
    variants = cfg["scale_effect"]["variants"]
    owner = "argument" if where.startswith("-") else "config"
    if variant not in variants:
        raise ParameterError(owner, where, variant, f"one of {sorted(variants)} (the config's scale_effect.variants)")
    cal = calibrations[(calibrations.level == level) & (calibrations.variant == variant) & (calibrations.fold == "all")]
    if len(cal) != 1:
        raise ParameterError(owner, where, variant,
                             f"a variant calibrated at level {level}: {SCALE_CALIBRATION.format(level=level)} has "
                             f"{sorted(set(calibrations.variant[calibrations.level == level]))} (build it with "
                             f"snakemake -c2 {SCALE_CALIBRATION.format(level=level)})")
    attr, _, what = FITTED[level]
    value = float(cal.value.iloc[0])
    ctx.size = SizeEffect.from_spec(variants[variant])
    setattr(ctx, attr, value)
    if hasattr(ctx, f"{attr}_source"):
        setattr(ctx, f"{attr}_source", f"{what} with the scale effect {variant} ({SCALE_CALIBRATION.format(level=level)})")
    return ctx


def scale_effect_context(ctx: Context, root, level, variant, profile="full", strength_law=None) -> Context:
    """``ctx`` (the pipeline's, under ``root``) with the scale effect's ``variant`` and its calibration at ``level``
    (the analytic level's for the trajectory level, SIZE_LEVEL) from the committed study (with_scale_effect);
    ``none`` leaves it as it is. Refused, naming what it needs, where size_problem finds a problem."""
    if variant == NO_SIZE:
        return ctx
    root = Path(root)
    cfg = root_config(root)
    problem = size_problem(cfg, root, level, variant, profile, strength_law)
    if problem is not None:
        raise ParameterError("argument", "--size", variant, problem)
    at = SIZE_LEVEL[level]
    return with_scale_effect(ctx, cfg, scale_calibration_table(root / SCALE_CALIBRATION.format(level=at)), at, variant)


def scale_effect_accuracy(root, level, variant):
    """The validation of ``variant`` at ``level`` (a row of figures/scale/validation_LEVEL.csv as a dict, with DO1's
    calibre from the reference as ``do1_diameter_m``), or None."""
    root = Path(root)
    level = SIZE_LEVEL[level]
    path = root / SCALE_VALIDATION.format(level=level)
    if variant == NO_SIZE or not path.is_file():
        return None
    rows = [r for r in scale_validation_rows(path) if r["level"] == level and r["variant"] == variant]
    if len(rows) != 1:
        return None
    cfg = root_config(root)
    refs = reference.load_reference(root / cfg["reference"])
    return {**rows[0], "do1_diameter_m": refs["table2.diameter"].si}


def cavity_calibration_path(root, calibration) -> Path:
    """The committed record of the cavity level's strength scale: ``laboratory``, ``do1`` or a file (a record of
    either form: a laboratory table or a one-row calibration with parameter strength_scale)."""
    root = Path(root)
    if calibration == "laboratory":
        return root / CAVITY_LABORATORY
    if calibration == "do1":
        return root / CAVITY_CALIBRATION
    return Path(calibration)


def fe_calibration_record(root, profile, calibration) -> tuple[Path, str]:
    """The committed record of the fe level's failure strain at ``profile``'s mesh and which calibration it is:
    its laboratory one unless ``calibration`` is ``do1`` or the profile has none, else DO1's."""
    lab = Path(root) / FE_LABORATORY.format(profile=profile)
    if calibration != "do1" and lab.is_file():
        return lab, "laboratory"
    return Path(root) / FE_CALIBRATION.format(profile=profile), "do1"


def context_from_pipeline(root=".", profile="full", strength_law=None, calibration="laboratory") -> Context:
    """The levels' context as the pipeline builds it, from the files under ``root``: the config, the reference and
    the committed calibration records (a level whose record is missing refuses to run, saying which file to build).

    ``calibration``: ``laboratory`` (the default: the cavity level's strength scale and the fe level's failure strain
    at the profile's mesh fitted on the laboratory shots; where the profile has no fe laboratory record the fe level
    carries its DO1 failure strain over, saying so in its source), ``do1`` (both levels calibrated on DO1) or the path
    of a cavity calibration record (the fe level then as with ``laboratory``)."""
    root = Path(root)
    cfg = root_config(root)  # the strict loader (a key given twice, NaN or inf refused) and the config schema
    cav = cavity_calibration_path(root, calibration)
    if calibration not in CALIBRATIONS and not cav.is_file():
        raise ParameterError("argument", "--calibration", calibration, f"one of {list(CALIBRATIONS)} or an existing "
                             "calibration record (CSV)")
    fe, fe_calibration = fe_calibration_record(root, profile, calibration)
    ctx = context_from_files(cfg, root / cfg["reference"], cav if cav.is_file() else None, fe if fe.is_file() else None,
                             profile, strength_law)
    if not cav.is_file():
        ctx.strength_scale_record = str(cav.relative_to(root)) if cav.is_relative_to(root) else str(cav)
    if fe.is_file() and fe_calibration == "do1" and calibration != "do1":
        ctx.failure_strain_source += f" (the {profile} mesh has no laboratory calibration: DO1's)"
    ctx.fe_profile = profile
    return ctx


VALIDATION_SUMMARY = "figures/fe/{profile}/validation_levels_summary.csv"


def validated_accuracy(root=".", profile="full", calibration="laboratory"):
    """(the development shots' ValidatedRange, level -> its errors on them) from the committed outputs under
    ``root`` (the config's validation.shots and figures/fe/PROFILE/validation_levels_summary.csv): per level its
    primary row; for the calibrated levels the row of the calibration the level runs with (``calibration``; the fe
    level's is DO1's where the profile has no laboratory record, as context_from_pipeline takes it). A level whose
    calibration has no row (a record of the user's own, or a validation built before that calibration) is left out.
    None where either file is missing."""
    root = Path(root)
    summary = root / VALIDATION_SUMMARY.format(profile=profile)
    try:
        cfg = root_config(root)
        _, rows = read_rows(root / cfg["validation"]["shots"])
    except (OSError, KeyError, ValueError):
        return None
    if not summary.is_file():
        return None
    table = read_record(summary, {"level": "text", "shots": "count", "median_abs_rel_err": "number",
                                  "p90_abs_rel_err": "number", "mean_rel_err": "number", "within_10pct": "count"},
                        {"primary": "flag", "calibration": "text", "scoring": "text"},
                        what="the levels' validation, rule validation_levels")
    table = [r for r in table if r.get("primary") in (None, True)]
    _, fe_calibration = fe_calibration_record(root, profile, calibration)
    errors = {}
    for r in table:
        level = r["level"]
        if level in errors:
            continue
        if level in ("cavity", "fe") and r.get("calibration") != (fe_calibration if level == "fe" else calibration):
            continue
        errors[level] = r
    try:
        return ValidatedRange.from_rows(rows), errors
    except (KeyError, ValueError) as err:
        raise RecordError(f"record {root / cfg['validation']['shots']}", "rows", str(err),
                          "the development shots' columns as numbers") from None
