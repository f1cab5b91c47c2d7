"""A user's nose study: several noses, one projectile and target, velocities and levels -> depths, each nose's
contrast against a reference nose, and the contrast's uncertainty with its parts named.

The contrast of nose X at a level and velocity is depth(X) / depth(reference), both from that level. Its
uncertainty has up to four parts, each a column (relative to the contrast; empty where a part is not included, and
the ``parts`` column names what the combined value holds):

* ``u_validated``: the level's median |contrast error| on the development shots' measured nose pairs
  (figures/fe/PROFILE/validation_nose_pairs_summary.csv, studies.nose_pairs): what the level got wrong about the
  one measured contrast (CRH 6 against CRH 3, one 76.2 mm series), carried over to the user's noses as a scale.
* ``u_calibration``: the contrast's change under the level's other calibration (analytic and trajectory: the other
  published S law; cavity and fe: DO1's calibration against the laboratory one); the fe level's at the top
  velocity only, applied as a relative value at every velocity.
* ``u_chaos`` (fe): the standard deviation of the contrast over ``members`` realisations (the velocity moved by
  k x 1e-9, as the FE chaos studies do) at the top velocity, applied at every velocity; with 2 members it is one
  difference, a rough estimate.
* ``u_mesh`` (fe, with ``mesh_check``): the contrast's change from the study's mesh to the other profile's at the
  top velocity (the full mesh costs about 10-70 times the ci mesh's).

``u_combined`` is their root sum of squares (the parts included): a scale of the contrast's uncertainty, not a
confidence interval.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..errors import ParameterError
from ..levels import LEVELS
from ..nose.nstar import nstar
from ..nose.solve import solve_nose
from .fields import SHOT_FIELDS, field_value
from .ladder import Context, UserShot, psi_from_crh, run, shot_si

MEMBER_STEP = 1e-9          # relative velocity step between realisations (the FE chaos studies' perturbation)
MAX_NOSES, MAX_VELOCITIES, MAX_MEMBERS = 12, 50, 10
SHOT_KEYS = ("mass_kg", "diameter_m", "length_m", "fc_MPa", "target_density_kgm3")
OTHER_LAW = {"li_chen": "forrestal", "forrestal": "li_chen"}


@dataclass(frozen=True)
class Study:
    """What a comparison needs: noses (label -> (kind, keys as nstar takes them, without radius)), the reference
    nose's label, the shot keys (SHOT_KEYS, in their units), velocities (m/s) and levels."""
    noses: dict
    reference: str
    shot: dict
    velocities: tuple
    levels: tuple = ("analytic",)
    members: int = 2
    mesh_check: bool = False
    title: str = ""

    def __post_init__(self):
        if not 2 <= len(self.noses) <= MAX_NOSES:
            raise ParameterError("compare", "noses", len(self.noses), f"2 to {MAX_NOSES} noses")
        if self.reference not in self.noses:
            raise ParameterError("compare", "reference", self.reference, f"one of the noses' labels {list(self.noses)}")
        if not 1 <= len(self.velocities) <= MAX_VELOCITIES:
            raise ParameterError("compare", "velocities", len(self.velocities), f"1 to {MAX_VELOCITIES} velocities")
        for v in self.velocities:
            _field("velocity_ms", v)   # in the shot field's range
        if len(set(self.velocities)) != len(self.velocities):
            raise ParameterError("compare", "velocities", list(self.velocities), "each velocity once")
        for lv in self.levels:
            if lv not in LEVELS:
                raise ParameterError("compare", "levels", lv, f"levels among {list(LEVELS)}")
        if not self.levels or len(set(self.levels)) != len(self.levels):
            raise ParameterError("compare", "levels", list(self.levels), "at least one level, each once")
        if not 2 <= self.members <= MAX_MEMBERS:
            raise ParameterError("compare", "members", self.members, f"2 <= members <= {MAX_MEMBERS} (realisations "
                                 "of the fe level's chaos at the top velocity)")
        unknown = sorted(set(self.shot) - set(SHOT_KEYS))
        if unknown:
            raise ParameterError("compare", unknown[0], self.shot[unknown[0]], f"a shot key among {list(SHOT_KEYS)}")
        for key in ("mass_kg", "diameter_m", "fc_MPa"):
            if key not in self.shot:
                raise ParameterError("compare", key, None, f"required: the {SHOT_FIELDS[key].what}, "
                                     f"{SHOT_FIELDS[key].allowed}")
        for key, value in self.shot.items():
            _field(key, value)
        if "fe" in self.levels and "length_m" not in self.shot:
            raise ParameterError("compare", "length_m", None, "required at the fe level: the projectile's length (m)")


