"""The verdict on the paper's nose contrasts, one table: each contrast at each Table 3 velocity, per model, its value
+- the uncertainty of the model's own numerics (chaos and mesh), the spread over the inputs the paper does not state
shown apart, the paper's simulated value, and which unstated input at which setting reaches it.

Models (their sources, all outputs of the pipeline):

- Eq 9 with the paper's S = 72 fc^-0.5 (nothing calibrated; figures/nose_contrasts_table.csv): a closed form, no
  numerical uncertainty, no unstated input it could take;
- the trajectory and the cavity level with their strength calibrated on DO1 (the same table; the cavity level's
  calibration variants, figures/cavity_table3_sensitivity.csv, are its unstated inputs: friction, lock and cracking
  conventions, zone counts);
- the eroding FE target at zero element size (figures/fe/contrast_extrapolation.csv: a line through many meshes each
  calibrated on DO1, its interval) with the changes the unstated inputs make at the default mesh
  (figures/fe/unstated_inputs.csv: nose friction, the paper's failure strain as stated);
- the erosion-free FE target at zero element size (figures/fe/erosion_free/chaos_v*.csv: realisations on the meshes
  of fe_realisations.chaos, Table 1's HJC as stated) with the changes nose friction makes at its coarsest mesh; a resolved change of the
  target's own numerical control (the lip's ejection halved or doubled) joins its uncertainty.

An unstated input "reaches" the paper's value when the paper's value lies between the model's value and the value
that input's setting gives (widened by the model's uncertainty): a setting in between would give it. Nothing here is
tuned toward the paper's contrasts. Nothing here reads or writes a file.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..studies.fe_results import CONTRASTS
from .diff import Row, interval_status

TOLERANCE = 0.02   # a contrast within 2 points of the paper's (the diff's goal for an FE contrast)
UNSTATED = ("friction", "failure strain")   # the inputs of the unstated-inputs study the paper does not state
EQ9, TRAJECTORY, CAVITY, ERODING, FREE = ("Eq 9 (S = 72 fc^-0.5 as stated)", "trajectory (S calibrated on DO1)",
                                          "cavity level (strength calibrated on DO1)",
                                          "eroding FE at zero element size (fs calibrated on DO1 per mesh)",
                                          "erosion-free FE at zero element size (Table 1 HJC as stated)")
CALIBRATED = {EQ9: False, TRAJECTORY: True, CAVITY: True, ERODING: True, FREE: False}
SHORT = {EQ9: "Eq 9 (stated S)", TRAJECTORY: "trajectory", CAVITY: "cavity", ERODING: "eroding FE, zero size",
         FREE: "erosion-free FE, zero size"}
KEYS = {EQ9: "eq9", TRAJECTORY: "trajectory", CAVITY: "cavity", ERODING: "eroding", FREE: "erosion_free"}
COLUMNS = ("contrast", "velocity_ms", "model", "value", "uncertainty", "uncertainty_basis", "calibrated", "provenance",
           "unstated_low", "unstated_high", "unstated_inputs", "paper_sim_ratio", "paper_minus_value_points",
           "paper_within_uncertainty", "paper_within_unstated", "reached_by", "limit")


def _reached(value, u, paper, settings):
    """The settings (label -> value) that move the model's value towards the paper's and whose value and the
    model's bracket the paper's, widened by u; none where the paper's value already lies within value +- u."""
    if abs(paper - value) <= u:
        return []
    return [label for label, x in settings.items()
            if (x - value) * (paper - value) > 0 and min(value, x) - u <= paper <= max(value, x) + u]


