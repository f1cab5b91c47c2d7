"""Every rung of the fidelity ladder for a user's own shot: depth, time to rest, peak deceleration, cost.

Levels (``LEVELS``):

- ``analytic``: Eq 9 (Forrestal's crater F = c z up to 4a, then Eq 7's tunnel
  force), with S from a published S(fc) law; the time to rest and the peak
  deceleration in the closed form of the same two-phase model.
- ``trajectory``: the rigid-body trajectory (crater, static and inertial
  effects) integrated in time, the same target law.
- ``cavity``: the HJC sigma_n(v) table of the shot's concrete (dynamic
  spherical cavity expansion) integrated over the nose along the trajectory.
- ``fe``: the 2-D axisymmetric finite-element level (HJC target with erosion,
  rigid projectile), minutes per shot.

The concrete of the cavity and fe levels is Table 1's HJC set with the configured conventions (``Context.base``),
scaled to the shot's fc and density by the HJC scaling rule of ``concrete`` (``concrete.shot_concrete``).

Calibrations: the cavity level's strength_scale (a factor on the strength surface) fitted on the laboratory shots
(``laboratory``, the default) or on the DO1 shot (5.1 m at 835 m/s, 48 MPa); the fe level's failure strain likewise,
fitted per mesh profile (DO1's where a profile has no laboratory record), the latter on the calibration's mesh scaled with
the projectile: the same elements across the shank radius, and the core,
window, margins, target radius, output interval, deceleration bins and
filter cut-off in proportion to the radius (the time scales with the length
at equal velocity). Neither is refitted to the user's shots.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..analytic.dop import penetration_depth
from ..analytic.resistance import STRENGTH_LAWS, Target, crater_coefficient, crater_velocity_squared, strength_factor
from ..analytic.trajectory import assemble, integrate
from ..cavity.expansion import Controls as CavityControls, Mesh as CavityMesh
from ..cavity.level import SigmaTable, cavity_trajectory, sigma_table
from ..concrete.hjc import HJC
from ..concrete.material import shot_concrete
from ..concrete.size import SizeEffect, fracture_factor, regularised, sized_target, with_rate_law
from ..errors import ParameterError
from ..levels import LEVELS
from ..nose.geometry import NOSES
from ..nose.nstar import nstar
from ..nose.solve import CONSTRAINTS, solve_nose
from .fields import (ATTRIBUTE_FIELDS, SHOT_FIELDS, ShotError, crh_value, eq9_columns, expected_depth, field_value,
                     output_fields as shots_output_fields, row_nose, row_predictions, shot_values)

TRAJECTORY_EFFECTS = ("crater", "static", "inertial")
CAVITY_EFFECTS = ("crater", "cavity")
# Ranges of a user's shot (SI, exclusive low, inclusive high) by UserShot attribute: those of shots.SHOT_FIELDS
SHOT_RANGES = {attr: (SHOT_FIELDS[name].lo * SHOT_FIELDS[name].si, SHOT_FIELDS[name].hi * SHOT_FIELDS[name].si)
               for attr, name in ATTRIBUTE_FIELDS.items()}


@dataclass(frozen=True)
class UserShot:
    """One shot: a nose of the registry (with its shank radius), the projectile and the concrete (SI)."""
    nose: object
    mass: float
    velocity: float
    fc: float
    density: float = 2440.0
    length: float | None = None   # projectile length (m); needed by the fe level only
    label: str = ""
    defaults: tuple = ()          # the shot fields (shots.SHOT_FIELDS names) the user left to their defaults

    def __post_init__(self):
        """Each attribute in its range; an error names the shot field (shots.SHOT_FIELDS) and its unit."""
        for attr, (lo, hi) in SHOT_RANGES.items():
            v = getattr(self, attr)
            if v is None and attr == "length":
                continue
            if not (isinstance(v, (int, float)) and math.isfinite(v) and lo < v <= hi):
                name = ATTRIBUTE_FIELDS[attr]
                f = SHOT_FIELDS[name]
                raise ParameterError("shot", name, v / f.si if isinstance(v, (int, float)) else v, f.allowed)
        if self.length is not None and self.length < self.nose.length:
            raise ParameterError("shot", "length_m", self.length,
                                 f">= the nose length {self.nose.length:.6g} m (the projectile is nose and shank)")


def closed_form(mass, radius, n, target: Target, vs):
    """Depth, time to rest and peak deceleration of Forrestal's two-phase model (Eq 8 crater, Eq 7 tunnel).

    Crater: m z'' = -c z, so z = (vs/w) sin(w t), w = sqrt(c/m), up to z = 4a;
    tunnel: m v' = -pi a^2 (S fc + N* rho v^2), so t = atan(V1 sqrt(b/k))/sqrt(k b)
    with k = pi a^2 S fc/m, b = pi a^2 N* rho/m. The force grows through the
    crater and falls in the tunnel: its peak is at z = 4a. A shot that stops
    in the crater (V1^2 <= 0) rests at t = pi/(2w) with the peak c z_max/m.
    """
    depth = float(penetration_depth(mass, radius, n, target, vs))
    c = float(crater_coefficient(mass, radius, n, target, vs))
    v1sq = float(crater_velocity_squared(mass, radius, n, target, vs))
    w = math.sqrt(c / mass)
    if v1sq <= 0:
        return depth, 0.5 * math.pi / w, vs * w
    t1 = math.asin(min(1.0, 4.0 * radius * w / vs)) / w
    k = math.pi * radius**2 * target.R / mass
    b = math.pi * radius**2 * n * target.rho / mass
    t2 = math.atan(math.sqrt(v1sq * b / k)) / math.sqrt(k * b)
    return depth, t1 + t2, 4.0 * radius * c / mass


@dataclass
class LevelResult:
    level: str
    depth_m: float
    time_to_rest_s: float
    peak_deceleration_m_s2: float
    wall_time_s: float
    status: str = "rest"
    notes: str = ""
    history: dict | None = None
    fields: tuple | None = None   # the fe level's (snapshots, element corners) where Context.fe_snapshot_times asks

    def record(self) -> dict:
        return {"level": self.level, "depth_m": self.depth_m, "time_to_rest_s": self.time_to_rest_s,
                "peak_deceleration_m_s2": self.peak_deceleration_m_s2, "wall_time_s": self.wall_time_s,
                "status": self.status, "notes": self.notes}


@dataclass
class Context:
    """What the levels beyond the closed form need: the base HJC set (Table 1 with the configured conventions,
    concrete.configured), the DO1 calibrations, the solvers' settings.

    ``tables`` caches sigma_n tables per (material, radius), so that shots on a few distinct concretes and
    calibers cost a few tables; ``table_builds`` counts the tables computed.
    """
    base: HJC = field(default_factory=HJC)
    strength_law: str = "li_chen"
    strength_factor_scale: float = 1.0     # a factor on the law's S (the closed forms' calibration; 1: the law as published)
    size: SizeEffect | None = None         # the scale effect (concrete.size), None: every level scale-free
    strength_scale: float | None = None
    strength_scale_source: str = ""
    strength_scale_record: str = "figures/calibration_cavity_laboratory.csv"   # named when the scale is missing
    failure_strain: float | None = None
    failure_strain_source: str = ""
    fe_reference_radius: float = 0.07       # m: shank radius of the DO1 mesh the failure strain belongs to
    fe_settings: object = None              # fe.shot.Settings of the calibration mesh (None: its defaults)
    fe_target_radius: float = 4.8           # m, at the reference radius (config fe.target_radius)
    cavity_velocities: tuple = (50.0, 100.0, 150.0, 200.0, 300.0, 400.0, 500.0, 600.0, 800.0, 1000.0, 1200.0, 1500.0,
                                2000.0)
    cavity_mesh: CavityMesh = field(default_factory=CavityMesh)
    cavity_controls: CavityControls = field(default_factory=CavityControls)
    trajectory_rtol: float = 1e-8
    cavity_rtol: float = 1e-9
    tables: dict = field(default_factory=dict)
    table_builds: int = 0
    fe_max_seconds: float = math.inf        # an fe shot estimated to cost more is refused before it runs
    fe_profile: str = "full"                # the mesh profile of the fe calibration (named in messages)
    fe_available_memory: float = math.inf   # bytes an fe shot may use (the caller reads what is free now)
    fe_snapshot_times: tuple = ()           # s: the fe level keeps the target's state at these times and at the end

    def __post_init__(self):
        if self.strength_law not in STRENGTH_LAWS:
            raise ParameterError("levels", "strength_law", self.strength_law, f"one of {sorted(STRENGTH_LAWS)}")

    def table(self, material: HJC, radius) -> SigmaTable:
        key = (material, float(radius))
        if key not in self.tables:
            self.tables[key], _ = sigma_table(material, self.cavity_velocities, radius, self.cavity_mesh,
                                              self.cavity_controls)
            self.table_builds += 1
        return self.tables[key]


def _target(shot: UserShot, ctx: Context) -> Target:
    """The closed forms' target: S of the context's law, times its calibration factor and the scale effect's factor
    at the shot's calibre and striking velocity (V/d, concrete.size) where the context has one."""
    S = float(strength_factor(shot.fc, ctx.strength_law)) * ctx.strength_factor_scale
    return sized_target(Target(shot.density, shot.fc, S), ctx.size, 2.0 * shot.nose.radius, shot.velocity)


