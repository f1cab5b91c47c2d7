"""Scenes: YAML files naming projectile, noses, target, velocities, level, effects.

A scene is validated against ``workflow/schemas/scene.schema.json`` when it
is loaded, then resolved: inferred noses and radii, and calibrated strength
factors, are read from the result files of the rules that made them, so a
scene never carries a number from the paper that is not its own input.

A paper case is written once (``workflow/scenes/table3.yaml``); a level's
scene of the same case (``workflow/scenes/cavity/table3.yaml``,
``workflow/scenes/fe/table3.yaml``) names it with ``extends: ../table3.yaml``
and writes only what the level changes, as a JSON merge patch (RFC 7386) on
it: a mapping merges key by key, any other value replaces, ``null`` removes
the key. The merged scene is what is validated and run.
"""
from __future__ import annotations

import dataclasses
import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..analytic.resistance import Target, strength_factor
from ..analytic.trajectory import EFFECTS, EXCLUDES
from ..concrete.effects import MATERIAL_EFFECTS
from ..concrete.size import SizeEffect, sized_target
from ..levels import WHAT
from ..nose.geometry import Cone, Flat, MinimumNstar, Ogive, with_radius
from . import config

MAX_VELOCITIES = 1000
# Effects of the finite-element level beyond the material's (fe.erosion_strain sets the criterion's value).
FE_EFFECTS = {"erosion": "element erosion once the equivalent plastic strain reaches fe.erosion_strain"}
# The scale effect (concrete.size), at every level: a scene lists it as effect ``size`` with its settings in ``size``.
SIZE = "size"
# Level -> (effects it can use, effects it must have, what it is). The analytic
# level is Eq 9, the closed form of exactly crater + static + inertial (with the
# scale effect's factor on S where size is listed); a trajectory needs a static
# term to stop; the cavity level's forces come from its sigma_n table.
LEVELS = {name: (allowed | {SIZE}, required, WHAT[name]) for name, allowed, required in (
    ("analytic", {"crater", "static", "inertial"}, {"crater", "static", "inertial"}),
    ("trajectory", set(EFFECTS) - {"cavity"}, {"static"}),
    ("cavity", set(EFFECTS) - EXCLUDES["cavity"] | set(MATERIAL_EFFECTS), {"cavity"}),
    ("fe", set(FE_EFFECTS) | {"friction"} | set(MATERIAL_EFFECTS), set()),
)}
FE_TARGETS = ("semi_infinite", "block")


class SceneError(ValueError):
    """A scene whose fields are each valid but do not fit together (the message names field and allowed values)."""


@dataclass(frozen=True)
class Scene:
    name: str
    mass: float
    radius: float
    noses: dict
    target: Target
    velocities: np.ndarray
    level: str
    effects: tuple                  # the level's physics; the scale effect, where listed, is ``size`` instead
    friction: float = 0.0
    ramp_depth: float | None = None
    provenance: dict = field(default_factory=dict)
    material: dict = field(default_factory=dict)
    fe: dict = field(default_factory=dict)
    size_variant: str | None = None  # the scale effect's variant the scene names (effect size), None: scale-free
    size: SizeEffect | None = None   # that variant's effect, set with its calibration by ``sized``
    size_calibration: float | None = None  # the level's factor the study fitted with it on the laboratory shots
    size_profile: str | None = None        # the fe mesh profile that factor belongs to (the fe level's)

    def target_at(self, radius, velocity) -> Target:
        """The closed forms' target of a shot of this scene at nose ``radius`` and striking ``velocity``: S times
        the scale effect's factor at calibre 2 radius and V (concrete.size.resistance_factor), or the scene's."""
        return sized_target(self.target, self.size, 2.0 * radius, velocity)


# a scene's name (its file's stem) as the Snakefile's scene wildcard admits it
SCENE_NAME = r"[A-Za-z0-9_]+"


def check_scene_name(path):
    """Refuse a scene file whose name the scene wildcard cannot match (Snakemake would say only that no rule
    produces its outputs), naming the file, the allowed pattern and a name that would do."""
    stem = Path(path).stem
    if not re.fullmatch(SCENE_NAME, stem, re.ASCII):
        fixed = re.sub(r"[^A-Za-z0-9_]", "_", stem, flags=re.ASCII) or "scene"
        raise SceneError(f"{path}: scene name {stem!r} is not allowed: a name matching {SCENE_NAME} (letters, digits "
                         f"and underscores: the Snakefile's scene wildcard), e.g. {fixed}{Path(path).suffix}")
    return stem


def scene_names(folder) -> list:
    """Names of the scenes of ``folder`` (every *.yaml), each checked by check_scene_name."""
    return [check_scene_name(path) for path in sorted(Path(folder).glob("*.yaml"))]


EXTENDS = "extends"
MAX_EXTENDS = 8