def _row(contrast, v, model, value, u, basis, provenance, paper, settings, limit=True):
    """One row of the table; ``settings``: label -> the contrast the model gives at that unstated setting (a
    non-finite one left out); ``limit``: whether the value is a limit (false: a study found none, the row is read as
    undecided)."""
    settings = {k: x for k, x in settings.items() if math.isfinite(x)}
    values = [value, *settings.values()]
    finite = value is not None and math.isfinite(value)
    low, high = (min(values), max(values)) if finite and settings else (math.nan, math.nan)
    within = bool(finite and abs(paper - value) <= u) if finite else None
    reached = _reached(value, u, paper, settings) if finite else []
    inside = bool(finite and abs(paper - value) <= u)
    return {"contrast": contrast, "velocity_ms": float(v), "model": model, "value": value if finite else math.nan,
            "uncertainty": u, "uncertainty_basis": basis, "calibrated": CALIBRATED[model], "provenance": provenance,
            "unstated_low": low, "unstated_high": high,
            "unstated_inputs": "; ".join(f"{k} {x:.3f}" for k, x in settings.items()),
            "paper_sim_ratio": paper, "paper_minus_value_points": 100 * (paper - value) if finite else math.nan,
            "paper_within_uncertainty": within,
            "paper_within_unstated": bool(finite and settings and low - u <= paper <= high + u) if finite else None,
            "reached_by": "; ".join(reached) if reached else ("none" if finite and settings and not inside else ""),
            "limit": limit}


def _cavity_variants(sensitivity: pd.DataFrame, contrast, v):
    """The cavity level's Table 3 contrast under each calibration variant that changes an input or convention the
    paper does not state (label -> ratio): not the record variant itself, nor those that change only the zone count
    (a numerical setting)."""
    num, den = CONTRASTS[contrast]
    record = sensitivity[sensitivity.variant.str.startswith("record")]
    zones = int(record.zones.iloc[0]) if len(record) else None
    keep = sensitivity[~sensitivity.variant.str.startswith("record") & (sensitivity.zones == zones)]
    out = {}
    for name, g in keep[keep.velocity == v].groupby("variant", sort=False):
        d = g.set_index("nose").cavity_m
        if num in d and den in d:
            out[f"cavity variant {name}"] = float(d[num] / d[den])
    return out


def _unstated_changes(unstated: pd.DataFrame | None, target, contrast, v, base_value):
    """label -> base_value + the change that scene's unstated setting makes to the contrast (realisations' means);
    a setting whose shots did not come to rest (no contrast) is left out."""
    if unstated is None:
        return {}
    u = unstated[(unstated.target == target) & (unstated.contrast == contrast) & (unstated.velocity_ms == v)]
    return {f"{r['input']} {r['setting']:g}": base_value + r.change_points / 100 for _, r in u.iterrows()
            if str(r.baseline) != "True" and r["input"] in UNSTATED and np.isfinite(r.change_points)}


def _control_changes(unstated: pd.DataFrame | None, target, contrast, v):
    """The resolved changes (points) a target's numerical controls (not UNSTATED inputs) make to the contrast."""
    if unstated is None:
        return []
    u = unstated[(unstated.target == target) & (unstated.contrast == contrast) & (unstated.velocity_ms == v)
                 & ~unstated["input"].isin(UNSTATED) & (unstated.baseline.astype(str) != "True")]
    return [(f"{r['input']} {r['setting']:g}", float(r.change_points)) for _, r in u.iterrows()
            if str(r.change_resolved) == "True"]


