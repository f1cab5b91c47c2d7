"""The ladder of fidelity: its levels (rungs), cheapest first. The one list of them: the command line's choices, the
scenes' levels, the validation's rows, the sweep's curves, the docs and the report walk the ladder from here.

A level is a rung of the ladder, nothing else: ``analytic`` (the closed form, Eq 9), ``trajectory`` (the rigid-body
trajectory with Eq 7's terms), ``cavity`` (the trajectory driven by the HJC cavity-expansion law) and ``fe`` (the
axisymmetric finite-element model with HJC)."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Level:
    """A rung: its ``name`` (the command line's --model, a scene's level, a column's key), its ``label`` in tables
    and figures, and ``what`` it is in a sentence."""
    name: str
    label: str
    what: str


LADDER = (
    Level("analytic", "Eq 9", "Eq 9"),
    Level("trajectory", "trajectory", "the rigid-body trajectory with Eq 7's terms"),
    Level("cavity", "cavity", "the trajectory with the HJC cavity-expansion law"),
    Level("fe", "finite elements", "the axisymmetric finite-element model with HJC"),
)
LEVELS = tuple(level.name for level in LADDER)
LABELS = {level.name: level.label for level in LADDER}
WHAT = {level.name: level.what for level in LADDER}