def merge_patch(target, patch):
    """``patch`` applied to ``target`` as a JSON merge patch (RFC 7386): mappings merge key by key (a key keeps its
    place in ``target``; new keys follow), ``None`` removes a key, any other value replaces."""
    if not isinstance(patch, dict):
        return patch
    out = dict(target) if isinstance(target, dict) else {}
    for key, value in patch.items():
        if value is None:
            out.pop(key, None)
        else:
            out[key] = merge_patch(out.get(key), value)
    return out


def _chain(path) -> list:
    """(file, its mapping) for the scene file and each file it extends in turn, each file read once."""
    chain = []
    nxt = Path(path)
    while True:
        data = config.read_yaml(nxt) or {}
        chain.append((nxt, data))
        base = data.get(EXTENDS) if isinstance(data, dict) else None
        if base is None:
            return chain
        here = chain[-1][0]
        if not isinstance(base, str):
            raise SceneError(f"{here}: {EXTENDS}: {base!r}; allowed: the path of a scene file, relative to this one")
        nxt = Path(os.path.normpath(here.parent / base))
        if not nxt.is_file():
            raise SceneError(f"{here}: {EXTENDS}: {base!r}: no such file ({nxt})")
        files = [f for f, _ in chain]
        if nxt.resolve() in [f.resolve() for f in files] or len(files) > MAX_EXTENDS:
            raise SceneError(f"{here}: {EXTENDS}: {base!r} makes a cycle or a chain longer than {MAX_EXTENDS}: "
                             f"{' -> '.join(str(f) for f in files + [nxt])}")


def scene_files(path) -> list:
    """The files a scene is made of: the file itself, then the file it extends, and so on (a rule's inputs, so that
    a change to the paper's case reruns every level's scene of it)."""
    return [str(f) for f, _ in _chain(path)]


def scene_data(path) -> dict:
    """A scene file's mapping, the files it extends merged in (merge_patch, the base first); not yet validated."""
    merged = {}
    for _, data in reversed(_chain(path)):
        merged = merge_patch(merged, {k: v for k, v in data.items() if k != EXTENDS})
    return merged


def read_scene(path, schema_path, levels=None):
    """The scene file as a validated dict (the scenes it extends merged in: scene_data); ``levels``: the levels the
    reading rule runs (others are refused). A file whose name the scene wildcard cannot match is refused
    (check_scene_name)."""
    check_scene_name(path)
    data = config.validate(scene_data(path), json.loads(Path(schema_path).read_text()), str(path))
    if levels is not None and data["level"] not in levels:
        raise SceneError(f"{path}: level: {data['level']!r} is not run by this rule; allowed: {list(levels)}"
                         + ({"cavity": " (cavity scenes live in workflow/scenes/cavity/)", "fe": " (fe scenes live in workflow/scenes/fe/)"}.get(data["level"], "")))
    check_level(data, str(path))
    velocities(data["velocities"], f"{path}: velocities")
    return data


def velocities(spec, where="velocities"):
    """Striking velocities of a scene: a list, or {start, stop, step} with stop >= start (at most MAX_VELOCITIES)."""
    if isinstance(spec, dict):
        start, stop, step = spec["start"], spec["stop"], spec["step"]
        if not all(np.isfinite([start, stop, step])) or stop < start:
            raise SceneError(f"{where}: start {start}, stop {stop}, step {step}; allowed: finite, stop >= start")
        n = int(round((stop - start) / step)) + 1
        if n > MAX_VELOCITIES:
            raise SceneError(f"{where}: {n} velocities; allowed: at most {MAX_VELOCITIES}")
        return start + step * np.arange(n)
    v = np.asarray(spec, float)
    if not np.all(np.isfinite(v)):
        raise SceneError(f"{where}: {spec}; allowed: finite numbers (m/s)")
    return v


