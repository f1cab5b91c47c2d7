"""The FE level's result tables and its statistical studies, as pure functions of tables.

Inputs are the per-shot summaries, per-mesh Table 3 files and DO1 calibrations the tasks read (as pandas frames,
dicts or arrays); outputs are frames and dicts. Nothing here reads or writes a file or draws.

- Table 3 at the FE level: each depth against the paper's simulated one (goal: within DEPTH_GOAL), the nose
  contrasts (depth ratios; goal: within CONTRAST_GOAL of the paper's ratio).
- Intervals: the mean of a sample with Student's t, the difference of two means with Welch's (``stats``), both at a
  two-sided confidence.
- Ensembles (realisations of the erosion chaos on one mesh) and bands (meshes of nearly one size, each calibrated on
  DO1): mean, spread and interval of each depth and contrast. Their spread is scatter, not discretisation error.
- Convergence: each contrast against the element size, the limit at h = 0 by ``mesh_convergence.size_regression``.
- The rear face (a chain of targets, one change a step) and the moving window (window against whole domain): the
  difference of mean depths with Welch's interval.
- DO1 as a test of the level calibrated on other shots: its realisations per target, the measured depth's excess
  over their mean, and each target's effect against the first.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .mesh_convergence import size_regression
from .stats import t_interval, welch

MM = 1e-3
DEPTH_GOAL = 0.05     # |FE depth / paper's simulated depth - 1|
CONTRAST_GOAL = 0.02  # |FE ratio - paper's ratio| (2 points)
# the nose contrasts of Table 3: name -> (numerator nose, denominator nose)
CONTRASTS = {"DO/CRH 4.5": ("double_ogive", "crh45"), "CRH 4.5/CRH 3": ("crh45", "crh3"),
             "DO/CRH 3": ("double_ogive", "crh3")}
# the contrasts over Fig 15's sweep, in the order they are drawn
SWEEP_CONTRASTS = (("DO/CRH 4.5", "double_ogive", "crh45"), ("DO/CRH 3", "double_ogive", "crh3"),
                   ("CRH 4.5/CRH 3", "crh45", "crh3"), ("minimum N*/DO", "minimum_nstar", "double_ogive"))


def depth_within_goal(depth, paper):
    return abs(depth / paper - 1) <= DEPTH_GOAL


def contrast_within_goal(ratio, paper):
    return abs(ratio - paper) <= CONTRAST_GOAL


# ------------------------------------------------------------------------------------------------ Table 3
def table3_rows(shots: pd.DataFrame, paper: dict, calibrated: set, calibration_velocity: float) -> pd.DataFrame:
    """Table 3 at the FE level, one row per shot (frame of shot summaries): the depth against the paper's simulated
    one (``paper``: (velocity, nose) -> m), the goal flag, the shot's distance from the DO1 calibration (its nose in
    ``calibrated``; its velocity minus ``calibration_velocity``) and the shot's audit."""
    rows = []
    for _, s in shots.sort_values(["velocity", "nose"]).iterrows():
        v = int(round(s.velocity))
        p = paper[(v, s.nose)]
        rows.append({"velocity_ms": v, "nose": s.nose, "fe_m": s.depth_m, "paper_sim_m": p,
                     "rel_dev_fe_vs_paper_sim_pct": 100 * (s.depth_m / p - 1),
                     "within_5pct_goal": depth_within_goal(s.depth_m, p),
                     "calibration_nose": s.nose in calibrated, "velocity_minus_calibration_ms": v - calibration_velocity,
                     "time_to_rest_s": s.time_to_rest_s,
                     "peak_deceleration_m_s2": s.peak_deceleration_m_s2, "eroded_mass_kg": s.eroded_mass_kg,
                     "tunnel_eroded_share": s.tunnel_eroded_share, "energy_error_max": s.energy_error_max,
                     "hourglass_over_internal": s.hourglass_over_internal, "element_steps": s.element_steps,
                     "failure_strain": s.failure_strain, "element_size_m": s.element_size})
    return pd.DataFrame(rows)


