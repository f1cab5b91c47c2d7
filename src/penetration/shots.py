"""Users' shots: checks of a shot's fields and the closed-form prediction of its depth.

A shot is one row in the schema of ``workflow/data/experiments-dev.csv``
(strings as read from a CSV, units in the column names). Each field is
checked against its allowed range before anything is computed; a row that
fails is reported by number and reason, never guessed at.
"""
from __future__ import annotations

import math

from .dop import penetration_depth
from .geometry import Flat, Ogive
from .nstar import nstar
from .resistance import Target, strength_factor
from .units import MPA

# name -> (exclusive lower bound, inclusive upper bound), in the column's unit
SHOT_FIELDS = {"mass_kg": (1e-6, 1e6), "diameter_m": (2e-6, 10.0), "target_density_kgm3": (100.0, 2e4),
               "fc_MPa": (0.5, 2000.0), "velocity_ms": (0.0, 1e4)}
NOSE_SHAPES = ("ogive", "hemispherical", "flat")
CRH_RANGE = (0.5, 1e4)


class ShotError(ValueError):
    """A shot field outside its allowed range (the message names field, value and range)."""


def shot_nstar(row) -> float:
    """N* of a shot's nose from its nose_shape and crh columns."""
    shape = row.get("nose_shape", "")
    if shape not in NOSE_SHAPES:
        raise ShotError(f"nose_shape = {shape!r} is not allowed: one of {list(NOSE_SHAPES)}")
    if shape == "hemispherical":
        return nstar(Ogive(0.5, 1.0))
    if shape == "flat":
        return nstar(Flat(1.0))
    lo, hi = CRH_RANGE
    crh = _number(row, "crh", f"a number in [{lo}, {hi}] for an ogive")
    if not lo <= crh <= hi:
        raise ShotError(f"crh = {crh} is not allowed: a number in [{lo}, {hi}] for an ogive")
    return nstar(Ogive(crh, 1.0))


def _number(row, name, allowed):
    try:
        value = float(row.get(name, ""))
    except (TypeError, ValueError):
        raise ShotError(f"{name} = {row.get(name)!r} is not allowed: {allowed}") from None
    if not math.isfinite(value):
        raise ShotError(f"{name} = {value} is not allowed: {allowed}")
    return value


def shot_values(row) -> dict:
    """The numeric fields of a shot, each checked against SHOT_FIELDS."""
    out = {}
    for name, (lo, hi) in SHOT_FIELDS.items():
        allowed = f"a number in ({lo:g}, {hi:g}]"
        v = _number(row, name, allowed)
        if not lo < v <= hi:
            raise ShotError(f"{name} = {v:g} is not allowed: {allowed}")
        out[name] = v
    return out


def predicted_depth(row, law="li_chen") -> float:
    """Eq 9 depth (m) of one shot row, S from the published S(fc) law ``law``."""
    v = shot_values(row)
    n = shot_nstar(row)
    fc = v["fc_MPa"] * MPA
    target = Target(v["target_density_kgm3"], fc, float(strength_factor(fc, law)))
    depth = float(penetration_depth(v["mass_kg"], 0.5 * v["diameter_m"], n, target, v["velocity_ms"]))
    if not (math.isfinite(depth) and depth > 0):
        raise ShotError(f"the predicted depth is {depth}: the fields are out of the range where Eq 9 is finite")
    return depth


def output_fields(fields):
    """Header of the predictions: the input's fields, then dop_pred_m (replacing one the input already has)."""
    return [f for f in fields if f != "dop_pred_m"] + ["dop_pred_m"]


def row_problem(i, row):
    """'row i: reason' for a row with more or fewer fields than the header (csv.DictReader puts fields beyond the
    header under the key None and leaves missing ones None), else None."""
    if None in row:
        return f"row {i}: {len(row) - 1 + len(row[None])} fields, the header has {len(row) - 1}"
    if None in row.values():
        return f"row {i}: {sum(v is not None for v in row.values())} fields, the header has {len(row)}"
    return None


def predict_rows(rows, law="li_chen"):
    """Predicted depths for shot rows: (rows with dop_pred_m added, 'row N: reason' per skipped row).

    Rows are dicts as csv.DictReader yields them: fields beyond the header
    sit under the key None, missing ones are None; such rows are skipped. N counts the header
    as row 1, as a spreadsheet does.
    """
    good, problems = [], []
    for i, row in enumerate(rows, start=2):
        if (problem := row_problem(i, row)) is not None:
            problems.append(problem)
            continue
        try:
            dop = predicted_depth(row, law)
        except ShotError as err:
            problems.append(f"row {i}: {err}")
            continue
        good.append({**row, "dop_pred_m": f"{dop:.6g}"})
    return good, problems
