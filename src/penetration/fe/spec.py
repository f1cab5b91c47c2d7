"""The FE level's run spec: what one shot depends on, as typed, checked values with their defaults in one place.

``Controls`` are the solver's numerical controls; ``Settings`` the level's mesh
and run settings (``Settings.from_config`` takes the fields an ``fe`` config
slice names and keeps these defaults for the others: the config schema only
bounds them); ``TargetSpec`` the target's kind, size and faces; ``RunSpec`` one
whole shot. This module imports no solver code, so that the configuration's
checks can read the defaults cheaply.

Target (``TargetSpec``): ``semi_infinite`` (the paper's simulation, text
l.240: "a circular semi-infinite target") is a cylinder of radius
``radius`` with non-reflecting lateral and bottom boundaries, deep enough
for the shot (a run that reaches the bottom is repeated on a domain twice as
deep, unless the depth is set); ``block`` is the experiment's 3.6 m x 3.6 m x 5.4 m block as a
cylinder of the same cross-section area (radius 3.6/sqrt(pi) = 2.031 m)
and depth 5.4 m with free faces. The lateral and bottom faces can be set apart
(``lateral``, ``bottom``: non-reflecting or free), so that the rear-face study
changes one thing at a time between the two.

Moving window (``window_ahead``, ``window_tail``): only the rows from
window_tail behind the projectile's tail to window_ahead ahead of its tip are
computed (the rule fe_window_study compares DO1 with the window and with the
whole domain: figures/fe/{profile}/window_summary.csv).

Deceleration: the contact impulses are summed in bins of ``bin_width`` and
filtered by a zero-phase fourth-order Butterworth low-pass at ``cutoff_hz``
(the declared filter; tasks.fe records the peak at the other cut-offs of the config).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace

from ..errors import ParameterError
from .erosion_free.controls import ErosionFree
from .state import BOUNDARIES, EROSION_KINDS


@dataclass(frozen=True)
class Controls:
    """Numerical controls; defaults follow LS-DYNA's (QH 0.1, Q1 1.5, Q2 0.06, time-step factor 0.9)."""
    dt_factor: float = 0.9
    hourglass: float = 0.1
    q1: float = 1.5
    q2: float = 0.06
    erosion: str = "none"
    erosion_value: float = math.inf
    guard: bool = True          # erode inverted or time-step-collapsed elements (else stop with a diagnostic)
    dt_floor: float = 1e-3      # guard threshold: element step below this fraction of the initial step
    drop_free_nodes: bool = True
    lateral: str = "free"
    bottom: str = "free"
    end_time: float = 0.05
    output_interval: float = 1e-4
    max_energy_error: float = 0.5  # stop (unstable) when the audit's relative error exceeds this
    window_ahead: float | None = None   # m: rows computed down to this far ahead of the tip (None: whole domain)
    window_behind: float | None = None  # m: rows further behind the tip than this are retired (None: kept)
    erosion_free: ErosionFree | None = None  # the erosion-free target's controls (fe.erosion_free): rezoned, its
    #                                     guard ejects and never erodes; None: the eroding target

    def __post_init__(self):
        if not 0.0 < self.dt_factor <= 1.0:
            raise ParameterError("fe controls", "dt_factor", self.dt_factor, "0 < dt_factor <= 1")
        if not 0.0 <= self.hourglass <= 0.15:
            raise ParameterError("fe controls", "hourglass", self.hourglass, "0 <= hourglass <= 0.15 (unstable above)")
        if self.erosion not in EROSION_KINDS:
            raise ParameterError("fe controls", "erosion", self.erosion, f"one of {sorted(EROSION_KINDS)}")
        if self.erosion != "none" and not self.erosion_value > 0:
            raise ParameterError("fe controls", "erosion_value", self.erosion_value, "> 0")
        for key in ("lateral", "bottom"):
            if getattr(self, key) not in BOUNDARIES:
                raise ParameterError("fe controls", key, getattr(self, key), f"one of {sorted(BOUNDARIES)}")
        for key in ("window_ahead", "window_behind"):
            v = getattr(self, key)
            if v is not None and not v > 0:
                raise ParameterError("fe controls", key, v, "> 0 (m) or None")
        if not (self.end_time > 0 and self.output_interval > 0):
            raise ParameterError("fe controls", "end_time, output_interval", (self.end_time, self.output_interval), "> 0 (s)")
        if self.erosion_free is not None and self.erosion != "none":
            raise ParameterError("fe controls", "erosion", self.erosion, "none for the erosion-free target")


