"""How far to trust an answer: each level's validated accuracy and the range it was validated over.

The levels are validated on the development shots (``workflow/data/experiments-dev.csv``; each calibration is
scored only on the shots it was not fitted to: figures/fe/{profile}/validation_levels_summary.csv has each level's
errors per calibration). An answer is reported with its level's errors there, at the calibration in use, and with a warning for every quantity of the shot outside the range of those shots
(calibre, projectile mass, concrete strength and density, striking velocity, nose): there the errors are not
known. Pure functions: the files are read by ``shots.records.validated_accuracy``.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from ..studies.scale import goals_met

# shot quantity (SI, as levels.UserShot holds it) -> (development shots' CSV column, its SI factor, label, unit
# shown, the unit's factor from SI)
QUANTITIES = {"diameter": ("diameter_m", 1.0, "calibre (diameter_m)", "mm", 1e3),
              "mass": ("mass_kg", 1.0, "projectile mass (mass_kg)", "kg", 1.0),
              "fc": ("fc_MPa", 1e6, "concrete strength (fc_MPa)", "MPa", 1e-6),
              "density": ("target_density_kgm3", 1.0, "concrete density (target_density_kgm3)", "kg/m^3", 1.0),
              "velocity": ("velocity_ms", 1.0, "striking velocity (velocity_ms)", "m/s", 1.0)}


@dataclass(frozen=True)
class ValidatedRange:
    """The development shots' range of each quantity (SI) and the noses they had."""
    bounds: dict            # quantity -> (low, high), SI
    crh: tuple              # (low, high) of the ogives' CRH
    shots: int

    @classmethod
    def from_rows(cls, rows):
        """From the development shots' CSV rows (dicts of strings or numbers, the CSV's columns)."""
        rows = list(rows)
        if not rows:
            raise ValueError("no development shots: a validated range needs at least one")
        bounds = {}
        for q, (col, si, *_) in QUANTITIES.items():
            values = [float(r[col]) * si for r in rows]
            bounds[q] = (min(values), max(values))
        shapes = {r["nose_shape"] for r in rows}
        if shapes != {"ogive"}:
            raise ValueError(f"development shots with nose shapes {sorted(shapes)}: only ogives are described here")
        crh = [float(r["crh"]) for r in rows]
        return cls(bounds, (min(crh), max(crh)), len(rows))

    def describe(self) -> str:
        parts = []
        for q, (lo, hi) in self.bounds.items():
            _, _, label, unit, f = QUANTITIES[q]
            parts.append(f"{label.split(' (')[0]} {lo * f:.4g}-{hi * f:.4g} {unit}")
        return f"{self.shots} shots: " + ", ".join(parts) + f", ogive noses of CRH {self.crh[0]:g}-{self.crh[1]:g}"


def shot_values(shot) -> dict:
    """The quantities of a levels.UserShot, SI."""
    return {"diameter": 2 * shot.nose.radius, "mass": shot.mass, "fc": shot.fc, "density": shot.density,
            "velocity": shot.velocity}


def warnings(shot, rng: ValidatedRange) -> list[str]:
    """One line for each quantity of ``shot`` outside ``rng`` that the user gave (a default is said once, in
    defaults_note), and for a nose that is not an ogive of its CRHs."""
    out = []
    for q, v in shot_values(shot).items():
        lo, hi = rng.bounds[q]
        if QUANTITIES[q][0] in getattr(shot, "defaults", ()):
            continue
        if not lo <= v <= hi:
            _, _, label, unit, f = QUANTITIES[q]
            out.append(f"{label} {v * f:.4g} {unit} is outside the validated {lo * f:.4g}-{hi * f:.4g} {unit}")
    nose = shot.nose
    if nose.kind != "ogive" or getattr(nose, "tip_radius", 0.0):
        out.append(f"a {nose.kind} nose is outside the validated noses (ogives of CRH {rng.crh[0]:g}-{rng.crh[1]:g})")
    elif not rng.crh[0] <= nose.psi <= rng.crh[1]:
        out.append(f"CRH {nose.psi:g} is outside the validated CRH {rng.crh[0]:g}-{rng.crh[1]:g}")
    return out


def defaults_note(shot, rng: ValidatedRange) -> str:
    """The quantities ``shot`` took by default that lie outside ``rng``, said once (empty where none does)."""
    out = []
    for q, v in shot_values(shot).items():
        col, _, label, unit, f = QUANTITIES[q]
        lo, hi = rng.bounds[q]
        if col in getattr(shot, "defaults", ()) and not lo <= v <= hi:
            out.append(f"{col} not given: its default {v * f:.4g} {unit} lies outside the validated {lo * f:.4g}-"
                       f"{hi * f:.4g} {unit}")
    return "; ".join(out)


def with_scale_effect_range(rng: ValidatedRange, row) -> ValidatedRange:
    """The validated range of a level run with a variant of the scale effect (``row``: its validation, with DO1's
    calibre): the calibres widened up to DO1's where the variant meets every goal of the validation (studies.scale:
    among them DO1, which no fit has seen, predicted within 10 %); else the development shots' range."""
    if row is None or not all(goals_met(row).values()):
        return rng
    lo, hi = rng.bounds["diameter"]
    return dataclasses.replace(rng, bounds={**rng.bounds, "diameter": (lo, max(hi, float(row["do1_diameter_m"])))})


def scale_effect_line(variant, why, row) -> str:
    """What an answer's scale effect is and how its level did with it on the validation (``row``; None: not
    validated)."""
    if variant == "none":
        return f"scale effect none ({why})"
    if row is None:
        return f"scale effect {variant} ({why}), which the scale effect's study has not validated at this level"
    met = goals_met(row)
    return (f"scale effect {variant} ({why}): leave one series out on {int(row['loso_shots'])} laboratory shots, "
            f"median |error| {100 * float(row['loso_median_abs_rel_err']):.0f} %, 90th percentile "
            f"{100 * float(row['loso_p90_abs_rel_err']):.0f} %, the two series' factors {float(row['split_ratio']):.2f} "
            f"apart; DO1 ({1e3 * float(row['do1_diameter_m']):.0f} mm, in no fit) "
            f"{100 * float(row['do1_rel_error']):+.0f} %; {sum(met.values())} of {len(met)} goals met")


def accuracy_line(level, errors: dict) -> str:
    """The validated accuracy of a level from its row of validation_levels_summary.csv."""
    sign = "too deep" if errors["mean_rel_err"] > 0 else "too shallow"
    how = f" ({errors['calibration']} calibration, {errors['scoring']})" if "calibration" in errors else ""
    return (f"validated accuracy of the {level} level{how} on {int(errors['shots'])} development shots: depth error median "
            f"{100 * errors['median_abs_rel_err']:.0f} %, 90th percentile {100 * errors['p90_abs_rel_err']:.0f} %, "
            f"mean {100 * errors['mean_rel_err']:+.0f} % ({sign} on average); {int(errors['within_10pct'])} of "
            f"{int(errors['shots'])} within 10 %")