def table3_ratios(table: pd.DataFrame) -> pd.DataFrame:
    """The nose contrasts of Table 3 (rows of ``table3_rows``) per velocity: FE and paper ratios, the goal flag,
    the gains in metres."""
    ratios = []
    for v, g in table.groupby("velocity_ms"):
        d = g.set_index("nose")
        for name, (num, den) in CONTRASTS.items():
            ours, paper = d.fe_m[num] / d.fe_m[den], d.paper_sim_m[num] / d.paper_sim_m[den]
            ratios.append({"velocity_ms": v, "contrast": name, "fe_ratio": ours, "paper_sim_ratio": paper,
                           "difference_points": 100 * (ours - paper), "within_2_points_goal": contrast_within_goal(ours, paper),
                           "fe_gain_m": d.fe_m[num] - d.fe_m[den], "paper_sim_gain_m": d.paper_sim_m[num] - d.paper_sim_m[den]})
    return pd.DataFrame(ratios)


def paper_sweep_contrasts(paper: dict) -> pd.DataFrame:
    """The paper's simulated depth ratio and gain of each pair of SWEEP_CONTRASTS whose noses Table 3 has
    (``paper``: (velocity, nose) -> m), per velocity."""
    velocities, noses = sorted({v for v, _ in paper}), {n for _, n in paper}
    rows = [{"contrast": name, "velocity": v, "ratio": paper[(v, num)] / paper[(v, den)],
             "gain_m": paper[(v, num)] - paper[(v, den)]}
            for name, num, den in SWEEP_CONTRASTS if {num, den} <= noses for v in velocities]
    return pd.DataFrame(rows)


def sweep_contrasts(shots: pd.DataFrame) -> pd.DataFrame:
    """Depth ratio and gain of each pair of SWEEP_CONTRASTS at each velocity of a sweep (frame of shot summaries)."""
    d = shots.pivot_table(index="velocity", columns="nose", values="depth_m")
    rows = []
    for name, num, den in SWEEP_CONTRASTS:
        for v, row in d.iterrows():
            rows.append({"contrast": name, "velocity": v, "ratio": row[num] / row[den], "gain_m": row[num] - row[den]})
    return pd.DataFrame(rows)


# ------------------------------------------------------------------------------------------- mesh studies
def mesh_study_rows(calibrations) -> pd.DataFrame:
    """One row per DO1 calibration (dicts of the calibration records), coarsest mesh first: fs, the depth and peak
    deceleration of the run nearest the measured depth, the wall times."""
    rows = []
    for c in calibrations:
        best = min(c["runs"], key=lambda r: abs(r["depth_m"] - c["data"]["measured_depth"]))
        rows.append({"element_size_m": c["element_size"], "elements_across_radius": c["elements_across_radius"],
                     "failure_strain": c["fs"], "depth_m": best["depth_m"], "residual_m": c["residual_m"],
                     "peak_deceleration_m_s2": best.get("peak_deceleration_m_s2", math.nan),
                     "wall_time_per_run_s": best["wall_time_s"], "runs": len(c["runs"]),
                     "calibration_wall_time_s": c["wall_time_s"], "converged": c["converged"]})
    return pd.DataFrame(rows).sort_values("element_size_m", ascending=False)


def check_one_mesh(cal: dict, table: pd.DataFrame, table_name, cal_name):
    """Raise ValueError unless every cell of a mesh's Table 3 was computed at its calibration's element size."""
    if not all(math.isclose(h, cal["element_size"], rel_tol=1e-9) for h in table.element_size_m):
        raise ValueError(f"{table_name}: element sizes {sorted(set(table.element_size_m))}; allowed: the calibration's "
                         f"{cal['element_size']} m ({cal_name})")