def _s_note(ctx):
    """How the closed forms' S was made, for a result's notes."""
    return (f"S from {ctx.strength_law}" + (f" times {ctx.strength_factor_scale:.6g}" if ctx.strength_factor_scale != 1.0
                                            else "") + (f", scale effect {'+'.join(ctx.size.mechanisms)}" if ctx.size else ""))


def _analytic(shot, ctx):
    n = nstar(shot.nose)
    depth, t, peak = closed_form(shot.mass, shot.nose.radius, n, _target(shot, ctx), shot.velocity)
    return LevelResult("analytic", depth, t, peak, 0.0, notes=_s_note(ctx))


def _from_trajectory(level, tr, notes):
    hist = {"t": tr.t, "depth": tr.z, "velocity": tr.v, "deceleration": tr.deceleration}
    return LevelResult(level, tr.depth, tr.duration, float(np.max(tr.deceleration)), 0.0, notes=notes, history=hist)


def _trajectory(shot, ctx):
    asm = assemble(TRAJECTORY_EFFECTS, shot.nose, nstar(shot.nose), shot.mass, _target(shot, ctx), shot.velocity)
    tr = integrate(asm, shot.mass, shot.velocity, rtol=ctx.trajectory_rtol)
    return _from_trajectory("trajectory", tr, f"effects {'+'.join(TRAJECTORY_EFFECTS)}, {_s_note(ctx)}")