def _field(name, value) -> float:
    """A shot field's value checked against its range (shots.fields), refused as a ParameterError naming it."""
    from .fields import ShotError
    try:
        return field_value(name, str(value))
    except ShotError as err:
        raise ParameterError("compare", name, value, err.allowed) from None


STUDY_KEYS = ("noses", "reference", "shot", "velocities", "levels", "members", "mesh_check", "title")


def study_from_doc(doc, where="study", **override) -> Study:
    """A Study from a study YAML's mapping (STUDY_KEYS); ``override``: values given elsewhere (the command line's
    options), None where not given."""
    doc = doc or {}
    if not isinstance(doc, dict):
        raise ParameterError(where, "contents", type(doc).__name__, f"a mapping of keys {', '.join(STUDY_KEYS)}")
    unknown = sorted(set(doc) - set(STUDY_KEYS))
    if unknown:
        raise ParameterError(where, unknown[0], doc[unknown[0]], f"a key among {', '.join(STUDY_KEYS)}")
    noses = override.get("noses")
    if noses is None:
        noses = {}
        spec_noses = doc.get("noses") or {}
        if not isinstance(spec_noses, dict):
            raise ParameterError(where, "noses", spec_noses, "a mapping label: {kind: ..., key: value}")
        for label, spec in spec_noses.items():
            if not isinstance(spec, dict) or "kind" not in spec:
                raise ParameterError(where, f"noses.{label}", spec, "a mapping with kind and the nose's keys")
            noses[str(label)] = (str(spec["kind"]), {k: str(v) for k, v in spec.items() if k != "kind"})
    shot_doc = doc.get("shot") or {}
    if not isinstance(shot_doc, dict):
        raise ParameterError(where, "shot", shot_doc, f"a mapping of shot keys ({', '.join(SHOT_KEYS)})")
    shot = {k: str(v) for k, v in shot_doc.items()}
    shot.update(override.get("shot") or {})
    pick = lambda key, default: override[key] if override.get(key) is not None else doc.get(key, default)  # noqa: E731
    velocities = pick("velocities", ())
    if not isinstance(velocities, (list, tuple)) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                           for v in velocities):
        raise ParameterError(where, "velocities", velocities, "a list of numbers (m/s)")
    members = pick("members", 2)
    if isinstance(members, bool) or not isinstance(members, int):
        raise ParameterError(where, "members", members, f"a whole number, 2 to {MAX_MEMBERS}")
    levels = pick("levels", ("analytic",))
    levels = (levels,) if isinstance(levels, str) else levels
    if not isinstance(levels, (list, tuple)):
        raise ParameterError(where, "levels", levels, f"a list of levels among {list(LEVELS)}")
    mesh_check = pick("mesh_check", False)
    if not isinstance(mesh_check, bool):
        raise ParameterError(where, "mesh_check", mesh_check, "true or false")
    return Study(noses=noses, reference=str(pick("reference", None) or next(iter(noses), "")), shot=shot,
                 velocities=tuple(float(v) for v in velocities), levels=tuple(str(x) for x in levels),
                 members=members, mesh_check=mesh_check, title=str(pick("title", "")))


def parse_nose(text: str):
    """(label, kind, keys) of a nose given as 'LABEL=KIND key=value ...' (or 'KIND key=value ...': the kind is
    the label)."""
    words = text.split()
    if not words:
        raise ParameterError("compare", "nose", text, "'LABEL=KIND key=value ...'")
    head, rest = words[0], words[1:]
    label, _, kind = head.partition("=") if "=" in head else (head, "", head)
    keys = {}
    for w in rest:
        k, sep, v = w.partition("=")
        if not sep or not k:
            raise ParameterError("compare", f"nose {label}", w, "key=value")
        if k in keys:
            raise ParameterError("compare", f"nose {label}", k, "each key once")
        keys[k] = v
    return label, kind, keys


