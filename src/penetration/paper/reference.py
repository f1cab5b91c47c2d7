"""Reference values transcribed from the paper: the table of every number it states.

Each row has an id, the item and quantity it belongs to, the value as
printed with its unit, the relation the paper states (eq, le, ...), the
tolerance a comparison may use, and its source in the paper. Tolerances are
stored with the reference values, never in code. The diff against our
numbers is ``penetration.paper.diff``.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass

UNITS = {"1": 1.0, "%": 0.01, "m": 1.0, "kg": 1.0, "m/s": 1.0, "1/s": 1.0, "kg/m3": 1.0,
         "g/cm3": 1e3, "MPa": 1e6, "GPa": 1e9, "ms": 1e-3, "g": 9.80665, "as printed": 1.0}
VELOCITIES = (500, 800, 1000, 1200)
TABLE3_NOSES = ("double_ogive", "crh45", "crh3")
@dataclass(frozen=True)
class Ref:
    id: str
    item: str
    quantity: str
    case: str
    value: float
    unit: str
    relation: str
    tol: float
    source: str
    note: str

    @property
    def si(self) -> float:
        return self.value * UNITS[self.unit]


def load_reference(path) -> dict[str, Ref]:
    """Read the reference CSV; checks units, relations and unique ids."""
    refs = {}
    with open(path, newline="") as fh:
        for n, row in enumerate(csv.DictReader(fh), start=2):
            if row["id"] in refs:
                raise ValueError(f"{path} row {n}: duplicate id {row['id']}")
            if row["unit"] not in UNITS:
                raise ValueError(f"{path} row {n}: unit {row['unit']!r} not in {sorted(UNITS)}")
            if row["relation"] not in ("eq", "le", "ge", "lt", "gt"):
                raise ValueError(f"{path} row {n}: relation {row['relation']!r} not in eq, le, ge, lt, gt")
            refs[row["id"]] = Ref(row["id"], row["item"], row["quantity"], row["case"], float(row["value"]),
                                  row["unit"], row["relation"], float(row["tol"]), row["source"], row["note"])
    return refs