BLOCK_RADIUS = 3.6 / math.sqrt(math.pi)  # equal cross-section area with the 3.6 m x 3.6 m block


TARGET_FACES = ("non_reflecting", "free")
# eroding: the paper's counterpart (elements deleted at a failure strain); erosion_free: no element of the target
# is deleted, the nose opens a pilot hole along the axis and the mesh near it is rezoned (fe.erosion_free)
FORMULATIONS = ("eroding", "erosion_free")


@dataclass(frozen=True)
class TargetSpec:
    kind: str = "semi_infinite"
    radius: float = 4.8          # m (config fe.target_radius; block: BLOCK_RADIUS)
    depth: float | None = None   # m; None: from the expected depth (semi-infinite) or 5.4 (block)
    lateral: str | None = None   # the lateral face, one of TARGET_FACES; None: by kind (semi-infinite non-reflecting)
    bottom: str | None = None    # the bottom face, likewise
    formulation: str = "eroding"  # one of FORMULATIONS
    pilot_hole: float = 0.25     # erosion-free: the pilot hole's radius over the shank's (a study drives it to 0)
    pilot_guide: bool = False    # erosion-free: a rigid frictionless guide fills the hole (its wall cannot enter it)
    ejection_scale: float = 1.0  # erosion-free: ejection this many times as ready (the thinness threshold, which
    #                              also rules the crater wall's debris, times it, the lip's height threshold over it;
    #                              a study halves and doubles it)

    def __post_init__(self):
        if self.kind not in ("semi_infinite", "block"):
            raise ParameterError("fe target", "kind", self.kind, "semi_infinite or block")
        if not self.radius > 0:
            raise ParameterError("fe target", "radius", self.radius, "> 0 (m)")
        if self.depth is not None and not self.depth > 0:
            raise ParameterError("fe target", "depth", self.depth, "> 0 (m) or None")
        if self.formulation not in FORMULATIONS:
            raise ParameterError("fe target", "formulation", self.formulation, f"one of {FORMULATIONS}")
        if not (math.isfinite(self.pilot_hole) and 0.0 < self.pilot_hole < 1.0):
            raise ParameterError("fe target", "pilot_hole", self.pilot_hole, "0 < pilot_hole < 1 (of the shank radius)")
        if not (math.isfinite(self.ejection_scale) and 0.1 <= self.ejection_scale <= 4.0):
            raise ParameterError("fe target", "ejection_scale", self.ejection_scale, "0.1 <= ejection_scale <= 4")
        if self.formulation != "erosion_free" and self.ejection_scale != 1.0:
            raise ParameterError("fe target", "ejection_scale", self.ejection_scale,
                                 "1 on an eroding target (nothing is ejected there; erosion_free only)")
        if not isinstance(self.pilot_guide, bool):
            raise ParameterError("fe target", "pilot_guide", self.pilot_guide, "true or false")
        for name in ("lateral", "bottom"):
            if getattr(self, name) not in (None, *TARGET_FACES):
                raise ParameterError("fe target", name, getattr(self, name), f"one of {TARGET_FACES} or None")

    @classmethod
    def from_scene(cls, fe, target_radius, block_depth):
        """A scene's target (its ``fe`` slice: target, target_radius, target_depth, lateral_boundary,
        bottom_boundary, formulation, pilot_hole, pilot_guide, ejection_scale): its kind's radius and depth (``target_radius``, the semi-infinite target's; the block's
        BLOCK_RADIUS and ``block_depth``) unless the scene sets them."""
        kind = fe.get("target", "semi_infinite")
        block = kind == "block"
        return cls(kind, fe.get("target_radius", BLOCK_RADIUS if block else target_radius),
                   fe.get("target_depth", block_depth if block else None),
                   fe.get("lateral_boundary"), fe.get("bottom_boundary"), fe.get("formulation", "eroding"),
                   fe.get("pilot_hole", 0.25), fe.get("pilot_guide", False), fe.get("ejection_scale", 1.0))

    def boundary(self, face):
        """The boundary of a face ('lateral' or 'bottom'): as set, else free for the block, non-reflecting else."""
        return getattr(self, face) or ("free" if self.kind == "block" else "non_reflecting")