def _need(value, name, how, owner="levels"):
    if value is None:
        raise ParameterError(owner, name, None, how)
    return value


def cavity_material(shot: UserShot, ctx: Context) -> HJC:
    """The cavity level's concrete of a shot: the base set scaled to its fc and density, at the calibrated strength
    scale; with the scale effect, times its fracture factor at the shot's calibre and with MC2010's rate factor at
    each point's rate in place of HJC's (its rate mechanism)."""
    rec = ctx.strength_scale_record
    scale = _need(ctx.strength_scale, "strength_scale", f"the cavity level's calibration (its committed record {rec}: "
                  f"snakemake -c2 {rec}; or --calibration do1|laboratory|FILE, or give a strength scale: "
                  "--strength-scale)")
    scale *= fracture_factor(ctx.size, 2.0 * shot.nose.radius)
    return with_rate_law(shot_concrete(ctx.base, shot.fc, shot.density, scale), ctx.size)


def fe_material(shot: UserShot, ctx: Context) -> HJC:
    """The fe level's concrete of a shot: the base set scaled to its fc and density (its calibration, the failure
    strain, belongs to the run settings); with the scale effect's rate mechanism, MC2010's rate factor at each
    element's rate in place of HJC's (its fracture mechanism, a crack band, needs the element size: fe_spec)."""
    return with_rate_law(shot_concrete(ctx.base, shot.fc, shot.density), ctx.size)


def check_table_span(shot: UserShot, ctx: Context):
    """Refuse a striking velocity above the top of the cavity level's sigma_n(v) table: beyond it the table would
    continue as a straight line in v^2 through its two fastest nodes (cavity_level.SigmaTable), a law nothing
    computed. The normal velocity over the nose never exceeds the striking velocity, so up to the top every
    stress the trajectory asks for is the table's own."""
    top = max(ctx.cavity_velocities)
    if shot.velocity > top:
        raise ParameterError("shot", "velocity_ms", shot.velocity,
                             f"at most {top:g} m/s at the cavity level: its sigma_n(v) table spans 0-{top:g} m/s (the "
                             "config's cavity.velocities; add faster velocities there to go further)")