def table3_contrasts(ratios: pd.DataFrame) -> pd.DataFrame:
    """The rows of a Table 3 ratios file that are CONTRASTS."""
    return ratios[ratios.contrast.isin(list(CONTRASTS))]


def convergence_rows(meshes) -> pd.DataFrame:
    """The contrasts of Table 3 at several meshes: ``meshes`` lists (calibration dict, Table 3 frame, contrasts
    frame) per mesh; one row per mesh, velocity and contrast with both depths."""
    rows = []
    for cal, t3, ratios in meshes:
        depth = {(int(r.velocity_ms), r.nose): r.fe_m for r in t3.itertuples()}
        for r in ratios.itertuples():
            num, den = CONTRASTS[r.contrast]
            v = int(r.velocity_ms)
            rows.append({"elements_across_radius": cal["elements_across_radius"], "element_size_m": cal["element_size"],
                         "failure_strain": cal["fs"], "velocity_ms": v, "contrast": r.contrast, "fe_ratio": r.fe_ratio,
                         "paper_sim_ratio": r.paper_sim_ratio, "difference_points": 100 * (r.fe_ratio - r.paper_sim_ratio),
                         "depth_num_m": depth[(v, num)], "depth_den_m": depth[(v, den)]})
    return pd.DataFrame(rows).sort_values(["contrast", "velocity_ms", "elements_across_radius"])


# ---------------------------------------------------------------------------------------------- ensembles
def ensemble_tables(shots, paper_depth: dict, paper_ratio: dict, confidence):
    """Realisations of the erosion chaos on one mesh: (depths, contrasts, member ratios).

    ``shots``: summaries (dicts with nose, velocity, depth_m, element_size and member, absent for member 0);
    ``paper_depth``: (nose, velocity) -> m; ``paper_ratio``: (contrast, velocity) -> ratio. Ratios pair the
    members of equal number; the interval of a mean is Student's t over the realisations.
    """
    depth, sizes = {}, set()
    for s in shots:
        sizes.add(s["element_size"])
        depth.setdefault((s["nose"], int(round(s["velocity"]))), {})[int(s.get("member", 0))] = s["depth_m"]
    if len(sizes) != 1:
        raise ValueError(f"ensemble members at element sizes {sorted(sizes)}; allowed: one mesh")
    drows = []
    for (nose, v), d in sorted(depth.items()):
        x = np.array([d[k] for k in sorted(d)])
        drows.append({"velocity_ms": v, "nose": nose, "realisations": x.size, "depth_member0_m": d[0], "mean_m": x.mean(),
                      "std_m": x.std(ddof=1), "rel_std_pct": 100 * x.std(ddof=1) / x.mean(), "min_m": x.min(),
                      "max_m": x.max(), "paper_sim_m": paper_depth[(nose, v)]})
    rows, members = [], []
    for name, (num, den) in CONTRASTS.items():
        for v in sorted({v for _, v in depth}):
            a, b = depth[(num, v)], depth[(den, v)]
            pairs = [k for k in sorted(a) if k in b]
            x = np.array([a[k] / b[k] for k in pairs])
            members += [{"contrast": name, "velocity_ms": v, "member": k, "ratio": r} for k, r in zip(pairs, x)]
            lo, hi = t_interval(x, confidence)
            p = paper_ratio[(name, v)]
            rows.append({"contrast": name, "velocity_ms": v, "element_size_m": min(sizes), "realisations": x.size,
                         "ratio_member0": x[0],
                         "mean_ratio": x.mean(), "std_ratio": x.std(ddof=1), "min_ratio": x.min(), "max_ratio": x.max(),
                         "interval_low": float(lo), "interval_high": float(hi), "confidence": confidence,
                         "paper_sim_ratio": p, "mean_minus_paper_points": 100 * (x.mean() - p),
                         "paper_inside_interval": bool(lo <= p <= hi)})
    return pd.DataFrame(drows), pd.DataFrame(rows), pd.DataFrame(members)


