"""The erosion-free target's grid-convergence study, as pure functions of tables.

Table 3's shots on meshes refined by one constant ratio, at each of several pilot holes halved in turn (the hole
fixed while the mesh refines, so that each sequence refines one geometry alike):

1. per hole, per depth and per nose contrast (a depth ratio, ``fe_studies.CONTRASTS``): the observed order, the
   Richardson extrapolation to zero element size and Roache's GCI of the finest mesh
   (``mesh_convergence.grid_refinement``), against the study's goals (``convergence_rows``);
2. over the holes: the same refinement of the zero-size values to zero hole (``hole_rows``), the hole's own order
   and GCI beside the largest mesh GCI of the holes;
3. what each mesh cost (``cost_rows``).

Nothing here reads or writes a file or draws.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .fe_results import CONTRASTS
from .mesh_convergence import MONOTONE, grid_refinement, least_squares_uncertainty

STOPPED = "stopped"   # a shot of the sequence stopped (tasks.fe.fe_shot's record): refined up to it, no goal met

SHOT_COLUMNS = ("depth_m", "wall_time_s", "steps", "elements", "energy_error_max", "eroded_mass_kg",
                "ejected_mass_kg", "crater_debris_mass_kg", "wall_debris_mass_kg", "remap_energy_j", "status",
                "diagnostic")
# a shot's record from before the wall-debris rule (fe.spec.Controls.wall_debris_behind) has no wall debris: an
# element that lost its shape there stopped the run instead
DEFAULTS = {"diagnostic": "", "wall_debris_mass_kg": 0.0}


def shot_rows(shots, across) -> pd.DataFrame:
    """One row per shot of the study: its mesh (profile, elements across the shank radius, element size) and what it
    gave and cost. ``shots``: the shots' summaries (tasks.fe); ``across``: profile -> elements across."""
    rows = []
    for s in shots:
        if s["profile"] not in across:
            raise ValueError(f"shot {s['nose']} at {s['velocity']} m/s: profile {s['profile']} is not one of the "
                             f"study's {sorted(across)}")
        if s["target"]["formulation"] != "erosion_free":
            raise ValueError(f"shot {s['nose']} at {s['velocity']} m/s on {s['profile']}: formulation "
                             f"{s['target']['formulation']}, the study's is erosion_free")
        rows.append({"pilot_hole": float(s["target"]["pilot_hole"]), "profile": s["profile"],
                     "elements_across": float(across[s["profile"]]), "element_size_m": s["element_size"],
                     # a record from before the key ran with the moving window
                     "domain": s.get("domain", "window"), "nose": s["nose"], "velocity_ms": float(s["velocity"]),
                     **{k: s.get(k, DEFAULTS[k]) if k in DEFAULTS else s[k] for k in SHOT_COLUMNS}})
    domains = sorted({r["domain"] for r in rows})
    if len(domains) > 1:
        raise ValueError(f"grid study: shots computed on domains {domains}; allowed: one (a window biases a depth by "
                         "up to several per cent, so the meshes would not compare)")
    return pd.DataFrame(rows).sort_values(["pilot_hole", "velocity_ms", "nose", "elements_across"],
                                          ascending=[False, True, True, True], ignore_index=True)


def refinement_ratio(across):
    """The one constant ratio of successive meshes (elements across, coarse first); an error if they are not so."""
    n = np.sort(np.asarray(across, float))
    r = n[1:] / n[:-1]
    if n.size < 3 or not np.allclose(r, r[0], rtol=1e-9) or not r[0] > 1:
        raise ValueError(f"grid study: meshes of {list(n)} elements across; allowed: >= 3 refined by one constant ratio > 1")
    return float(r[0])