def _cavity(shot, ctx):
    check_table_span(shot, ctx)
    table = ctx.table(cavity_material(shot, ctx), shot.nose.radius)
    tr = cavity_trajectory(shot.nose, shot.mass, shot.velocity, table, CAVITY_EFFECTS, rtol=ctx.cavity_rtol)
    return _from_trajectory("cavity", tr, f"HJC scaled to fc = {shot.fc / 1e6:.4g} MPa, strength_scale "
                            f"{ctx.strength_scale:.6g} ({ctx.strength_scale_source})")


def fe_settings_for(shot: UserShot, ctx: Context):
    """The calibration mesh and run settings scaled to the shot's radius (same elements across the radius)."""
    from ..fe.shot import Settings
    rec = f"figures/fe/{ctx.fe_profile}/calibration_fe_do1.csv"
    fs = _need(ctx.failure_strain, "failure_strain", f"the fe level's DO1 calibration (its committed record {rec}: "
               f"snakemake -c2 {rec}; or give a failure strain: --failure-strain)")
    length = _need(shot.length, "length_m", "the projectile length in m (the fe level meshes nose and shank)", "shot")
    base = ctx.fe_settings or Settings()
    k = shot.nose.radius / ctx.fe_reference_radius
    scaled = lambda x: None if x is None else x * k
    controls = dataclasses.replace(base.controls, end_time=base.controls.end_time * max(1.0, k))
    s = dataclasses.replace(base, element_size=base.element_size * k, depth_margin=base.depth_margin * k,
                            body_length=length, bin_width=base.bin_width * k, cutoff_hz=base.cutoff_hz / k,
                            output_interval=base.output_interval * k, window_ahead=scaled(base.window_ahead),
                            window_tail=scaled(base.window_tail), controls=controls)
    return s.with_failure_strain(fs), k


def fe_spec(shot: UserShot, ctx: Context):
    """The fe level's run spec of a user's shot, built once: the calibration mesh and settings scaled to the shot's
    radius (fe_settings_for), the shot's concrete (fe_material; with the scale effect's crack band at the mesh's
    element size), a semi-infinite target of the context's radius
    scaled likewise, and the domain's depth from the closed form (shots.expected_depth). Returns (spec, scale)."""
    from ..fe.level import run_spec
    from ..fe.shot import TargetSpec
    settings, k = fe_settings_for(shot, ctx)
    material = regularised(fe_material(shot, ctx), ctx.size, settings.element_size)
    return run_spec(shot.nose, shot.mass, shot.velocity, material, settings,
                    TargetSpec("semi_infinite", ctx.fe_target_radius * k),
                    expected_depth(shot.nose, shot.mass, shot.velocity, shot.fc, shot.density)), k


def _fe(shot, ctx, log=None):
    """The fe level: its cost is estimated first (fe.level.estimate_cost, told to ``log``), and a shot estimated to
    cost more than ctx.fe_max_seconds is refused before it runs (no estimate, which probes the kernels for about a
    second, when there is neither a limit nor a log to tell it to)."""
    from ..fe.level import estimate_cost
    from ..fe.shot import progress_to, run_shot
    spec, _ = fe_spec(shot, ctx)
    settings = spec.settings
    est = None
    if log is not None or math.isfinite(ctx.fe_max_seconds):
        est = estimate_cost(spec, max_seconds=ctx.fe_max_seconds, available_memory=ctx.fe_available_memory)
        if log is not None:
            log(est.describe())
    if est is not None and est.seconds > ctx.fe_max_seconds:
        raise ParameterError("fe shot", "estimated cost", ("" if est.ns_per_element_step else "at least ")
                             + f"{est.seconds / 60:.3g} min",
                             f"at most --max-minutes {ctx.fe_max_seconds / 60:g} ({est.describe()}); raise "
                             "--max-minutes to run it")
    with progress_to(log):
        r = run_shot(spec, snapshot_times=ctx.fe_snapshot_times)
    s = r.summary()
    notes = (f"HJC scaled to fc = {shot.fc / 1e6:.4g} MPa, failure strain {ctx.failure_strain:.6g} "
             f"({ctx.failure_strain_source}), {shot.nose.radius / settings.element_size:.3g} elements across the radius, "
             f"{r.elements} elements, energy error {s['energy_error_max']:.2g}"
             + (f", estimated cost {est.seconds:.3g} s" if est is not None else ""))
    h = r.histories
    tb = h["t_bins"]   # depth and velocity on the deceleration's bins
    hist = {"t": tb, "depth": np.interp(tb, h["t"], h["depth"]), "velocity": np.interp(tb, h["t"], h["velocity"]),
            "deceleration": h["deceleration"]}
    return LevelResult("fe", r.depth, r.time, r.peak_deceleration, 0.0, status=r.status, notes=notes, history=hist,
                       fields=(r.snapshots, r.conn) if ctx.fe_snapshot_times else None)