# -------------------------------------------------------------------------------------------------- bands
def band_tables(meshes, band, confidence):
    """One band of meshes (centre first; ``meshes`` as in ``convergence_rows``): (per mesh and contrast, per cell
    over the meshes, per contrast over the meshes), each mean with its Student-t interval and the goal flags."""
    rows_m, cells, ratios = [], {}, {}
    centre = None
    for cal, t3, mesh_ratios in meshes:
        across = cal["elements_across_radius"]
        centre = across if centre is None else centre
        for r in t3.itertuples():
            cells.setdefault((int(r.velocity_ms), r.nose), {"paper": r.paper_sim_m, "x": []})["x"].append(r.fe_m)
        for r in mesh_ratios.itertuples():
            v = int(r.velocity_ms)
            ratios.setdefault((r.contrast, v), {"paper": r.paper_sim_ratio, "x": []})["x"].append(r.fe_ratio)
            rows_m.append({"band": band, "centre_elements_across": centre, "elements_across_radius": across,
                           "element_size_m": cal["element_size"], "failure_strain": cal["fs"],
                           "calibration_residual_m": cal["residual_m"], "velocity_ms": v, "contrast": r.contrast,
                           "fe_ratio": r.fe_ratio, "paper_sim_ratio": r.paper_sim_ratio,
                           "difference_points": 100 * (r.fe_ratio - r.paper_sim_ratio),
                           "within_2_points_goal": contrast_within_goal(r.fe_ratio, r.paper_sim_ratio)})
    m = pd.DataFrame(rows_m)
    n = m.elements_across_radius.nunique()
    if n < 2:
        raise ValueError(f"band {band}: {n} mesh; allowed: at least 2")
    fs = m.drop_duplicates("elements_across_radius").failure_strain.to_numpy()
    head = {"band": band, "centre_elements_across": centre, "meshes": n}
    return m, _band_cells(cells, head, confidence), _band_contrasts(ratios, head, fs, confidence)


def _band_cells(cells, head, confidence):
    rows = []
    for (v, nose), c in sorted(cells.items()):
        x, p = np.array(c["x"]), c["paper"]
        lo, hi = t_interval(x, confidence)
        rows.append({**head, "velocity_ms": v, "nose": nose, "mean_m": x.mean(), "std_m": x.std(ddof=1),
                     "rel_std_pct": 100 * x.std(ddof=1) / x.mean(), "min_m": x.min(), "max_m": x.max(),
                     "interval_low_m": lo, "interval_high_m": hi, "confidence": confidence, "paper_sim_m": p,
                     "mean_rel_dev_pct": 100 * (x.mean() / p - 1), "within_5pct_goal": depth_within_goal(x.mean(), p),
                     "paper_inside_interval": bool(lo <= p <= hi)})
    return pd.DataFrame(rows)


def _band_contrasts(ratios, head, fs, confidence):
    rows = []
    for name in CONTRASTS:
        for v in sorted(v for c, v in ratios if c == name):
            x, p = np.array(ratios[(name, v)]["x"]), ratios[(name, v)]["paper"]
            lo, hi = t_interval(x, confidence)
            rows.append({**head, "contrast": name, "velocity_ms": v, "mean_ratio": x.mean(), "std_ratio": x.std(ddof=1),
                         "min_ratio": x.min(), "max_ratio": x.max(), "interval_low": lo, "interval_high": hi,
                         "confidence": confidence, "paper_sim_ratio": p, "mean_minus_paper_points": 100 * (x.mean() - p),
                         "within_2_points_goal": contrast_within_goal(x.mean(), p), "paper_inside_interval": bool(lo <= p <= hi),
                         "failure_strain_min": fs.min(), "failure_strain_max": fs.max()})
    return pd.DataFrame(rows)