def verdict_rows(table: pd.DataFrame, sensitivity: pd.DataFrame, eroding: pd.DataFrame | None,
                 chaos: pd.DataFrame | None, unstated: pd.DataFrame | None, provenance: dict,
                 free_velocities=(500.0, 1200.0)) -> pd.DataFrame:
    """The verdict table (module doc). ``table``: figures/nose_contrasts_table.csv; ``sensitivity``:
    figures/cavity_table3_sensitivity.csv; ``eroding``: figures/fe/contrast_extrapolation.csv; ``chaos``:
    figures/fe/erosion_free/chaos.csv; ``unstated``: figures/fe/unstated_inputs.csv (None where a study's output is
    missing: its rows say pending); ``provenance``: model key (KEYS) -> a note on its source (which build, which solver);
    ``free_velocities``: the velocities the erosion-free study runs (config fe_realisations.velocities)."""
    rows = []
    for _, t in table.iterrows():
        name, v, paper = t.contrast, float(t.velocity), float(t.paper_sim_ratio)
        if name not in CONTRASTS:
            continue
        rows.append(_row(name, v, EQ9, float(t.analytic_stated_S_ratio), 0.0, "closed form", provenance.get(KEYS[EQ9], ""),
                         paper, {}))
        rows.append(_row(name, v, TRAJECTORY, float(t.trajectory_ratio), 0.0, "ODE to 1e-8",
                         provenance.get(KEYS[TRAJECTORY], ""), paper, {}))
        rows.append(_row(name, v, CAVITY, float(t.cavity_ratio), 0.0, "cycles to 1e-6", provenance.get(KEYS[CAVITY], ""),
                         paper, _cavity_variants(sensitivity, name, v)))
        e = None if eroding is None else eroding[(eroding.contrast == name) & (eroding.velocity_ms == v)]
        if e is None or e.empty:
            rows.append(_row(name, v, ERODING, math.nan, math.nan, "pending: study fe_extrapolation",
                             provenance.get(KEYS[ERODING], ""), paper, {}))
        else:
            e = e.iloc[0]
            value = float(e.ratio_at_zero_size)
            u = max(value - float(e.interval_low), float(e.interval_high) - value)
            rows.append(_row(name, v, ERODING, value, u, f"{100 * float(e.confidence):.0f} % interval of the line through "
                             f"{int(e.meshes)} meshes", provenance.get(KEYS[ERODING], ""), paper,
                             _unstated_changes(unstated, "eroding", name, v, value)))
        if v not in free_velocities:
            continue
        c = None if chaos is None else chaos[(chaos.quantity == name) & (chaos.velocity_ms == v)]
        if c is None or c.empty:
            rows.append(_row(name, v, FREE, math.nan, math.nan, "pending: study fe_erosion_free_chaos",
                             provenance.get(KEYS[FREE], ""), paper, {}))
            continue
        c = c.iloc[0]
        if not math.isfinite(float(c.get("estimate", math.nan))):
            rows.append(_row(name, v, FREE, math.nan, math.nan, f"study fe_erosion_free_chaos: {c.status}",
                             provenance.get(KEYS[FREE], ""), paper, {}))
            continue
        value, u = float(c.estimate), float(c.uncertainty)
        holds = str(c.fit_holds) == "True"
        basis = (f"t x s.e. of the line through {int(c.meshes)} meshes ({int(c.realisations_min)}+ realisations each)"
                 + ("" if holds else "; the line does not hold the means: no limit"))
        controls = _control_changes(unstated, "erosion_free", name, v)
        if controls:   # a resolved change a numerical control makes joins the numerics' uncertainty
            u = math.hypot(u, max(abs(x) for _, x in controls) / 100)
            basis += "; with the largest resolved change of " + ", ".join(f"{k} ({x:+.1f} points)" for k, x in controls)
        rows.append(_row(name, v, FREE, value, u, basis, provenance.get(KEYS[FREE], ""), paper,
                         _unstated_changes(unstated, "erosion_free", name, v, value), holds))
    return pd.DataFrame(rows, columns=COLUMNS)


def verdict_diff_rows(verdict: pd.DataFrame) -> list:
    """The verdict in the diff (item table3, quantity "verdict: contrast (model)"): per contrast, velocity and model,
    the ratio against the paper's simulated one,
    judged on value +- uncertainty to within TOLERANCE (interval_status: an agreement of a calibrated model is
    agrees-after-calibration; a pending study's row undecided)."""
    out = []
    for _, r in verdict.iterrows():
        model = r.model.replace(",", ";")
        case = f"{int(r.velocity_ms)} m/s; the verdict table (figures/verdict.csv)"
        if not math.isfinite(r.value):
            out.append(Row("table3", f"verdict: {r.contrast} ({model})", f"{case}; {r.uncertainty_basis.replace(',', ';')}",
                           r.paper_sim_ratio, math.nan, math.nan, TOLERANCE / r.paper_sim_ratio, "undecided"))
            continue
        lo, hi = r.value - r.uncertainty, r.value + r.uncertainty
        tol = TOLERANCE / r.paper_sim_ratio   # relative, as every row's tol
        if not (math.isfinite(lo) and math.isfinite(hi)) or str(r.limit) != "True":
            status, note = "undecided", "; no limit"
        else:
            status, note = interval_status(r.paper_sim_ratio, lo, hi, TOLERANCE, str(r.calibrated) == "True"), ""
        out.append(Row("table3", f"verdict: {r.contrast} ({model})", f"{case}; +-{r.uncertainty:.3f}{note}",
                       r.paper_sim_ratio, r.value, abs(r.value - r.paper_sim_ratio) / r.paper_sim_ratio, tol, status))
    return out
