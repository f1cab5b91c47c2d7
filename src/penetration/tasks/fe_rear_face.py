"""Task of the rear-face study: DO1 from the semi-infinite target to the experiment's block, one change at a time.

The semi-infinite target (radius 1.2 m, non-reflecting sides and bottom, as deep as the shot needs) and the block
(radius 2.031 m, depth 5.4 m, free faces) differ in four things. The study runs DO1 on a chain of targets that
changes one at a time (params.chain, in order; each target's faces and sizes are read from its shots) and gives
each change its effect on the mean depth over realisations of the erosion chaos, with Welch's interval, and the
whole difference from the first target to the last.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..fe.shot import TargetSpec
from ..figures.fe_rear_face import rear_face_figure
from ..io import load_json, task, write_csv

# what a target's physics is made of (its kind only names defaults for these)
FACES = (("depth", "the bottom's depth"), ("bottom", "the bottom face"), ("radius", "the lateral radius"),
         ("lateral", "the lateral face"))


def _target(s):
    """A shot's target with its faces resolved by TargetSpec (records written before the faces could be set carry
    only kind, radius and depth)."""
    spec = TargetSpec(**s["target"])
    return {**s["target"], "lateral": spec.boundary("lateral"), "bottom": spec.boundary("bottom")}


def members_frame(paths):
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


def change_of(a, b):
    """What differs between two targets (rows of the members frame): the names of FACES that change."""
    diff = {"depth": not (a.bottom_depth_m == b.bottom_depth_m or (math.isnan(a.bottom_depth_m) and math.isnan(b.bottom_depth_m))),
            "bottom": a.bottom != b.bottom, "radius": not math.isclose(a.radius_m, b.radius_m),
            "lateral": a.lateral != b.lateral}
    return [name for name, _ in FACES if diff[name]]


def welch(x, y, confidence):
    """mean(y) - mean(x) and its Welch interval at the confidence."""
    from scipy import stats
    lo, hi = stats.ttest_ind(y, x, equal_var=False).confidence_interval(confidence)
    return float(y.mean() - x.mean()), float(lo), float(hi)


@task
def fe_rear_face(inputs, outputs, params):
    """The chain of targets: per target the depths over realisations, per change its effect with its interval."""
    m = members_frame([*inputs.shots, *inputs.members])
    if m.element_size_m.nunique() != 1:
        raise ValueError(f"rear-face realisations at element sizes {sorted(m.element_size_m.unique())}; allowed: one mesh")
    chain = list(params.chain)
    if set(m.scene) != set(chain):
        raise ValueError(f"rear-face realisations of scenes {sorted(set(m.scene))}; allowed: the chain {chain}")
    m = m.assign(order=m.scene.map(chain.index)).sort_values(["order", "member"]).drop(columns="order")
    write_csv(m, outputs.members)
    measured = load_json(inputs.cal)["data"]["measured_depth"]
    targets, depth = [], {}
    for k, scene in enumerate(chain):
        g = m[m.scene == scene]
        x = depth[scene] = g.depth_m.to_numpy()
        first = g.iloc[0]
        bottom = first.bottom_depth_m
        targets.append({"step": k, "scene": scene, "target_kind": first.target_kind, "radius_m": first.radius_m,
                        "bottom_depth_m": bottom, "lateral": first.lateral, "bottom": first.bottom,
                        "element_size_m": first.element_size_m, "realisations": x.size, "mean_m": x.mean(),
                        "std_m": x.std(ddof=1), "min_m": x.min(), "max_m": x.max(),
                        "least_distance_to_bottom_m": bottom - x.max() if not math.isnan(bottom) else math.nan,
                        "at_rest": int((g.status == "rest").sum()), "perforated": int((g.status == "perforated").sum()),
                        "moving_at_end": int((g.status == "end_time").sum()), "measured_depth_m": measured})
    t = pd.DataFrame(targets)
    write_csv(t, outputs.csv)
    effects = []
    pairs = [(chain[k - 1], chain[k]) for k in range(1, len(chain))] + [(chain[0], chain[-1])]
    for a, b in pairs:
        ra, rb = (m[m.scene == s].iloc[0] for s in (a, b))
        changed = change_of(ra, rb)
        d, lo, hi = welch(depth[a], depth[b], params.confidence)
        effects.append({"from_scene": a, "to_scene": b, "changes": " + ".join(dict(FACES)[c] for c in changed),
                        "single_change": len(changed) == 1, "effect_m": d, "interval_low_m": lo, "interval_high_m": hi,
                        "confidence": params.confidence, "zero_inside_interval": bool(lo <= 0 <= hi)})
    e = pd.DataFrame(effects)
    bad = e[~e.single_change].iloc[:-1]
    if len(bad):
        raise ValueError(f"rear-face chain {chain}: steps {list(zip(bad.from_scene, bad.to_scene))} change "
                         f"{list(bad.changes)}; allowed: one change a step")
    write_csv(e, outputs.effects)
    rear_face_figure(m, t, e, outputs.png, params.dpi)