def build_noses(study: Study):
    """label -> (the nose at the study's shank radius, its Solution or None)."""
    radius = 0.5 * field_value("diameter_m", str(study.shot["diameter_m"]))
    out = {}
    for label, (kind, keys) in study.noses.items():
        if kind == "table":
            raise ParameterError("compare", f"nose {label}", kind, "a nose kind with keys (outline a table's nose "
                                 "by its parameters; every nose of a comparison has the study's shank radius)")
        if "radius" in keys:
            raise ParameterError("compare", f"nose {label}", "radius", "no radius: the shank radius is diameter_m/2")
        out[label] = solve_nose(kind, {"radius": radius, **psi_from_crh(kind, keys)})
    return out


def shots(study: Study, noses: dict, velocity: float, member: int = 0):
    """label -> levels.UserShot at ``velocity`` (moved by member x MEMBER_STEP, relative)."""
    kw = {"density": SHOT_FIELDS["target_density_kgm3"].default,
          **shot_si({k: field_value(k, str(v)) for k, v in study.shot.items()})}
    v = float(velocity) * (1.0 + member * MEMBER_STEP)
    return {label: UserShot(nose, velocity=v, label=f"{label} {velocity:g} m/s", **kw)
            for label, (nose, _) in noses.items()}


@dataclass
class Job:
    level: str
    variant: str        # base, member K, calibration, mesh
    nose: str
    velocity: float
    member: int = 0


def plan(study: Study) -> list:
    """Every run of the comparison: each level, nose and velocity (base), and at the top velocity the calibration
    alternative of each level, the fe level's extra members and, with mesh_check, its other mesh."""
    top = max(study.velocities)
    jobs = [Job(lv, "base", n, v) for lv in study.levels for v in study.velocities for n in study.noses]
    for lv in study.levels:
        vs = study.velocities if lv != "fe" else (top,)
        jobs += [Job(lv, "calibration", n, v) for v in vs for n in study.noses]
        if lv == "fe":
            jobs += [Job(lv, f"member {k}", n, top, k) for k in range(1, study.members) for n in study.noses]
            if study.mesh_check:
                jobs += [Job(lv, "mesh", n, top) for n in study.noses]
    return jobs


def describe_plan(jobs, workers) -> str:
    """The line that announces a comparison's runs."""
    return f"compare: {len(jobs)} runs ({sum(j.level == 'fe' for j in jobs)} at the fe level, {workers} at a time)"


@dataclass
class Contexts:
    """The levels' contexts of each variant: 'base', 'calibration' (the other calibration), 'mesh' (fe's other
    profile); named as the table says them."""
    by_variant: dict
    names: dict = field(default_factory=dict)   # (level, variant) -> what the variant is

    def get(self, level, variant):
        key = "base" if variant.startswith("member") else variant
        return self.by_variant[key]


def contexts(root, profile, strength_law, calibration, levels, mesh_check, fe_max_seconds=math.inf, workers=1):
    """Contexts for the variants the plan uses, from the pipeline under ``root``."""
    from .records import context_from_pipeline
    need_sim = any(lv in ("cavity", "fe") for lv in levels)
    base = context_from_pipeline(root, profile, strength_law, calibration) if need_sim else Context(
        strength_law=strength_law)
    other_cal = "do1" if calibration == "laboratory" else "laboratory"
    # the closed forms' alternative is the other S law; the simulation levels' the other calibration
    by = {"base": base, "calibration_law": Context(strength_law=OTHER_LAW[strength_law]),
          "calibration_sim": context_from_pipeline(root, profile, strength_law, other_cal) if need_sim else None}
    names = {}
    for lv in levels:
        names[(lv, "calibration")] = (f"S law {OTHER_LAW[strength_law]} for {strength_law}" if lv in ("analytic", "trajectory")
                                      else f"calibration {other_cal} for {calibration}")
    if mesh_check and "fe" in levels:
        by["mesh"] = context_from_pipeline(root, "full" if profile == "ci" else "ci", strength_law, calibration)
        names[("fe", "mesh")] = f"mesh {'full' if profile == 'ci' else 'ci'} for {profile}"
    from ..pipeline.config import available_memory
    memory = available_memory() / max(1, workers)   # fe shots run workers at a time
    for c in by.values():
        if c is not None:
            c.fe_max_seconds = fe_max_seconds
            c.fe_available_memory = memory
    return Contexts(by, names)