def bands_tables(meshes, bands, confidence):
    """Every band: ``meshes`` lists the bands' meshes in order, ``bands`` (centre, number of meshes) per band.
    Returns the three frames of ``band_tables`` over all bands (the per-mesh one sorted by band centre)."""
    parts, start = [], 0
    for band, n in bands:
        parts.append(band_tables(meshes[start:start + n], band, confidence))
        start += n
    if start != len(meshes):
        raise ValueError(f"{len(meshes)} meshes given; the bands {bands} name {start}")
    m = pd.concat([p[0] for p in parts]).sort_values(["centre_elements_across", "contrast", "velocity_ms",
                                                      "elements_across_radius"])
    return m, pd.concat([p[1] for p in parts]), pd.concat([p[2] for p in parts])


# ------------------------------------------------------------------------------------ limit at zero size
def _monotone(x):
    d = np.diff(np.asarray(x, float))
    return bool(np.all(d >= 0) or np.all(d <= 0))


def extrapolation_rows(meshes, singles, confidence):
    """One row per (contrast, velocity): the regression over ``meshes`` (one row per mesh, cell and contrast:
    element_size_m, fe_ratio, paper_sim_ratio) and the series of ``singles`` (the same columns, ordered by
    elements_across_radius)."""
    rows = []
    for (name, v), g in meshes.groupby(["contrast", "velocity_ms"], sort=True):
        if g.element_size_m.duplicated().any():
            raise ValueError(f"{name} at {v} m/s: two results at one element size; allowed: one per mesh")
        fit = size_regression(g.element_size_m.to_numpy(), g.fe_ratio.to_numpy(), confidence)
        paper = float(g.paper_sim_ratio.iloc[0])
        s = singles[(singles.contrast == name) & (singles.velocity_ms == v)].sort_values("elements_across_radius")
        rows.append({"contrast": name, "velocity_ms": int(v), "meshes": fit.n,
                     "element_size_min_m": fit.h_min, "element_size_max_m": fit.h_max, "reach": fit.reach,
                     "ratio_at_zero_size": fit.f0, "interval_low": fit.f0_low, "interval_high": fit.f0_high,
                     "confidence": fit.confidence, "stderr": fit.f0_stderr,
                     "slope_points_per_mm": 100 * fit.slope * MM, "slope_p": fit.slope_p,
                     "scatter_points": 100 * fit.scatter, "mean_over_meshes": fit.mean, "paper_sim_ratio": paper,
                     "zero_size_minus_paper_points": 100 * (fit.f0 - paper), "paper_inside_interval": fit.inside(paper),
                     "interval_half_width_points": 50 * (fit.f0_high - fit.f0_low),
                     "single_meshes": len(s), "single_meshes_monotone": _monotone(s.fe_ratio)})
    return pd.DataFrame(rows)


def depth_rows(tables, confidence):
    """One row per Table 3 cell (velocity, nose): the FE depth over the meshes (``tables``: each mesh's Table 3
    frame) fitted against the element size and extrapolated to zero, with its interval."""
    t = pd.concat(tables, ignore_index=True)
    rows = []
    for (v, nose), g in t.groupby(["velocity_ms", "nose"], sort=True):
        fit = size_regression(g.element_size_m.to_numpy(), g.fe_m.to_numpy(), confidence)
        paper = float(g.paper_sim_m.iloc[0])
        rows.append({"velocity_ms": int(v), "nose": nose, "meshes": fit.n, "element_size_min_m": fit.h_min,
                     "element_size_max_m": fit.h_max, "depth_at_zero_size_m": fit.f0, "interval_low_m": fit.f0_low,
                     "interval_high_m": fit.f0_high, "confidence": fit.confidence, "scatter_m": fit.scatter,
                     "mean_over_meshes_m": fit.mean, "paper_sim_m": paper,
                     "zero_size_rel_dev_pct": 100 * (fit.f0 / paper - 1), "paper_inside_interval": fit.inside(paper)})
    return pd.DataFrame(rows)


