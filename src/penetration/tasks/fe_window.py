"""The FE level's moving window against the whole domain, on DO1 (eroding target) and on shots of the erosion-free
target.

The level's shots compute only the rows from ``fe.window_tail`` behind the
projectile's tail to ``fe.window_ahead`` ahead of its tip. This study runs the
DO1 shot (semi-infinite target, the profile's calibrated failure strain) with
that window and with the whole domain, each at several realisations of the
erosion chaos (struck at v (1 + k velocity_step), as the ensembles), and
compares the mean depths. A single pair of shots would measure the chaos as
much as the window (the DO1 depth moves by up to 2 % between realisations at
the default mesh), hence the means and an equivalence test: the window passes
if the whole Welch t interval of the difference of the means (at
``confidence``; two one-sided tests at (1 - confidence) / 2 each) lies within
+-``goal_pct`` per cent of the whole domain's mean depth. The interval is
divided by the whole domain's mean as if it were exact (its own uncertainty,
a few tenths of a per cent of it, is left out; penetration.studies.fe_results.window_summary).
"""
from __future__ import annotations

from types import SimpleNamespace

import pandas as pd

from ..fe.level import DOMAINS
from ..fe.spec import Settings
from ..pipeline.io import task, write_csv
from ..studies.fe_results import window_summary
from .fe import scene_shot


@task
def fe_window_study(inputs, outputs, params):
    """DO1 with the moving window and with the whole domain, ``members`` realisations each."""
    window_study(inputs, outputs, params, "double_ogive")


@task
def fe_erosion_free_window(inputs, outputs, params):
    """One shot of an erosion-free scene (``params.nose`` at ``params.velocity``) with the moving window and with the
    whole domain, ``members`` realisations each."""
    window_study(inputs, outputs, params, params.nose)


@task
def fe_table3_window(inputs, outputs, params):
    """One Table 3 shot of the eroding target (``params.nose`` at ``params.velocity``, the failure strain calibrated on
    DO1 at the mesh) with the moving window and with the whole domain, ``members`` realisations each."""
    window_study(inputs, outputs, params, params.nose)


@task
def fe_target_radius(inputs, outputs, params):
    """The semi-infinite target's radius (its lateral boundary non-reflecting: a dashpot, which carries no static
    load, so that a target of finite radius confines the concrete less than an infinite one): each shot of
    ``params.shots`` (nose_velocity) of the scene at each radius of ``params.radii`` (m), one realisation each; the
    depth against the largest radius's."""
    rows = []
    for name in params.shots:
        nose, velocity = name.rsplit("_", 1)
        for radius in params.radii:
            print(f"target radius study: {nose} at {velocity} m/s, radius {radius:g} m", flush=True)
            shot = SimpleNamespace(cfg={**params.cfg, "target_radius": float(radius)}, hjc=params.hjc,
                                   profile=params.profile, nose=nose, velocity=velocity)
            summary, r, _, sc = scene_shot(inputs, shot)
            rows.append({"nose": nose, "velocity_ms": float(velocity), "target_radius_m": float(radius),
                         "target_radius_over_shank": float(radius) / sc.radius, "depth_m": r.depth, "status": r.status,
                         "time_to_rest_s": r.time, "steps": r.steps, "mesh_elements": r.elements,
                         "element_size_m": summary["element_size"], "wall_time_s": r.wall_time})
    runs = pd.DataFrame(rows).sort_values(["nose", "velocity_ms", "target_radius_m"], kind="stable")
    widest = runs.groupby(["nose", "velocity_ms"]).depth_m.transform("last")
    runs["depth_over_widest"] = runs.depth_m / widest
    write_csv(runs, outputs.csv)


def window_study(inputs, outputs, params, nose):
    """The scene's shot of ``nose`` at ``params.velocity`` with the moving window and with the whole domain."""
    members, step = int(params.members), float(params.velocity_step)
    if members < 2:
        raise ValueError(f"fe_window.members = {members}; allowed: >= 2 (a mean and its spread)")
    if not 0.0 < step <= 1e-6:
        raise ValueError(f"fe_window.velocity_step = {step}; allowed: 0 < velocity_step <= 1e-6")
    level = Settings.from_config(params.cfg, params.profile)
    if level.window_ahead is None and level.window_tail is None:
        raise ValueError("fe.window_ahead and fe.window_tail are both unset: there is no window to compare")
    rows, wall = [], []
    shot = SimpleNamespace(cfg=params.cfg, hjc=params.hjc, profile=params.profile, nose=nose, velocity=params.velocity)
    for domain in DOMAINS:
        for k in range(members):
            print(f"window study, {nose} at {params.velocity} m/s: {domain} domain, realisation {k + 1} of {members}", flush=True)
            factor = 1.0 + k * step
            summary, r, _, _ = scene_shot(inputs, shot, factor, domain)
            rows.append({"domain": domain, "member": k, "striking_velocity_ms": summary["velocity"] * factor,
                         "depth_m": r.depth, "status": r.status, "time_to_rest_s": r.time,
                         "steps": r.steps, "mesh_elements": r.elements,
                         "failure_strain": summary["failure_strain"], "element_size_m": summary["element_size"]})
            wall.append({"domain": domain, "member": k, "wall_time_s": r.wall_time})
    runs = pd.DataFrame(rows)
    if not (runs.status == "rest").all():
        bad = runs[runs.status != "rest"]
        raise RuntimeError(f"window study: shots that did not come to rest: {bad[['domain', 'member', 'status']].to_dict('records')}")
    s = window_summary(runs, float(params.confidence), float(params.goal_pct))
    t = pd.DataFrame(wall).groupby("domain").wall_time_s.sum()
    s_time = {"profile": params.profile, "element_size_m": rows[0]["element_size_m"], "realisations": members,
              "wall_window_s": t["window"], "wall_whole_s": t["whole"], "wall_ratio": t["window"] / t["whole"]}
    print(f"window {s['mean_window_m']:.4f} m, whole domain {s['mean_whole_m']:.4f} m: {s['difference_pct']:+.2f} % "
          f"({100 * s['confidence']:.0f} % interval {s['interval_low_pct']:+.2f} to {s['interval_high_pct']:+.2f} %, "
          f"{'within' if s['within_goal'] else 'not within'} +-{s['goal_pct']:g} %); "
          f"wall time {s_time['wall_ratio']:.2f} of the whole domain's", flush=True)
    write_csv(runs, outputs.runs)
    write_csv(pd.DataFrame([{"element_size_m": rows[0]["element_size_m"], **s}]), outputs.summary)
    write_csv(pd.DataFrame([s_time]), outputs.timing)