@dataclass(frozen=True)
class Settings:
    """Mesh and run settings of the level (element size in m; the core is core_calibers shank radii wide)."""
    element_size: float = 0.00875
    core_calibers: float = 3.0
    grading: float = 1.1
    depth_margin: float = 1.0      # m of target beyond the expected depth (semi-infinite)
    body_length: float = 1.13      # m, projectile length (Table 2)
    bin_width: float = 2e-6        # s, deceleration bins
    cutoff_hz: float = 10e3        # Hz, declared low-pass cut-off of the deceleration
    output_interval: float = 1e-4  # s
    window_ahead: float | None = 1.5    # m computed ahead of the tip (None: the whole domain)
    window_tail: float | None = 0.5     # m kept behind the tail (rows further behind are retired; None: kept)
    controls: Controls = field(default_factory=Controls)

    @classmethod
    def from_config(cls, cfg, profile, element_size=None):
        """The settings of an ``fe`` config slice at a mesh profile's element size (or ``element_size``): each field
        of the settings and of their controls that the slice names takes its value, every other keeps its default
        here (the config schema only bounds them)."""
        own = {f.name for f in fields(cls)} - {"element_size", "controls"}
        controls = Controls(**{f.name: cfg[f.name] for f in fields(Controls) if f.name in cfg and f.name not in own})
        h = element_size if element_size is not None else cfg["profiles"][profile]["element_size"]
        return cls(element_size=h, controls=controls, **{k: cfg[k] for k in own if k in cfg})

    def with_controls(self, **changes) -> "Settings":
        """These settings with the named solver controls changed."""
        return replace(self, controls=replace(self.controls, **changes))

    def with_failure_strain(self, fs) -> "Settings":
        """These settings with element erosion once the equivalent plastic strain reaches ``fs``."""
        return self.with_controls(erosion="plastic_strain", erosion_value=fs)


@dataclass(frozen=True)
class RunSpec:
    """Everything one FE shot depends on: the rigid projectile (``nose`` + shank to settings.body_length, ``mass``
    in kg, striking ``velocity`` in m/s, Coulomb ``friction`` on its surface), the target's ``material`` (an
    fe.constitutive material: concrete.configured's HJC for a scene) and geometry, the mesh and run settings, and
    ``expected_depth`` (m), which sizes a semi-infinite domain (a run that reaches its bottom is repeated on a
    domain twice as deep)."""
    nose: object
    mass: float
    velocity: float
    material: object
    settings: Settings = field(default_factory=Settings)
    target: TargetSpec = field(default_factory=TargetSpec)
    expected_depth: float = 5.0
    friction: float = 0.0

    def __post_init__(self):
        if not (math.isfinite(self.velocity) and 0 < self.velocity <= 3000):
            raise ParameterError("fe shot", "velocity", self.velocity, "0 < velocity <= 3000 (m/s)")
        if not (math.isfinite(self.mass) and self.mass > 0):
            raise ParameterError("fe shot", "mass", self.mass, "> 0 (kg)")
        if not (math.isfinite(self.expected_depth) and self.expected_depth > 0):
            raise ParameterError("fe shot", "expected_depth", self.expected_depth, "> 0 (m)")
        if not (math.isfinite(self.friction) and 0 <= self.friction <= 1):
            raise ParameterError("fe shot", "friction", self.friction, "0 <= friction <= 1")
        if self.target.formulation == "erosion_free" and self.settings.controls.erosion != "none":
            raise ParameterError("fe shot", "erosion", self.settings.controls.erosion,
                                 "none: the erosion-free target deletes no element")

    def with_settings(self, settings: Settings) -> "RunSpec":
        return replace(self, settings=settings)

    def with_failure_strain(self, fs) -> "RunSpec":
        return replace(self, settings=self.settings.with_failure_strain(fs))