# ----------------------------------------------------------------------------------------------- rear face
# what a target's physics is made of (its kind only names defaults for these)
FACES = (("depth", "the bottom's depth"), ("bottom", "the bottom face"), ("radius", "the lateral radius"),
         ("lateral", "the lateral face"))


def change_of(a, b):
    """What differs between two targets (rows of the members frame): the names of FACES that change."""
    diff = {"depth": not (a.bottom_depth_m == b.bottom_depth_m or (math.isnan(a.bottom_depth_m) and math.isnan(b.bottom_depth_m))),
            "bottom": a.bottom != b.bottom, "radius": not math.isclose(a.radius_m, b.radius_m),
            "lateral": a.lateral != b.lateral}
    return [name for name, _ in FACES if diff[name]]


def rear_face_members(m: pd.DataFrame, chain) -> pd.DataFrame:
    """The realisations (one row each: scene, member, depth_m, status, element_size_m and the target's faces) in the
    chain's order, checked to be of one mesh and of the chain's scenes."""
    if m.element_size_m.nunique() != 1:
        raise ValueError(f"rear-face realisations at element sizes {sorted(m.element_size_m.unique())}; allowed: one mesh")
    chain = list(chain)
    if set(m.scene) != set(chain):
        raise ValueError(f"rear-face realisations of scenes {sorted(set(m.scene))}; allowed: the chain {chain}")
    return in_order(m, "scene", chain)


def in_order(m: pd.DataFrame, column, order) -> pd.DataFrame:
    """The realisations ``m`` sorted by ``column`` in the order of ``order`` (which holds every value of it), then by
    member."""
    order = list(order)
    return m.assign(_order=m[column].map(order.index)).sort_values(["_order", "member"]).drop(columns="_order")


def outcomes(status: pd.Series) -> dict:
    """How many realisations came to rest, perforated the target or still moved at the run's end (``status``: each
    one's run status)."""
    return {"at_rest": int((status == "rest").sum()), "perforated": int((status == "perforated").sum()),
            "moving_at_end": int((status == "end_time").sum())}


def rear_face_targets(m: pd.DataFrame, chain, measured) -> pd.DataFrame:
    """Per target of the chain (``m``: rear_face_members): its faces, the depths over its realisations, how many came
    to rest, perforated or still moved, and the least distance of a tip to the bottom."""
    targets = []
    for k, scene in enumerate(chain):
        g = m[m.scene == scene]
        x = g.depth_m.to_numpy()
        first = g.iloc[0]
        bottom = first.bottom_depth_m
        targets.append({"step": k, "scene": scene, "target_kind": first.target_kind, "radius_m": first.radius_m,
                        "bottom_depth_m": bottom, "lateral": first.lateral, "bottom": first.bottom,
                        "element_size_m": first.element_size_m, "realisations": x.size, "mean_m": x.mean(),
                        "std_m": x.std(ddof=1), "min_m": x.min(), "max_m": x.max(),
                        "least_distance_to_bottom_m": bottom - x.max() if not math.isnan(bottom) else math.nan,
                        **outcomes(g.status), "measured_depth_m": measured})
    return pd.DataFrame(targets)


def rear_face_effects(m: pd.DataFrame, chain, confidence) -> pd.DataFrame:
    """Each step of the chain and the whole chain (first to last target): what changes and its effect on the mean
    depth with Welch's interval; a step that changes more than one thing is refused."""
    chain = list(chain)
    effects = []
    pairs = [(chain[k - 1], chain[k]) for k in range(1, len(chain))] + [(chain[0], chain[-1])]
    for a, b in pairs:
        ra, rb = (m[m.scene == s].iloc[0] for s in (a, b))
        changed = change_of(ra, rb)
        d, lo, hi = welch(m[m.scene == a].depth_m.to_numpy(), m[m.scene == b].depth_m.to_numpy(), confidence)
        effects.append({"from_scene": a, "to_scene": b, "changes": " + ".join(dict(FACES)[c] for c in changed),
                        "single_change": len(changed) == 1, "effect_m": d, "interval_low_m": lo, "interval_high_m": hi,
                        "confidence": confidence, "zero_inside_interval": bool(lo <= 0 <= hi)})
    e = pd.DataFrame(effects)
    steps = e.iloc[:-1]  # the last row is the whole chain
    bad = steps[~steps.single_change]
    if len(bad):
        raise ValueError(f"rear-face chain {chain}: steps {list(zip(bad.from_scene, bad.to_scene))} change "
                         f"{list(bad.changes)}; allowed: one change a step")
    return e