def context_for(ctxs: Contexts, job: Job):
    if job.variant == "calibration":
        return ctxs.by_variant["calibration_law" if job.level in ("analytic", "trajectory") else "calibration_sim"]
    if job.variant == "mesh":
        return ctxs.by_variant["mesh"]
    return ctxs.by_variant["base"]


def _run_one(args):
    """One job in a worker: (job, depth m, wall s, error text or None); any error of the run is kept as its text (an
    interrupt is not caught)."""
    job, shot, ctx = args
    try:
        res = run(shot, job.level, ctx)
        return job, float(res.depth_m), float(res.wall_time_s), None
    except Exception as err:   # noqa: BLE001 -- a failed run is a row with its reason, never the whole study lost
        return job, math.nan, 0.0, f"{type(err).__name__}: {err}"


def _worker_init():
    try:
        import numba
        numba.set_num_threads(1)
    except (ImportError, ValueError):
        pass


def run_jobs(study: Study, noses: dict, ctxs: Contexts, jobs: list, workers: int = 1, progress=None, done=None):
    """Run ``jobs``: the closed forms and the cavity level in this process, the fe level's shots ``workers`` at a
    time (one numba thread each). ``done``: a list the finished (job, depth, wall, error) are appended to as they
    come (an interrupted run keeps them there). Returns ``done``."""
    done = [] if done is None else done
    cheap = [j for j in jobs if j.level != "fe"]
    heavy = [j for j in jobs if j.level == "fe"]
    total = len(jobs)

    built = {}

    def args(j):
        key = (j.velocity, j.member)
        if key not in built:
            built[key] = shots(study, noses, j.velocity, j.member)
        return j, built[key][j.nose], context_for(ctxs, j)
    for j in cheap:
        done.append(_run_one(args(j)))
        if progress:
            progress(len(done), total)
    if heavy and workers > 1:
        import multiprocessing as mp
        from concurrent.futures import ProcessPoolExecutor, as_completed
        method = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
        pool = ProcessPoolExecutor(workers, mp_context=mp.get_context(method), initializer=_worker_init)
        finished = False
        try:
            futures = {pool.submit(_run_one, args(j)): j for j in heavy}
            for f in as_completed(futures):
                try:
                    done.append(f.result())
                except Exception as err:   # noqa: BLE001 -- a worker that died (out of memory, killed)
                    done.append((futures[f], math.nan, 0.0, f"the worker running it ended: {type(err).__name__}: {err}"))
                if progress:
                    progress(len(done), total)
            finished = True
        finally:
            if not finished:   # an interrupt: the running shots are stopped, not waited for
                for proc in list(getattr(pool, "_processes", {}).values()):
                    proc.terminate()
            pool.shutdown(wait=finished, cancel_futures=True)
    else:
        for j in heavy:
            done.append(_run_one(args(j)))
            if progress:
                progress(len(done), total)
    return done


def validated_errors(root, profile) -> dict:
    """(level, calibration) -> (median |contrast error|, what it rests on), from the committed nose-pair summary
    (empty when the file is missing)."""
    from pathlib import Path
    path = Path(root) / f"figures/fe/{profile}/validation_nose_pairs_summary.csv"
    if not path.is_file():
        return {}
    from ..pipeline.records import read_record
    rows = read_record(path, {"level": "text", "calibration": "text", "pairs": "count", "shots": "count",
                              "noses": "text", "median_abs_contrast_error": "number"},
                       what="the levels' nose-pair validation, rule validation_nose_pairs")
    return {(r["level"], r["calibration"].split(":")[0]): (r["median_abs_contrast_error"],
                                                           f"{r['pairs']} pairs of {r['shots']} shots, {r['noses']}")
            for r in rows}


