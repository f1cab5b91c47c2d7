"""Scenes: YAML files naming projectile, noses, target, velocities, level, effects.

A scene is validated against ``workflow/schemas/scene.schema.json`` when it
is loaded, then resolved: inferred noses and radii, and calibrated strength
factors, are read from the result files of the rules that made them, so a
scene never carries a number from the paper that is not its own input.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import config
from .geometry import Cone, Flat, MinimumNstar, Ogive, with_radius
from .resistance import Target, strength_factor


@dataclass(frozen=True)
class Scene:
    name: str
    mass: float
    radius: float
    noses: dict
    target: Target
    velocities: np.ndarray
    level: str
    effects: tuple
    friction: float = 0.0
    ramp_depth: float | None = None
    provenance: dict = field(default_factory=dict)
    material: dict = field(default_factory=dict)


def read_scene(path, schema_path):
    """The scene file as a validated dict."""
    return config.load(path, schema_path)


def velocities(spec):
    if isinstance(spec, dict):
        n = int(round((spec["stop"] - spec["start"]) / spec["step"])) + 1
        return spec["start"] + spec["step"] * np.arange(n)
    return np.asarray(spec, float)


def _nose(spec, radius, inferred):
    if "inferred" in spec:
        return with_radius(inferred[spec["inferred"]], radius)
    kind = spec["kind"]
    if kind == "ogive":
        return Ogive(spec["psi"], radius, spec.get("tip_radius", 0.0))
    if kind == "flat":
        return Flat(radius)
    length = Ogive(spec["length_of_crh"], radius).length
    return Cone(radius, length) if kind == "cone" else MinimumNstar(radius, length)


def resolve(name, data, inferred_noses, calibrations, diameters):
    """Scene object from a validated dict and the result files' contents.

    inferred_noses: rule name -> nose; calibrations: name -> dict with 'S';
    diameters: name -> dict with 'diameter'.
    """
    prov = {}
    radius = data["projectile"]["radius"]
    if isinstance(radius, dict):
        prov["radius"] = f"inferred ({radius['inferred']})"
        radius = 0.5 * diameters[radius["inferred"]]["diameter"]
    t = data["target"]
    strength = t["strength"]
    if "law" in strength:
        S = float(strength_factor(t["fc"], strength["law"]))
        prov["S"] = f"law {strength['law']}"
    elif "calibrated" in strength:
        S = calibrations[strength["calibrated"]]["S"]
        prov["S"] = f"calibrated ({strength['calibrated']})"
    else:
        S = strength["value"]
        prov["S"] = "given"
    noses = {n: _nose(spec, radius, inferred_noses) for n, spec in data["noses"].items()}
    return Scene(name, data["projectile"]["mass"], radius, noses, Target(t["rho"], t["fc"], S),
                 velocities(data["velocities"]), data["level"], tuple(data["effects"]),
                 data.get("friction", 0.0), data.get("ramp_depth"), prov,
                 {k: data[k] for k in ("lock", "tension") if k in data})


def scene_name(path):
    return Path(path).stem


def load_json(path):
    return json.loads(Path(path).read_text())