RUNNERS = {"analytic": _analytic, "trajectory": _trajectory, "cavity": _cavity, "fe": _fe}


def run(shot: UserShot, level: str, ctx: Context, log=None) -> LevelResult:
    """Run one shot at one level; the result's wall_time_s is this call's (sigma_n tables built for it included)."""
    if level not in RUNNERS:
        raise ParameterError("levels", "model", level, f"one of {list(LEVELS)}")
    t0 = time.perf_counter()
    res = RUNNERS[level](shot, ctx, log) if level == "fe" else RUNNERS[level](shot, ctx)
    res.wall_time_s = time.perf_counter() - t0
    return res


# ------------------------------------------------------------------ shots CSV rows at any level
def shot_si(values: dict) -> dict:
    """UserShot keyword arguments (SI) from shot field values in their units (those given)."""
    return {SHOT_FIELDS[name].attribute: v * SHOT_FIELDS[name].si for name, v in values.items()
            if SHOT_FIELDS[name].attribute}


def user_shot(row, base=None) -> UserShot:
    """The UserShot of a shots-CSV row (fields checked as shots.shot_values does; length_m, when the row has it,
    for the fe level; the nose from nose_shape and its columns, shots.fields.row_nose, a table's path relative to
    ``base``)."""
    v = shot_values(row, base)
    nose = row_nose(row, 0.5 * v["diameter_m"], base)
    try:
        return UserShot(nose, **shot_si(v), label=row.get("shot_id", ""))
    except ValueError as err:
        raise ShotError(str(err)) from None


# keys of the former command line (SI, radius instead of diameter) -> the shot field that replaces each
FORMER_KEYS = {"mass": "mass_kg", "velocity": "velocity_ms", "fc": "fc_MPa", "density": "target_density_kgm3",
               "radius": "diameter_m", "length": "length_m"}


def nose_keys(kind) -> list:
    """The keys of a nose kind on dop and simulate's command line: its own (as nstar takes them) minus radius,
    which is diameter_m/2 (an ogive's psi may also be given as crh, the shots CSV's name), and the constraints of a
    nose by constraint (nose.solve.CONSTRAINTS, solve) for every kind with a free parameter."""
    if kind == "table":
        return ["path"]
    keys = [f.name for f in dataclasses.fields(NOSES[kind]) if f.name != "radius"]
    return keys + (["crh"] if kind == "ogive" else []) + ([*CONSTRAINTS, "solve"] if kind != "flat" else [])


def psi_from_crh(kind, keys: dict) -> dict:
    """An ogive's keys with crh (the shots CSV's name for psi, checked against its range) given as psi."""
    if kind != "ogive" or "crh" not in keys:
        return keys
    keys = dict(keys)
    if "psi" in keys:
        raise ParameterError("ogive", "crh", keys["crh"], f"psi or crh, not both (psi={keys['psi']} is given): crh is "
                             "the shots CSV's name for psi")
    try:
        keys["psi"] = crh_value(keys.pop("crh"))
    except ShotError as err:
        raise ParameterError("ogive", "crh", err.value, err.allowed) from None
    return keys