def _why(errors, level, variant, noses, velocity) -> str:
    """The first error of a variant's runs of ``noses`` at ``velocity`` (why a part is not available)."""
    for n in noses:
        e = errors.get((level, variant, n, velocity))
        if e:
            return e
    return "its runs did not finish"


def base_failures(done) -> list:
    """(job, error) of the base runs that failed: the comparison's depths are missing there."""
    return [(j, e) for j, _, _, e in done if e and j.variant == "base"]


def tabulate(study: Study, noses: dict, done: list, validated: dict, calibration: str, strength_law: str,
             ctxs: Contexts) -> pd.DataFrame:
    """The comparison's table: one row per level, nose and velocity."""
    depth = {(j.level, j.variant, j.nose, j.velocity): d for j, d, _, _ in done}
    wall = {(j.level, j.variant, j.nose, j.velocity): w for j, _, w, _ in done}
    errors = {(j.level, j.variant, j.nose, j.velocity): e for j, _, _, e in done if e}
    top = max(study.velocities)
    ref = study.reference
    rows = []
    for lv in study.levels:
        cal_key = (lv, "none" if lv in ("analytic", "trajectory") else calibration)
        u_val, val_scope = validated.get(cal_key, (math.nan, "no committed nose-pair validation"))

        def contrast(variant, nose, v):
            num, den = depth.get((lv, variant, nose, v), math.nan), depth.get((lv, variant, ref, v), math.nan)
            return num / den if den > 0 else math.nan

        chaos, chaos_n = {}, {}
        if lv == "fe":
            for n in study.noses:
                c = np.array([contrast("base" if k == 0 else f"member {k}", n, top) for k in range(study.members)])
                c = c[np.isfinite(c)]
                chaos_n[n] = c.size
                chaos[n] = float(np.std(c, ddof=1) / np.mean(c)) if c.size >= 2 else math.nan
        for v in study.velocities:
            for n, (nose, sol) in noses.items():
                c = contrast("base", n, v)
                parts, u = [], {}
                if n != ref:
                    u["u_validated"] = u_val
                    parts.append(f"validated (the level's median |contrast error|, {val_scope})")
                    cal_v = v if lv != "fe" else top
                    u["u_calibration"] = abs(contrast("calibration", n, cal_v) / contrast("base", n, cal_v) - 1.0)
                    parts.append(f"calibration ({ctxs.names.get((lv, 'calibration'), '')}"
                                 + (f", at {top:g} m/s)" if lv == "fe" else ")")
                                 + ("" if math.isfinite(u["u_calibration"]) else " not available: "
                                    + _why(errors, lv, "calibration", (n, ref), cal_v)))
                    if lv == "fe":
                        u["u_chaos"] = chaos[n]
                        parts.append(f"chaos ({chaos_n[n]} realisations at {top:g} m/s)" if chaos_n[n] >= 2 else
                                     f"chaos not available: {chaos_n[n]} of {study.members} realisations at {top:g} m/s "
                                     "finished")
                        if study.mesh_check:
                            u["u_mesh"] = abs(contrast("mesh", n, top) / contrast("base", n, top) - 1.0)
                            parts.append(f"mesh ({ctxs.names.get(('fe', 'mesh'), '')}, at {top:g} m/s)"
                                         + ("" if math.isfinite(u["u_mesh"]) else " not available: "
                                            + _why(errors, lv, "mesh", (n, ref), top)))
                        else:
                            parts.append("mesh not included (--mesh-check)")
                finite = [x for x in u.values() if math.isfinite(x)]
                rows.append({
                    "level": lv, "nose": n, "kind": study.noses[n][0], "nstar": nstar(nose), "nose_length_m": nose.length,
                    "velocity_ms": v, "depth_m": depth.get((lv, "base", n, v), math.nan),
                    "contrast": c if n != ref else 1.0, "reference": ref,
                    "u_validated": u.get("u_validated", math.nan), "u_calibration": u.get("u_calibration", math.nan),
                    "u_chaos": u.get("u_chaos", math.nan), "u_mesh": u.get("u_mesh", math.nan),
                    "u_combined": math.sqrt(sum(x * x for x in finite)) if n != ref and finite else math.nan,
                    "parts": "; ".join(parts) if n != ref else "the reference nose",
                    "wall_time_s": wall.get((lv, "base", n, v), math.nan),
                    "error": errors.get((lv, "base", n, v), "")})
    return pd.DataFrame(rows)