def _row(quantity, case, v, f, across, ratio, paper, goal, relative):
    """One quantity's refinement. A mesh whose shot stopped (NaN) ends the sequence there: the meshes before it are
    refined when they are three or more (status STOPPED, the numbers those meshes give, no goal met), else nothing
    is."""
    f = np.asarray(f, float)
    upto = int(np.argmax(~np.isfinite(f))) if not np.all(np.isfinite(f)) else f.size
    nan = float("nan")
    if upto >= 3:
        g = grid_refinement(f[:upto], ratio)
        order, order_c, asym, ext, gci_f, gci_rel = (g.order, g.order_coarse, g.asymptotic_ratio, g.extrapolated,
                                                     g.gci_fine, g.gci_fine_relative)
        status = g.status if upto == f.size else STOPPED
    else:
        order = order_c = asym = ext = gci_f = gci_rel = nan
        status = STOPPED
    gci = gci_rel if relative else gci_f
    # Eça & Hoekstra's least-squares uncertainty of the finest mesh's value, on every mesh that ran (>= 4): the
    # estimate that stands where the three-mesh GCI finds no asymptotic range (mesh_convergence)
    if upto >= 4:
        ls = least_squares_uncertainty(1.0 / np.asarray(across[:upto], float), f[:upto])
        ls_cols = {"ls_fit": ls.fit, "ls_order": ls.found_order, "ls_value": ls.value, "ls_exact": ls.exact,
                   "ls_uncertainty": ls.uncertainty, "ls_uncertainty_relative": ls.relative}
    else:
        ls_cols = {"ls_fit": "", "ls_order": nan, "ls_value": nan, "ls_exact": nan, "ls_uncertainty": nan,
                   "ls_uncertainty_relative": nan}
    return {"quantity": quantity, "case": case, "velocity_ms": v,
            **{f"value_at_{n:g}_across": x for n, x in zip(across, f)},
            "meshes_refined": upto if upto >= 3 else 0,
            "observed_order": order, "observed_order_coarse": order_c, "asymptotic_ratio": asym,
            "status": status, "extrapolated": ext, "gci_fine": gci_f,
            "gci_fine_relative": gci_rel, "gci_goal": goal, "gci_goal_kind": "relative" if relative else "absolute",
            "goal_met": bool(status == MONOTONE and gci <= goal), "paper_simulated": paper,
            "paper_inside_gci_band": bool(abs(paper - ext) <= gci_f) if np.isfinite(paper) and np.isfinite(ext) else False,
            **ls_cols}


def convergence_rows(shots: pd.DataFrame, paper_depth: dict, goal_depth, goal_contrast) -> pd.DataFrame:
    """Per pilot hole, depth (nose, velocity) and contrast (name, velocity): the values on each mesh (coarse first),
    the grid refinement and the goal (depth: relative GCI <= goal_depth; contrast: absolute GCI of the ratio <=
    goal_contrast; met only in the asymptotic range). ``paper_depth``: (velocity, nose) -> the paper's simulated
    depth."""
    frames = []
    for hole, g in shots.groupby("pilot_hole", sort=False):
        t = _hole_convergence(g, paper_depth, goal_depth, goal_contrast)
        t.insert(0, "pilot_hole", hole)
        t.insert(1, "domain", g.domain.iloc[0])   # one for the whole study (shot_rows)
        frames.append(t)
    return pd.concat(frames, ignore_index=True)


def _hole_convergence(shots, paper_depth, goal_depth, goal_contrast):
    across = sorted(shots.elements_across.unique())
    ratio = refinement_ratio(across)
    rows = []
    for v in sorted(shots.velocity_ms.unique()):
        cell = shots[shots.velocity_ms == v]
        depth = {}
        for nose, g in cell.groupby("nose", sort=False):
            g = g.sort_values("elements_across")
            if list(g.elements_across) != across:
                raise ValueError(f"grid study: {nose} at {v:g} m/s has meshes {list(g.elements_across)}, not {across}")
            depth[nose] = g.depth_m.to_numpy()
            rows.append(_row("depth_m", nose, v, depth[nose], across, ratio, paper_depth.get((v, nose), np.nan),
                             goal_depth, True))
        for name, (num, den) in CONTRASTS.items():
            if num in depth and den in depth:
                paper = paper_depth.get((v, num), np.nan) / paper_depth.get((v, den), np.nan)
                rows.append(_row("depth_ratio", name, v, depth[num] / depth[den], across, ratio, paper, goal_contrast,
                                 False))
    return pd.DataFrame(rows)