def shot_from_keywords(kind, keywords: dict, label="") -> UserShot:
    """The UserShot of dop and simulate's keys: the shot fields of shots.SHOT_FIELDS (in their units) and the keys
    of a nose of ``kind`` (nose_keys). A key of the former vocabulary is refused with the key that replaces it.

    diameter_m sets the nose's shank radius (diameter_m/2); a table nose has its own (its last y), and a
    diameter_m given with it must be twice that.
    """
    if kind not in NOSES:
        raise ParameterError("nose", "kind", kind, f"one of {sorted(NOSES)}")
    kw = dict(keywords)
    allowed_nose = nose_keys(kind)
    for key in kw:
        if key in SHOT_FIELDS or key in allowed_nose:
            continue
        if key in FORMER_KEYS:
            name = FORMER_KEYS[key]
            raise ParameterError("shot", key, kw[key], f"{key} is not a shot key: give {name} "
                                 f"({SHOT_FIELDS[name].unit}), the {SHOT_FIELDS[name].what}")
        raise ParameterError("shot", key, kw[key], f"a shot key ({', '.join(SHOT_FIELDS)}) or a key of the {kind} nose "
                             f"({', '.join(allowed_nose) or 'none'})")
    values, defaults = {}, []
    for name, f in SHOT_FIELDS.items():
        text = kw.pop(name, None)
        if text is None:
            if f.default is not None:
                values[name] = f.default
                defaults.append(name)
            elif name == "length_m" or (name == "diameter_m" and kind == "table"):
                continue
            else:
                raise ParameterError("shot", name, None, f"required: the {f.what}, {f.allowed}")
        else:
            try:
                values[name] = field_value(name, text)
            except ShotError as err:
                raise ParameterError("shot", name, text, err.allowed) from None
    kw = psi_from_crh(kind, kw)
    if kind == "table":
        nose = solve_nose(kind, kw)[0]
        if "diameter_m" in values and not math.isclose(values["diameter_m"], 2.0 * nose.radius, rel_tol=1e-9):
            raise ParameterError("shot", "diameter_m", values["diameter_m"], f"twice the table's shank radius (its "
                                 f"last y, {nose.radius:g} m): {2.0 * nose.radius:g} m, or leave diameter_m out")
    else:
        nose = solve_nose(kind, {"radius": 0.5 * values["diameter_m"], **kw})[0]
    return UserShot(nose, **shot_si(values), label=label, defaults=tuple(defaults))


# columns a prediction adds (one the input already has is replaced)
PREDICTED = ["model", "dop_pred_m", "time_to_rest_pred_s", "peak_deceleration_pred_m_s2", "wall_time_s"]


def output_fields(fields, level="analytic"):
    """Header of the predictions: the input's fields, then dop_pred_m (analytic) or every PREDICTED column."""
    if level == "analytic":
        return shots_output_fields(fields)
    return [f for f in fields if f not in PREDICTED] + PREDICTED


def predict_rows(rows, law="li_chen", level="analytic", ctx=None, progress=None, good=None, base=None):
    """Predictions for shot rows at any level: (rows with the predicted columns added, 'row N: reason' per skipped
    row), as fields.eq9_columns for the analytic level (dop_pred_m only: Eq 9); the other levels add the time to
    rest, the peak deceleration and the wall time of each shot and need ``ctx``. A run that fails (an unstable
    FE run) skips its row with the reason. ``progress(i, n)`` is called after each row. ``good``: a list the
    predicted rows are appended to as they come (an interrupted run keeps them there). ``base``: the folder a table
    nose's path is relative to (the shots file's).
    """
    if level == "analytic" and (ctx is None or ctx.size is None):
        return row_predictions(rows, eq9_columns(law, base))
    if level == "analytic":   # with the scale effect: the ladder's analytic level, S x the effect's factor per shot
        return row_predictions(rows, lambda row: {"dop_pred_m": f"{run(user_shot(row, base), level, ctx).depth_m:.6g}"},
                               (ShotError, ValueError), progress, good)

    def predict(row):
        res = run(user_shot(row, base), level, ctx)
        return {"model": level, "dop_pred_m": f"{res.depth_m:.6g}", "time_to_rest_pred_s": f"{res.time_to_rest_s:.6g}",
                "peak_deceleration_pred_m_s2": f"{res.peak_deceleration_m_s2:.6g}",
                "wall_time_s": f"{res.wall_time_s:.4g}"}
    # RuntimeError: a run that failed (fe.solver.Unstable)
    return row_predictions(rows, predict, (ShotError, ValueError, RuntimeError), progress, good)