def check_level(data, where="scene"):
    """Refuse effects and settings the scene's level would ignore, and effect sets that cannot stop a projectile."""
    level, effects = data["level"], set(data["effects"])
    allowed, required, what = LEVELS[level]
    unused = sorted(effects - allowed)
    if unused:
        raise SceneError(f"{where}: effects: {unused} not used at level {level} ({what}); allowed: {sorted(allowed)}")
    missing = sorted(required - effects)
    if missing:
        raise SceneError(f"{where}: effects: level {level} ({what}) needs {missing}; given {sorted(effects)}; "
                         f"allowed: a list including {sorted(required)}")
    settings = {"friction": "friction", "ramp_depth": "free_surface_ramp", "size": SIZE}
    for key, needs in settings.items():
        if key in data and needs not in effects:
            raise SceneError(f"{where}: {key} is set but effect {needs} is not listed; allowed: list {needs} or drop {key}")
    if SIZE in effects and SIZE not in data:
        raise SceneError(f"{where}: effect size is listed without its settings; allowed: size: {{variant: NAME}}, a "
                         "variant of the config's scale_effect.variants")
    if "friction" in effects and not data.get("friction", 0.0) > 0:
        raise SceneError(f"{where}: effect friction is listed with friction = {data.get('friction', 0.0)}; "
                         "allowed: friction > 0 (a coefficient up to 1)")
    conventions = [k for k in ("lock", "tension") if k in data]
    if conventions and level not in ("cavity", "fe"):
        raise SceneError(f"{where}: {conventions} apply to the HJC material; allowed only at levels cavity and fe")
    fe = data.get("fe")
    if fe is not None and level != "fe":
        raise SceneError(f"{where}: fe settings are given at level {level}; allowed only at level fe")
    if level == "fe":
        if "strength" in data["target"]:
            raise SceneError(f"{where}: target.strength is not used at level fe (the target is HJC concrete); "
                             "allowed: rho and fc only")
        has = "erosion_strain" in (fe or {})
        if ("erosion" in effects) != has:
            raise SceneError(f"{where}: effect erosion and fe.erosion_strain go together; allowed: list erosion and set "
                             "fe.erosion_strain ('calibrated' or a strain > 0), or neither")


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
    strength = t.get("strength", {})
    if not strength:
        S = None
        prov["S"] = "none (level fe: HJC target)"
    elif "law" in strength:
        S = float(strength_factor(t["fc"], strength["law"]))
        prov["S"] = f"law {strength['law']}"
    elif "calibrated" in strength:
        S = calibrations[strength["calibrated"]]["S"]
        prov["S"] = f"calibrated ({strength['calibrated']})"
    else:
        S = strength["value"]
        prov["S"] = "given"
    noses = {n: _nose(spec, radius, inferred_noses) for n, spec in data["noses"].items()}
    variant = data[SIZE]["variant"] if SIZE in data["effects"] else None
    return Scene(name, data["projectile"]["mass"], radius, noses, Target(t["rho"], t["fc"], S),
                 velocities(data["velocities"], f"{name}: velocities"), data["level"],
                 tuple(e for e in data["effects"] if e != SIZE), data.get("friction", 0.0), data.get("ramp_depth"), prov,
                 {k: data[k] for k in ("lock", "tension") if k in data}, dict(data.get("fe", {})), variant)


# the level whose factor a scene with the scale effect takes from the study: the trajectory level's closed-form
# effects take the analytic level's factor on S
SIZE_LEVEL = {"analytic": "analytic", "trajectory": "analytic", "cavity": "cavity", "fe": "fe"}


def sized(scene: Scene, spec) -> Scene:
    """The scene with the scale effect of the variant it names and the factor the scale effect's study fitted with
    it on the laboratory shots at its level (``spec``, a rule's size params: ``variants`` and ``law`` of the config,
    the study's ``fe_profile`` and its calibration table ``calibration``, rows as dicts). At the analytic and
    trajectory levels that factor multiplies S, which must then be the law the study fitted it on; the cavity and fe
    levels' tasks use it in place of their DO1 calibrations. Refused, naming the field, where the variant is not
    calibrated at the level or the scene would drop part of it (the rate mechanism lives in HJC's strain_rate term)."""
    where = f"{scene.name}: size.variant"
    variant, at = scene.size_variant, SIZE_LEVEL[scene.level]
    if variant not in spec["variants"]:
        raise SceneError(f"{where}: {variant!r}; allowed: one of {sorted(spec['variants'])} (scale_effect.variants)")
    effect = SizeEffect.from_spec(spec["variants"][variant])
    if effect is None:
        raise SceneError(f"{where}: {variant!r} is the study's variant without the effect; allowed: drop effect size")
    rows = [r for r in spec["calibration"] if r["level"] == at and r["variant"] == variant and r["fold"] == "all"]
    if len(rows) != 1:
        raise SceneError(f"{where}: {variant!r} has no calibration at the {at} level; allowed: a variant of "
                         f"figures/scale/calibration_{at}.csv (snakemake -c2 figures/scale/calibration_{at}.csv)")
    value = float(rows[0]["value"])
    prov = {**scene.provenance, SIZE: f"{variant}: {'+'.join(effect.mechanisms)}, the {at} level's factor {value:.6g} "
                                      f"fitted with it on the laboratory shots (figures/scale/calibration_{at}.csv)"}
    target = scene.target
    if at == "analytic":
        if scene.provenance.get("S") != f"law {spec['law']}":
            raise SceneError(f"{scene.name}: target.strength: {scene.provenance.get('S')} with effect size; allowed: "
                             f"{{law: {spec['law']}}} (the study fitted its factor on that law's S)")
        target = dataclasses.replace(target, S=target.S * value)
    elif "rate" in effect.mechanisms and "strain_rate" not in scene.effects:
        raise SceneError(f"{scene.name}: effects: size (variant {variant}, whose rate mechanism acts through HJC's "
                         "strain-rate term) without strain_rate; allowed: list strain_rate too")
    return dataclasses.replace(scene, target=target, size=effect, size_calibration=value, provenance=prov,
                               size_profile=spec["fe_profile"] if at == "fe" else None)


def scene_name(path):
    return Path(path).stem


def load_json(path):
    return json.loads(Path(path).read_text())