# ---------------------------------------------------------------------------------------------- the window
def window_summary(runs: pd.DataFrame, confidence: float, goal_pct: float) -> dict:
    """Mean depths of the window's and the whole domain's realisations (``runs``: domain, depth_m), their relative
    difference (window - whole, per cent of whole) with its Welch t interval, and whether that interval lies within
    +-goal_pct (an equivalence test)."""
    w = runs.loc[runs.domain == "window", "depth_m"].to_numpy()
    f = runs.loc[runs.domain == "whole", "depth_m"].to_numpy()
    if w.size < 2 or f.size < 2:
        raise ValueError(f"window study: {w.size} window and {f.size} whole-domain realisations; allowed: >= 2 each")
    _, lo, hi = welch(f, w, confidence)
    mean_f = f.mean()
    diff, lo_pct, hi_pct = 100 * (w.mean() - mean_f) / mean_f, 100 * lo / mean_f, 100 * hi / mean_f
    return {"realisations": int(w.size), "mean_window_m": w.mean(), "mean_whole_m": mean_f,
            "std_window_m": w.std(ddof=1), "std_whole_m": f.std(ddof=1), "difference_pct": diff,
            "interval_low_pct": lo_pct, "interval_high_pct": hi_pct, "confidence": confidence,
            "goal_pct": goal_pct, "within_goal": bool(-goal_pct <= lo_pct and hi_pct <= goal_pct)}


def do1_test_tables(members: pd.DataFrame, targets, measured, confidence):
    """DO1 as a test of the fe level over realisations of the erosion chaos in each of ``targets`` (in order, the first
    the reference; ``members``: one row per realisation with target, member, depth_m and status): per target the
    depths' mean, spread and Student-t interval, how many came to rest, perforated or still moved at the run's end,
    and the measured depth's excess over the mean with the interval's bounds carried over (measured / depth - 1: a
    positive excess, the measured shot went deeper); on every target after the first, its effect on the mean depth
    against the first with Welch's interval."""
    targets = list(targets)
    found = set(members.target)
    if not targets or found != set(targets):
        raise ValueError(f"do1_test_fe.targets: {targets}; allowed: the records' targets {sorted(found)}, each once")
    first = members[members.target == targets[0]].depth_m.to_numpy()
    rows = []
    for target in targets:
        g = members[members.target == target]
        x = g.depth_m.to_numpy()
        if x.size < 2:
            raise ValueError(f"do1_test_fe.members: {x.size} realisation of target {target}; allowed: >= 2 (an interval)")
        lo, hi = t_interval(x, confidence)
        d, dlo, dhi = welch(first, x, confidence) if target != targets[0] else (math.nan,) * 3
        rows.append({"target": target, "realisations": x.size, "mean_m": x.mean(), "std_m": x.std(ddof=1),
                     "min_m": x.min(), "max_m": x.max(), "mean_low_m": lo, "mean_high_m": hi,
                     **outcomes(g.status), "measured_depth_m": measured, "excess": measured / x.mean() - 1,
                     "excess_low": measured / hi - 1, "excess_high": measured / lo - 1,
                     "effect_vs_first_m": d, "effect_low_m": dlo, "effect_high_m": dhi, "confidence": confidence})
    return pd.DataFrame(rows)