def cost_rows(shots: pd.DataFrame, eroding=None, eroding_across=None) -> pd.DataFrame:
    """Per mesh: shots, wall time per shot (mean, max) and in all, steps and elements per shot (mean), formulation
    erosion_free; ``eroding``: the same noses and velocities on the eroding target at one mesh of ``eroding_across``
    elements across (their summaries, tasks.fe), a row of their own (formulation eroding) to set the per-shot time
    against."""
    def per_mesh(frame, formulation):
        g = frame.groupby(["profile", "elements_across", "element_size_m"], as_index=False)
        out = g.agg(shots=("wall_time_s", "size"), wall_time_mean_s=("wall_time_s", "mean"),
                    wall_time_max_s=("wall_time_s", "max"), wall_time_sum_s=("wall_time_s", "sum"),
                    steps_mean=("steps", "mean"), elements_mean=("elements", "mean"))
        out.insert(0, "formulation", formulation)
        return out

    parts = [per_mesh(shots, "erosion_free")]
    if eroding:
        pairs = set(zip(shots.nose, shots.velocity_ms))
        rows = [{"profile": e["profile"], "elements_across": float(eroding_across), "element_size_m": e["element_size"],
                 "nose": e["nose"], "velocity_ms": float(e["velocity"]), **{k: e[k] for k in ("wall_time_s", "steps", "elements")}}
                for e in eroding]
        missing = pairs - {(r["nose"], r["velocity_ms"]) for r in rows}
        if missing or len(rows) != len(pairs):
            raise ValueError(f"the eroding shots must be the study's noses and velocities once each: missing "
                             f"{sorted(missing)}, {len(rows)} shots for {len(pairs)}")
        parts.append(per_mesh(pd.DataFrame(rows), "eroding"))
    return pd.concat(parts, ignore_index=True).sort_values(["formulation", "elements_across"], ascending=[False, True],
                                                           ignore_index=True)


