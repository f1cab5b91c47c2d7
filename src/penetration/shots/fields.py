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
from ..errors import ParameterError
from ..nose.geometry import NOSES, Flat, Ogive, TabulatedNose
from ..nose.solve import solve_nose
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
NOSE_SHAPES = ("ogive", "hemispherical", "flat", "cone", "double_ogive", "minimum_nstar", "table")
CRH_RANGE = (0.5, 1e4)
CONSTRAINT_KEYS = ("nose_length", "nstar", "solve")   # nose.solve.CONSTRAINTS and solve=
# the nose columns of a shots CSV: name -> what it holds
NOSE_COLUMNS = {"nose_shape": f"one of {', '.join(NOSE_SHAPES)} (required)",
                "crh": f"caliber-radius-head of an ogive, a number in [{CRH_RANGE[0]:g}, {CRH_RANGE[1]:g}] "
                       "(required for nose_shape ogive unless nose_length or nstar is given, ignored otherwise)",
                "length, tip_radius": "cone: its length and flat tip's radius (m); minimum_nstar: length",
                "S1, S2, a1, a2, alpha, tip_length": "double_ogive: its keys as nstar takes them (m, alpha in rad)",
                "path": "table: a CSV of the outline (columns x, y in metres), relative to the shots file's folder",
                "nose_length, nstar, solve": "a nose by constraint: one key of the row's nose left empty and solved "
                                             "for its length (m) or its N* (python -m penetration nstar --help)"}
# a row reads only the columns of its own nose_shape: another kind's (e.g. an ogive row's S1) pass through


def nose_columns(shape) -> tuple:
    """The columns of a shots CSV that a row of nose_shape ``shape`` reads."""
    if shape in ("hemispherical", "flat"):
        return ()
    if shape == "table":
        return ("path",)
    keys = tuple(f.name for f in NOSES[shape].__dataclass_fields__.values() if f.name not in ("radius", "psi"))
    return (("crh",) if shape == "ogive" else keys) + CONSTRAINT_KEYS


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


def row_nose(row, radius, base=None):
    """The nose of a shots-CSV row at shank radius ``radius`` (m; a table nose keeps its own): nose_shape and the
    columns of nose_columns(nose_shape) that are not empty; a table's path relative to ``base`` (a folder)."""
    from pathlib import Path
    shape = row.get("nose_shape", "")
    if shape not in NOSE_SHAPES:
        raise ShotError(f"nose_shape = {shape!r} is not allowed: one of {list(NOSE_SHAPES)}")
    if shape == "hemispherical":
        return Ogive(0.5, radius)
    if shape == "flat":
        return Flat(radius)
    keys = {k: row[k].strip() for k in nose_columns(shape) if (row.get(k) or "").strip()}
    if shape == "ogive" and not any(k in keys for k in CONSTRAINT_KEYS[:2]):
        return Ogive(crh_value(row.get("crh", "")), radius)
    if shape == "ogive" and "crh" in keys:
        raise refused("crh", keys["crh"], "empty for an ogive given by nose_length or nstar (its CRH is solved for)")
    try:
        if shape == "table":
            path = Path(keys.get("path", ""))
            if keys.get("path") and base is not None and not path.is_absolute():
                path = Path(base) / path
            return TabulatedNose.from_keywords(path=str(path) if keys.get("path") else None)
        return solve_nose(shape, {"radius": radius, **keys})[0]
    except ParameterError as err:
        raise ShotError(str(err)) from None


def row_radius(row, base=None):
    """The shank radius (m) of a row: diameter_m/2 (checked), or a table nose's own where diameter_m is empty; a
    diameter_m given with a table must be twice the table's radius."""
    given = (row.get("diameter_m") or "").strip()
    if row.get("nose_shape") == "table":
        table = row_nose(row, 1.0, base)
        if given and not math.isclose(field_value("diameter_m", given), 2.0 * table.radius, rel_tol=1e-9):
            raise refused("diameter_m", field_value("diameter_m", given), f"twice the table's shank radius (its last y, "
                          f"{table.radius:g} m): {2.0 * table.radius:g} m, or empty")
        return table.radius
    return 0.5 * field_value("diameter_m", given)


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


def shot_values(row, base=None) -> dict:
    """The numeric fields of a shot (in the columns' units), each checked against SHOT_FIELDS; an optional field
    that is missing or empty is left out; a table nose's row may leave diameter_m empty (row_radius)."""
    out = {}
    for name, f in SHOT_FIELDS.items():
        if name == "diameter_m" and row.get("nose_shape") == "table":
            out[name] = 2.0 * row_radius(row, base)
            continue
        if not f.required and row.get(name) in (None, ""):
            continue
        out[name] = field_value(name, row.get(name, ""))
    return out


def predicted_depth(row, law="li_chen", base=None) -> float:
    """Eq 9 depth (m) of one shot row, S from the published S(fc) law ``law``."""
    v = shot_values(row, base)
    n = nstar(row_nose(row, 0.5 * v["diameter_m"], base))
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


def eq9_columns(law="li_chen", base=None):
    """The analytic level's prediction of a shot row: dop_pred_m, Eq 9's depth with S from ``law``."""
    return lambda row: {"dop_pred_m": f"{predicted_depth(row, law, base):.6g}"}
