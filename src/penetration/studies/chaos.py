"""Realisations of the FE chaos, as pure functions of tables: a grid study whose error model holds the run-to-run
spread, and the contrasts of scenes that change one unstated input.

An FE depth is chaotic: a change of 1e-9 in the striking velocity moves it by tenths of a per cent. Each cell (a
scene at a mesh, one nose at one velocity) therefore has several realisations (``fe_realisations.members``); per cell
the realisations' mean, standard deviation and standard error (``cell_rows``). A nose contrast is the ratio of two
cells' means, its standard error by propagation of the two independent errors.

Over the meshes (``chaos_rows``), per depth and contrast:

1. the weighted least-squares line of the means against the element size h (first order, the weights the inverse
   squared standard errors of the means, from the chaos pooled over the meshes): its value at h = 0 and standard error, inflated by sqrt(chi2/dof) where the means
   scatter about the line beyond their chaos (the line then does not hold the data: ``fit_holds`` false where
   chi2/dof's upper tail probability under F(dof, the pooled chaos's dof) is below FIT_P_MIN: the weights' s.d. is
   itself estimated); the coverage factor stays Student's t on the pooled dof, conservative where the inflation
   applies;
2. each step between successive meshes against its noise (the standard error of the difference of the two means):
   a step is a mesh effect only beyond ``noise_sigmas`` of it. Only where the two steps of the finest triple are both
   mesh effects (and its meshes refined by one ratio) are the observed order, Richardson's value and Roache's GCI of
   that triple taken, with the safety factor 1.25 where it is monotone and its order in the asymptotic range, else 3
   with the order set to 1 (``gci_order``);
3. the estimate: the line's value at zero size, with U = t x its standard error (95 %, Student's t on the degrees of
   freedom of the chaos pooled over the meshes: each cell's standard error is the pooled s.d. over its root number of
   realisations, a few realisations giving a poor s.d. each), combined in quadrature
   with its distance from Richardson's value where the finest triple is asymptotic (the order assumed against the
   order observed); the GCI is reported beside it as the finest mesh's own uncertainty; ``within_goal`` against the uncertainty aimed at, and where it is missed the next mesh (1.25 times finer)
   and what it would cost at the measured cost growth.

Nothing here reads or writes a file or draws.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
from scipy import stats

from .fe_results import CONTRASTS
from .mesh_convergence import MONOTONE, grid_refinement
from .stats import t_quantile

FIT_P_MIN = 0.01        # the line holds the means unless the F test's upper tail probability falls below this
COVERAGE = 2.0          # a change beyond COVERAGE standard errors is resolved
CONFIDENCE = 0.95       # U: the Student-t interval of the line's value at zero size on the pooled chaos's dof
REFINE = 1.25           # the next mesh: this many times finer than the finest
SAFETY_MONOTONE, SAFETY_OTHER = 1.25, 3.0

MASSES = ("ejected_mass_kg", "crater_debris_mass_kg", "wall_debris_mass_kg")   # concrete taken out of the stress field
SHOT_COLUMNS = ("depth_m", "status", "wall_time_s", "ejected_mass_kg", "crater_debris_mass_kg", "wall_debris_mass_kg",
                "friction", "failure_strain")


def shot_rows(pieces, across=None) -> pd.DataFrame:
    """One row per realised shot. ``pieces``: the pieces' records ({"piece", "member", "shots"}); ``across``: profile
    -> elements across the shank radius (None: not recorded)."""
    rows = []
    for p in pieces:
        for s in p["shots"]:
            row = {"scene": s["scene"], "profile": s["profile"], "element_size_m": s["element_size"],
                   "nose": s["nose"], "velocity_ms": float(s["velocity"]), "member": int(p["member"]),
                   "velocity_factor": float(s.get("velocity_factor", 1.0)),
                   **{k: s.get(k, 0.0 if k == "friction" else math.nan) for k in SHOT_COLUMNS}}
            if across is not None:
                if s["profile"] not in across:
                    raise ValueError(f"shot {s['nose']} at {s['velocity']} m/s: profile {s['profile']} is not one of "
                                     f"the study's {sorted(across)}")
                row["elements_across"] = float(across[s["profile"]])
            rows.append(row)
    out = pd.DataFrame(rows)
    dup = out.duplicated(["scene", "profile", "nose", "velocity_ms", "member"])
    if dup.any():
        raise ValueError(f"realisations given twice: {out[dup][['scene', 'profile', 'nose', 'velocity_ms', 'member']].to_dict('records')}")
    return out.sort_values(["scene", "velocity_ms", "nose", "element_size_m", "member"],
                           ascending=[True, True, True, False, True], ignore_index=True)


def _depth_cell(d):
    ok = d[d.status == "rest"].depth_m.to_numpy(float)
    n = ok.size
    mean = float(ok.mean()) if n else math.nan
    sd = float(ok.std(ddof=1)) if n > 1 else math.nan
    return n, len(d), mean, sd, sd / math.sqrt(n) if n > 1 else math.nan


def cell_rows(shots: pd.DataFrame, keys=("scene", "profile", "element_size_m", "velocity_ms")) -> pd.DataFrame:
    """Per cell (``keys``) each nose's depth and each contrast of CONTRASTS: realisations (at rest / run), mean,
    standard deviation of one realisation and standard error of the mean (a contrast's by propagation), the depth's
    relative standard deviation in per cent and the ejected, crater and wall-debris mass (kg, mean; a contrast's the
    mean of its two noses')."""
    rows = []
    for key, g in shots.groupby(list(keys), sort=False):
        base = dict(zip(keys, key))
        if "elements_across" in g:
            base["elements_across"] = float(g.elements_across.iloc[0])
        depth, mass = {}, {}
        for nose, d in g.groupby("nose", sort=False):
            n, runs, mean, sd, se = _depth_cell(d)
            depth[nose] = (mean, sd, se, n, runs)
            mass[nose] = {k: d[k].mean() for k in MASSES}
            rows.append({**base, "quantity": nose, "kind": "depth", "realisations": n, "runs": runs, "mean": mean,
                         "sd": sd, "se": se, "sd_pct": 100 * sd / mean, **mass[nose],
                         "wall_time_s": d.wall_time_s.mean()})
        for name, (num, den) in CONTRASTS.items():
            if num in depth and den in depth:
                (ma, sa, ea, na, ra), (mb, sb, eb, nb, rb) = depth[num], depth[den]
                c = ma / mb
                rows.append({**base, "quantity": name, "kind": "contrast", "realisations": min(na, nb),
                             "runs": min(ra, rb), "mean": c, "sd": c * math.hypot(sa / ma, sb / mb),
                             "se": c * math.hypot(ea / ma, eb / mb), "sd_pct": math.nan,
                             **{k: 0.5 * (mass[num][k] + mass[den][k]) for k in MASSES}})
    return pd.DataFrame(rows)


def weighted_line(h, f, se):
    """Weighted least squares of f = f0 + a h (weights 1/se^2): (f0, its standard error, a, its standard error,
    chi2, dof), the standard errors inflated by sqrt(chi2/dof) where that exceeds 1."""
    h, f, se = (np.asarray(x, float) for x in (h, f, se))
    w = 1.0 / se ** 2
    X = np.column_stack([np.ones_like(h), h])
    cov = np.linalg.inv(X.T @ (w[:, None] * X))
    beta = cov @ X.T @ (w * f)
    chi2 = float(np.sum(w * (f - X @ beta) ** 2))
    dof = h.size - 2
    scale = math.sqrt(max(1.0, chi2 / dof)) if dof > 0 else 1.0
    return (float(beta[0]), scale * math.sqrt(cov[0, 0]), float(beta[1]), scale * math.sqrt(cov[1, 1]), chi2, dof)


def _refinement(h, f, se, sigmas):
    """The steps of the sequence (coarse first) against their noise, and the finest triple's grid refinement where
    both its steps are mesh effects: (steps text, steps resolved, observed order, order of the GCI, Richardson, GCI,
    safety, status). The triple's grid refinement only (its three meshes refined by one ratio; the steps before it
    are not checked against their noise); not monotone or not asymptotic: the GCI with Fs 3 and order 1."""
    steps = np.diff(f)
    noise = np.hypot(se[1:], se[:-1])
    resolved = np.abs(steps) > sigmas * noise
    text = " ".join(f"{s:+.4f}{'*' if r else ''}" for s, r in zip(steps, resolved))
    nan = math.nan
    if f.size < 3 or not (resolved[-1] and resolved[-2]):
        return text, int(resolved.sum()), nan, nan, nan, nan, nan, "steps within noise"
    r1, r2 = h[-3] / h[-2], h[-2] / h[-1]
    if abs(r1 / r2 - 1.0) > 1e-6:
        return text, int(resolved.sum()), nan, nan, nan, nan, nan, "finest triple not refined by one ratio"
    g = grid_refinement(f[-3:], r2)
    if g.status == MONOTONE:
        return text, int(resolved.sum()), g.order, g.order, g.extrapolated, g.gci_fine, SAFETY_MONOTONE, "asymptotic"
    gci = SAFETY_OTHER * abs(f[-1] - f[-2]) / (r2 - 1.0)
    return text, int(resolved.sum()), g.order, 1.0, nan, gci, SAFETY_OTHER, g.status


def chaos_rows(cells: pd.DataFrame, paper: dict, goals: dict, sigmas: float, cost: pd.DataFrame | None = None,
               members: int | None = None) -> pd.DataFrame:
    """Per depth and contrast (and velocity) over the meshes of ``cells`` (one scene): the estimate at zero size with
    its uncertainty (module doc). ``paper``: (velocity, quantity) -> the paper's value, where it has one; ``goals``:
    velocity -> U aimed at for a contrast (absolute; a depth's relative); ``cost``: wall time per shot (s) against
    elements across (columns elements_across, wall_time_s, velocity_ms), for the next mesh's cost."""
    rows = []
    for (v, q), g in cells.groupby(["velocity_ms", "quantity"], sort=False):
        kind = g.kind.iloc[0]
        g = g.sort_values("element_size_m", ascending=False)
        dropped = int((~(np.isfinite(g["mean"]) & (g.realisations >= 1))).sum())
        g = g[np.isfinite(g["mean"]) & (g.realisations >= 1)]   # a cell with no realisation at rest has no mean
        key = f"{v:g}"
        if key not in goals:
            raise ValueError(f"fe_realisations.chaos.goals has no goal for {key} m/s; it has {sorted(goals)}")
        goal = float(goals[key])
        base = {"quantity": q, "kind": kind, "velocity_ms": v, "meshes": len(g), "meshes_without_mean": dropped,
                "realisations_min": int(g.realisations.min()) if len(g) else 0}
        if len(g) < 3:
            rows.append({**base, "status": "fewer than 3 meshes with a mean"})
            continue
        h, f, sd, n = (g[c].to_numpy(float) for c in ("element_size_m", "mean", "sd", "realisations"))
        # the chaos pooled over the cells with two or more realisations (a few realisations per cell give a poor s.d.
        # each): its dof sets the coverage factor and the fit's test
        many = n >= 2
        dof_pool = float(np.sum(n[many] - 1))
        sd_pool = math.sqrt(float(np.sum((n[many] - 1) * sd[many] ** 2)) / dof_pool) if dof_pool > 0 else math.nan
        if not (np.isfinite(sd_pool) and sd_pool > 1e-12 * float(np.max(np.abs(f)))):
            rows.append({**base, "sd_pooled": sd_pool, "sd_pooled_dof": dof_pool,
                         "status": "no chaos measured (fewer than two realisations, or identical ones)"})
            continue
        se = sd_pool / np.sqrt(n)
        k = t_quantile(CONFIDENCE, dof_pool)
        f0, se0, a, sea, chi2, dof = weighted_line(h, f, se)
        # chi2/dof against F(dof, dof_pool): the weights' s.d. is itself estimated from the realisations
        p_fit = float(stats.f.sf(chi2 / dof, dof, dof_pool)) if dof > 0 else math.nan
        steps, n_resolved, order, gci_order, rich, gci, safety, status = _refinement(h, f, se, sigmas)
        u_fit = k * se0
        # where the finest triple is asymptotic, the line's first order against Richardson's observed one
        u_order = abs(f0 - rich) if np.isfinite(rich) else 0.0
        u = math.hypot(u_fit, u_order)
        scale = 1.0 if kind == "contrast" else abs(f0)   # a depth's goal is relative
        fit_holds = bool(p_fit >= FIT_P_MIN) if np.isfinite(p_fit) else False
        within = bool(fit_holds and u <= goal * scale)
        row = {**base, "finest_mean": f[-1], "finest_se": se[-1], "sd_finest": float(g.sd.iloc[-1]),
               **{f"{k.removesuffix('_kg')}_finest_kg": float(g[k].iloc[-1]) if k in g else math.nan for k in MASSES},
               "element_size_finest_m": h[-1], "zero_size": f0, "zero_size_se": se0, "slope_per_m": a, "slope_se_per_m": sea,
               "slope_resolved": bool(abs(a) > sigmas * sea), "sd_pooled": sd_pool, "sd_pooled_dof": dof_pool,
               "coverage_factor": k, "chi2": chi2, "dof": dof, "fit_p": p_fit,
               "fit_holds": fit_holds, "steps": steps, "steps_resolved": n_resolved, "order": order, "gci_order": gci_order,
               "richardson": rich, "gci": gci, "gci_safety": safety, "refinement": status,
               "estimate": f0, "uncertainty": u, "uncertainty_order": u_order,
               "goal": goal * scale, "within_goal": within, "paper": paper.get((v, q), math.nan)}
        row["paper_minus_estimate"] = row["paper"] - f0
        row["paper_inside"] = bool(abs(row["paper_minus_estimate"]) <= u) if np.isfinite(row["paper"]) else None
        if kind == "contrast" and within:
            row["status"] = f"limit within the goal (+-{goal * 100:g} points)"
        elif kind == "contrast":
            row["status"] = ("no limit: the means do not follow a first-order line within their chaos" if not fit_holds
                             else f"no limit within the goal (+-{goal * 100:g} points)")
        else:
            row["status"] = "limit within the goal" if within else "no limit within the goal"
        if not within and cost is not None:
            row.update(next_mesh(cost, v, members))
        rows.append(row)
    return pd.DataFrame(rows)


def next_mesh(cost: pd.DataFrame, velocity, members=None) -> dict:
    """The next mesh (REFINE times finer than the finest) and its cost: wall time per shot extrapolated along the
    power law of the measured wall times against elements across (this velocity's shots, the median per mesh: a shot
    paused or slowed by a neighbouring job would move a mean), times the shots a cell needs (three noses x
    ``members``)."""
    c = cost[cost.velocity_ms == velocity].groupby("elements_across").wall_time_s.median()
    n = c.index.to_numpy(float)
    t = c.to_numpy(float)
    if n.size < 2:
        return {}
    q = float(np.polyfit(np.log(n), np.log(t), 1)[0])
    nxt = float(n.max() * REFINE)
    per_shot = float(t[-1] * REFINE ** q)
    shots = 3 * (members or 1)
    return {"next_elements_across": nxt, "cost_exponent": q, "next_wall_time_per_shot_s": per_shot,
            "next_cell_hours": per_shot * shots / 3600.0}


def reading(r) -> tuple:
    """One row of ``chaos_rows`` (a dict or a CSV record, whose booleans come as text) read for a verdict: (estimate,
    U, limit), limit false where the study has no estimate (fewer than three meshes, no chaos measured) or where its
    first-order line does not hold the means within their chaos (then estimate +- U bounds nothing)."""
    est = float(r.get("estimate", math.nan) or math.nan)
    u = float(r.get("uncertainty", math.nan) or math.nan)
    return est, u, bool(math.isfinite(est) and math.isfinite(u) and str(r.get("fit_holds")) == "True")


def unstated_rows(cells: pd.DataFrame, baselines: dict, settings: dict, paper: dict) -> pd.DataFrame:
    """Per target, contrast and velocity: each scene's contrast (realisations' mean +- 2 s.e.; realisations: the members
    whose two shots both came to rest, of runs: the members run) and its change from the
    target's baseline scene (resolved beyond Student's t at 95 % on the two cells' realisations less two, times the
    change's standard error), the setting it changes and whether the paper's value lies within 2 s.e. of it.
    ``baselines``: target -> its baseline scene; ``settings``: scene -> (target, input, setting)."""
    rows = []
    con = cells[cells.kind == "contrast"]
    for scene, (target, name, setting) in settings.items():
        mine = con[con.scene == scene]
        base = con[con.scene == baselines[target]]
        for _, r in mine.iterrows():
            b = base[(base.quantity == r.quantity) & (base.velocity_ms == r.velocity_ms) & (base.profile == r.profile)]
            b0 = b.iloc[0] if len(b) else None
            change = r["mean"] - b0["mean"] if b0 is not None else math.nan
            change_se = math.hypot(r.se, b0.se) if b0 is not None and scene != baselines[target] else 0.0
            dof = r.realisations + b0.realisations - 2 if b0 is not None else 0
            k = t_quantile(CONFIDENCE, dof) if dof > 0 else math.inf
            p = paper.get((r.velocity_ms, r.quantity), math.nan)
            rows.append({"target": target, "scene": scene, "baseline": scene == baselines[target], "input": name,
                         "setting": setting,
                         "profile": r.profile, "element_size_m": r.element_size_m, "contrast": r.quantity,
                         "velocity_ms": r.velocity_ms, "realisations": r.realisations, "runs": r.runs,
                         "ratio": r["mean"],
                         "ratio_se": r.se, "sd": r.sd, **{k: r.get(k, math.nan) for k in MASSES},
                         "change_points": 100 * change, "change_se_points": 100 * change_se,
                         "change_resolved": bool(abs(change) > k * change_se) if change_se > 0 else False,
                         "change_t_factor": k if change_se > 0 else math.nan,
                         "paper_sim_ratio": p, "paper_within_2se": bool(abs(p - r["mean"]) <= COVERAGE * r.se)
                         if np.isfinite(p) and np.isfinite(r.se) else None})
    return pd.DataFrame(rows)