def reused(ctxs: Contexts, levels) -> list:
    """What the comparison carries over from the pipeline (printed by the command line)."""
    base = ctxs.by_variant["base"]
    out = []
    if "cavity" in levels:
        out.append(f"cavity strength scale {base.strength_scale:.4g} ({base.strength_scale_source})")
    if "fe" in levels:
        out.append(f"fe failure strain {base.failure_strain:.4g} ({base.failure_strain_source})")
    return out


def describe_inputs(study: Study) -> str:
    s = study.shot
    parts = [f"m = {float(s['mass_kg']):g} kg", f"d = {1e3 * float(s['diameter_m']):g} mm"]
    if "length_m" in s:
        parts.append(f"L = {1e3 * float(s['length_m']):g} mm")
    parts.append(f"fc = {float(s['fc_MPa']):g} MPa")
    if "target_density_kgm3" in s:
        parts.append(f"rho = {float(s['target_density_kgm3']):g} kg/m^3")
    return ", ".join(parts) + f"; contrast against {study.reference}"


def output_files(out) -> dict:
    """The files a comparison writes into folder ``out``."""
    from pathlib import Path
    return {name: Path(out) / name for name in ("compare.csv", "compare.png", "noses.csv", "noses.png")}


def prepare(study: Study, root, profile="ci", strength_law="li_chen", calibration="laboratory", fe_max_seconds=math.inf,
            say=None, workers=1):
    """Everything checked before any run: (the noses, the contexts, the validated contrast errors); ``say`` gets
    the solved noses and what the comparison reuses."""
    say = say or (lambda line: None)
    noses = build_noses(study)
    for label, (_, sol) in noses.items():
        if sol is not None:
            say(f"nose {label}: {sol.describe()}")
    shots(study, noses, max(study.velocities))   # the shot's checks
    ctxs = contexts(root, profile, strength_law, calibration, study.levels, study.mesh_check, fe_max_seconds, workers)
    for line in reused(ctxs, study.levels):
        say(f"reuses {line}")
    from ..pipeline.records import RecordError
    try:
        validated = validated_errors(root, profile if "fe" in study.levels else "full")
    except RecordError as err:
        say(f"warning: {err}; the validated part of the contrasts' uncertainty is left out")
        validated = {}
    return noses, ctxs, validated


def nose_rows(study: Study, noses: dict) -> pd.DataFrame:
    """One row per nose: its kind, keys, the solved key, radius, length and N*."""
    rows = []
    for label, (nose, sol) in noses.items():
        kind, keys = study.noses[label]
        rows.append({"nose": label, "kind": kind, "keys": " ".join(f"{k}={v}" for k, v in keys.items()),
                     "solved": sol.describe() if sol else "", "radius_m": nose.radius, "nose_length_m": nose.length,
                     "nstar": nstar(nose)})
    return pd.DataFrame(rows)


def drawing(study: Study, noses: dict, title_wrap=lambda t: t) -> dict:
    """What figures.compare.write_comparison draws besides the table: the noses' rows, their cumulative N* curves
    and the title."""
    from ..nose.nstar import cumulative_nstar
    return {"noses": nose_rows(study, noses), "title": title_wrap(study.title or describe_inputs(study)),
            "curves": {label: cumulative_nstar(nose, 120) for label, (nose, _) in noses.items()}}


def with_workers(n=None) -> int:
    return max(1, min(n or os.cpu_count() or 1, os.cpu_count() or 1))
