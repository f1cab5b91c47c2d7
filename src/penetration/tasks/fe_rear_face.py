"""Task of the rear-face study: DO1 from the semi-infinite target to the experiment's block, one change at a time.

The semi-infinite target (radius 1.2 m, non-reflecting sides and bottom, as deep as the shot needs) and the block
(radius 2.031 m, depth 5.4 m, free faces) differ in four things. The study runs DO1 on a chain of targets that
changes one at a time (params.chain, in order; each target's faces and sizes are read from its shots) and gives
each change its effect on the mean depth over realisations of the erosion chaos, with Welch's interval, and the
whole difference from the first target to the last (penetration.studies.fe_results).
"""
from __future__ import annotations

import math

import pandas as pd

from ..fe.shot import TargetSpec
from ..figures.fe_rear_face import rear_face_figure
from ..pipeline.io import load_json, task, write_csv
from ..studies import fe_results as fe_studies


def _target(s):
    """A shot's target with its faces resolved by TargetSpec (records written before the faces could be set carry
    only kind, radius and depth)."""
    spec = TargetSpec(**s["target"])
    return {**s["target"], "lateral": spec.boundary("lateral"), "bottom": spec.boundary("bottom")}


def members_frame(paths):
    """One row per realisation (shot JSON paths): its scene, member, depth, status and its target's faces."""
    rows = []
    for path in paths:
        s = load_json(path)
        t = _target(s)
        final = s.get("final_velocity_m_s")
        if final is None:  # a scene's own shot: its histories lie beside it
            final = float(pd.read_csv(str(path).replace(".json", "_histories.csv")).velocity.iloc[-1])
        rows.append({"scene": s["scene"], "member": int(s.get("member", 0)), "element_size_m": s["element_size"],
                     "striking_velocity_ms": s.get("striking_velocity", s["velocity"]), "depth_m": s["depth_m"],
                     "status": s["status"], "time_s": s["time_to_rest_s"], "final_velocity_ms": final,
                     "target_kind": t["kind"], "radius_m": t["radius"], "bottom_depth_m": t["depth"] or math.nan,
                     "lateral": t["lateral"], "bottom": t["bottom"]})
    return pd.DataFrame(rows)


@task
def fe_rear_face(inputs, outputs, params):
    """The chain of targets: per target the depths over realisations, per change its effect with its interval."""
    m = fe_studies.rear_face_members(members_frame([*inputs.shots, *inputs.members]), params.chain)
    write_csv(m, outputs.members)
    measured = load_json(inputs.cal)["data"]["measured_depth"]
    t = fe_studies.rear_face_targets(m, params.chain, measured)
    write_csv(t, outputs.csv)
    e = fe_studies.rear_face_effects(m, params.chain, params.confidence)
    write_csv(e, outputs.effects)
    rear_face_figure(m, t, e, outputs.png, params.dpi)
