"""Users' shots: the one table of a shot's fields, their checks, and the closed-form prediction of its depth.

A shot is one row in the schema of ``workflow/data/experiments-dev.csv``
(strings as read from a CSV, units in the column names). The same names are
the shot keys of the command line's ``dop`` and ``simulate`` (SHOT_FIELDS:
unit, range, what each is); inside the package everything is SI
(``ShotField.si``). Each field is checked against its allowed range before
anything is computed; a row that fails is reported by number and reason,
never guessed at. Numbers are read in units.NUMBER_FORM.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..analytic.dop import penetration_depth
from ..analytic.resistance import Target, strength_factor
from ..nose.geometry import Flat, Ogive
from ..nose.nstar import nstar
from ..units import MPA, NUMBER_FORM, parse_number


@dataclass(frozen=True)
class ShotField:
    """A numeric field of a shot: its unit, the unit in SI, its range (lo, hi] in its unit, what it is."""
    unit: str
    si: float
    lo: float
    hi: float
    what: str
    required: bool = True             # in a shots CSV row (False: may be missing or empty)
    default: float | None = None      # on the command line, when the key is not given
    attribute: str | None = None      # the levels.UserShot attribute (SI), None for diameter_m (the nose's)

    @property
    def allowed(self):
        return f"a number in ({self.lo:g}, {self.hi:g}] {self.unit}"


# The shot's numeric fields: the shots CSV's columns and the shot keys of dop and simulate (one vocabulary)
SHOT_FIELDS = {
    "mass_kg": ShotField("kg", 1.0, 1e-6, 1e6, "projectile mass", attribute="mass"),
    "diameter_m": ShotField("m", 1.0, 2e-6, 10.0, "shank diameter (the nose's radius is diameter_m/2)"),
    "length_m": ShotField("m", 1.0, 0.0, 1e3, "projectile length, nose and shank (needed by the fe level only)",
                          required=False, attribute="length"),
    "target_density_kgm3": ShotField("kg/m^3", 1.0, 100.0, 2e4, "concrete density", default=2440.0,
                                     attribute="density"),
    "fc_MPa": ShotField("MPa", MPA, 0.5, 2000.0, "concrete compressive strength (20-200 MPa at the cavity and fe "
                        "levels: the range of the HJC scaling rule)", attribute="fc"),
    "velocity_ms": ShotField("m/s", 1.0, 0.0, 1e4, "striking velocity", attribute="velocity"),
}
# shot field of each UserShot attribute (SI)
ATTRIBUTE_FIELDS = {f.attribute: name for name, f in SHOT_FIELDS.items() if f.attribute}
NOSE_SHAPES = ("ogive", "hemispherical", "flat")
CRH_RANGE = (0.5, 1e4)
# the nose columns of a shots CSV: name -> what it holds
NOSE_COLUMNS = {"nose_shape": f"one of {', '.join(NOSE_SHAPES)} (required)",
                "crh": f"caliber-radius-head of an ogive, a number in [{CRH_RANGE[0]:g}, {CRH_RANGE[1]:g}] "
                       "(required for nose_shape ogive, ignored otherwise)"}


class ShotError(ValueError):
    """A shot field outside its allowed range (the message names field, value and range)."""


def refused(name, value, allowed) -> ShotError:
    """The ShotError of field ``name`` at ``value`` (its text, or a number in the field's unit), with the field,
    the value and what is allowed as attributes."""
    shown = f"{value:g}" if isinstance(value, float) else repr(value)
    err = ShotError(f"{name} = {shown} is not allowed: {allowed}")
    err.name, err.value, err.allowed = name, value, allowed
    return err


def columns_help() -> str:
    """The shots CSV's columns, one a line: name, unit and range, required or optional (for predict --help)."""
    lines = [f"  {name:<20} {f.what}, {f.allowed} ({'required' if f.required else 'optional'})"
             for name, f in SHOT_FIELDS.items()]
    lines += [f"  {name:<20} {text}" for name, text in NOSE_COLUMNS.items()]
    return "\n".join(lines)


def crh_value(value) -> float:
    """A CRH (the shots CSV's crh, dop's crh=) checked against CRH_RANGE."""
    lo, hi = CRH_RANGE
    allowed = f"a number in [{lo:g}, {hi:g}] for an ogive"
    try:
        crh = parse_number(value)
    except ValueError:
        raise refused("crh", value, f"{allowed} ({NUMBER_FORM})") from None
    if not lo <= crh <= hi:
        raise refused("crh", crh, allowed)
    return crh


def shot_nstar(row) -> float:
    """N* of a shot's nose from its nose_shape and crh columns."""
    shape = row.get("nose_shape", "")
    if shape not in NOSE_SHAPES:
        raise ShotError(f"nose_shape = {shape!r} is not allowed: one of {list(NOSE_SHAPES)}")
    if shape == "hemispherical":
        return nstar(Ogive(0.5, 1.0))
    if shape == "flat":
        return nstar(Flat(1.0))
    return nstar(Ogive(crh_value(row.get("crh", "")), 1.0))


def _number(row, name, allowed):
    try:
        return parse_number(row.get(name, ""))
    except (TypeError, ValueError):
        raise refused(name, row.get(name), f"{allowed} ({NUMBER_FORM})") from None


def field_value(name, text) -> float:
    """The value (in the field's unit) of shot field ``name`` from its text, checked against its range."""
    f = SHOT_FIELDS[name]
    v = _number({name: text}, name, f.allowed)
    if not f.lo < v <= f.hi:
        raise refused(name, v, f.allowed)
    return v


def shot_values(row) -> dict:
    """The numeric fields of a shot (in the columns' units), each checked against SHOT_FIELDS; an optional field
    that is missing or empty is left out."""
    out = {}
    for name, f in SHOT_FIELDS.items():
        if not f.required and row.get(name) in (None, ""):
            continue
        out[name] = field_value(name, row.get(name, ""))
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


DEPTH_ALLOWANCE = 1.6  # the stated S = 72 fc^-0.5 gives 0.64-0.7 of the depths the FE level reaches


def expected_depth(nose, mass, velocity, fc, rho) -> float:
    """The depth (m) that sizes a simulation's semi-infinite domain: DEPTH_ALLOWANCE times Eq 9 with Li and Chen's S
    (the FE level repeats a run that reaches the bottom on a domain twice as deep)."""
    return DEPTH_ALLOWANCE * float(penetration_depth(mass, nose.radius, nstar(nose),
                                                     Target(rho, fc, strength_factor(fc, "li_chen")), velocity))


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


def row_predictions(rows, predict, errors=(ShotError,), progress=None, good=None):
    """Predictions for shot rows: (rows with the columns of ``predict(row)`` added, 'row N: reason' per skipped row).

    Rows are dicts as csv.DictReader yields them: fields beyond the header sit under the key None, missing ones are
    None; such rows are skipped, and so is a row whose prediction raises one of ``errors`` (with its message). N
    counts the header as row 1, as a spreadsheet does. ``progress(i, n)`` is called after each row; ``good``: a list
    the predicted rows are appended to as they come (an interrupted run keeps them there).
    """
    good = [] if good is None else good
    problems = []
    for k, row in enumerate(rows):
        i = k + 2
        if progress is not None and k:
            progress(k, len(rows))
        if (problem := row_problem(i, row)) is not None:
            problems.append(problem)
            continue
        try:
            columns = predict(row)
        except errors as err:
            problems.append(f"row {i}: {err}")
            continue
        good.append({**row, **columns})
    if progress is not None and rows:
        progress(len(rows), len(rows))
    return good, problems


def eq9_columns(law="li_chen"):
    """The analytic level's prediction of a shot row: dop_pred_m, Eq 9's depth with S from ``law``."""
    return lambda row: {"dop_pred_m": f"{predicted_depth(row, law):.6g}"}