def hole_rows(conv: pd.DataFrame, goal_depth, goal_contrast) -> pd.DataFrame:
    """Per depth and contrast: its zero-size values at each pilot hole (largest first), refined to zero hole by
    grid_refinement with the holes' ratio (their observed order, extrapolation and GCI), beside the largest mesh
    GCI among the holes (the zero-size values' own uncertainty). Needs >= 3 holes halved (or refined by one
    ratio) in turn."""
    holes = sorted(conv.pilot_hole.unique(), reverse=True)
    if len(holes) < 3:
        raise ValueError(f"grid study: pilot holes {holes}; allowed: >= 3, refined by one constant ratio")
    ratio = refinement_ratio([1.0 / x for x in holes])
    rows = []
    value_cols = [c for c in conv.columns if c.startswith("value_at_")]
    for (quantity, case, v), g in conv.groupby(["quantity", "case", "velocity_ms"], sort=False):
        g = g.set_index("pilot_hole").loc[holes]
        f = g.extrapolated.to_numpy()
        values = g[value_cols].to_numpy().ravel()
        values = values[np.isfinite(values)]
        # every mesh's and hole's value: what the study can say when it finds no limit (its range, not an interval)
        spread = {"values": int(values.size), "values_min": float(values.min()), "values_median": float(np.median(values)),
                  "values_max": float(values.max())}
        relative = quantity == "depth_m"
        goal = goal_depth if relative else goal_contrast
        paper = float(g.paper_simulated.iloc[0])
        # the least-squares intervals of the holes' finest values (value +- U), their hull where every hole has one:
        # what the study can bound when it finds no limit (at the holes run, not at zero hole)
        lo_ls, hi_ls = (g.ls_value - g.ls_uncertainty).to_numpy(), (g.ls_value + g.ls_uncertainty).to_numpy()
        every = bool(np.all(np.isfinite(lo_ls) & np.isfinite(hi_ls)))
        ls = {"ls_holes": int(np.sum(np.isfinite(g.ls_uncertainty.to_numpy()))),
              "ls_low": float(lo_ls.min()) if every else float("nan"),
              "ls_high": float(hi_ls.max()) if every else float("nan")}
        ls["ls_ranking"] = ("" if relative else "holds at every hole" if every and ls["ls_low"] > 1
                            else "fails at every hole" if every and ls["ls_high"] < 1 else "undecided")
        row = {"quantity": quantity, "case": case, "velocity_ms": v, "domain": g.domain.iloc[0],
               **{f"zero_size_at_hole_{h:g}": x for h, x in zip(holes, f)}}
        if np.all(np.isfinite(f)):
            r = grid_refinement(f, ratio)
            gci = r.gci_fine_relative if relative else r.gci_fine
            mesh = (g.gci_fine_relative if relative else g.gci_fine).max()
            band = max(r.gci_fine, float(g.gci_fine.max()))
            limit = bool(np.isfinite(band) and np.isfinite(r.extrapolated))
            met = bool(r.status == MONOTONE and gci <= goal and mesh <= goal and (g.status == MONOTONE).all())
            hole = {"hole_order": r.order, "hole_order_coarse": r.order_coarse,
                    "hole_asymptotic_ratio": r.asymptotic_ratio, "hole_status": r.status,
                    "at_zero_hole": r.extrapolated, "hole_gci": r.gci_fine, "hole_gci_relative": r.gci_fine_relative}
        else:   # a hole whose meshes stopped too early: nothing to extrapolate to zero hole
            nan = float("nan")
            band, limit, met = nan, False, False
            hole = {"hole_order": nan, "hole_order_coarse": nan, "hole_asymptotic_ratio": nan, "hole_status": STOPPED,
                    "at_zero_hole": nan, "hole_gci": nan, "hole_gci_relative": nan}
        rank = "" if relative else ranking(hole["at_zero_hole"], band) if limit else "undecided"
        side = "" if relative else side_of_one(spread["values_min"], spread["values_max"])
        verdict, basis = ("", "") if relative else ranking_verdict(limit, rank, ls["ls_ranking"], side)
        rows.append({**row, **hole, "mesh_gci_largest": float(g.gci_fine.max()),
                     "mesh_gci_largest_relative": float(g.gci_fine_relative.max()),
                     "mesh_status_all_asymptotic": bool(np.all(np.isfinite(f)) and (g.status == MONOTONE).all()),
                     "meshes_stopped": bool((g.status == STOPPED).any()),
                     "gci_goal": goal, "goal_met": met, "uncertainty": band, "limit_found": limit, **spread,
                     # a contrast's verdict on the paper's ranking (the ratio above 1): on its limit where there is
                     # one, else undecided, with the side of 1 its values lie on
                     "ranking": rank, "side_of_1": side, **ls,
                     # the one verdict the diff, the docs and the claims read: on the limit, else on the holes'
                     # least-squares hull, else undecided (its basis: the side of 1 of every mesh's and hole's value)
                     "verdict": verdict, "verdict_basis": basis,
                     "paper_simulated": paper,
                     "paper_inside": bool(limit and np.isfinite(paper) and abs(paper - hole["at_zero_hole"]) <= band)})
    return pd.DataFrame(rows)


def side_of_one(low, high) -> str:
    """Where a study's depth ratios, ``low`` to ``high`` over every mesh and hole, lie against 1 (the paper's ranking:
    the ratio above 1): the words of a contrast's ``side_of_1`` column."""
    return ("above 1 on every mesh and hole" if low > 1 else "below 1 on every mesh and hole" if high < 1
            else "on both sides of 1" if low < 1 < high else "reaching 1")


def ranking_verdict(limit, rank, ls_ranking, side) -> tuple:
    """(verdict, basis) of a contrast on the paper's ranking (the ratio above 1): on the limit at zero size and hole
    where there is one (``rank``, basis "limit"); else on the hull of the holes' least-squares intervals where it lies
    on one side of 1 at every hole (basis "least squares"); else undecided, the basis the side of 1 of every mesh's
    and hole's value (``side``)."""
    if limit:
        return rank, "limit"
    word = {"holds at every hole": "holds", "fails at every hole": "fails"}.get(ls_ranking)
    return (word, "least squares") if word else ("undecided", side)


def ranking(ratio, band) -> str:
    """The paper's ranking (a depth ratio above 1) judged on a limit ``ratio`` +- ``band``: holds, fails or
    undecided (the band holds 1)."""
    return "holds" if ratio - band > 1 else "fails" if ratio + band < 1 else "undecided"
