"""How well a level predicts the contrast between two noses: scored on the development shots' measured nose pairs.

A measured nose pair is two shots of one series (same calibre, same concrete strength: the same targets' make)
with different noses. Its contrast error is the level's ratio of predicted to measured depth for the sharper
nose over that for the blunter one, minus one: (pred_a / meas_a) / (pred_b / meas_b) - 1. The bias a level has
for the series (its strength, its scale) cancels; what remains is what the level gets wrong about the noses, the
number a user comparing noses needs. Two shots at different velocities are a pair too: the level carries the
velocity. The pairs of one series share shots, so they are not independent; the summary says how many shots
and series they rest on.
"""
from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

SERIES_KEYS = ("diameter_m", "fc_MPa")


def sharpness(row) -> tuple:
    """An order of noses from blunt to sharp: flat, hemisphere (CRH 0.5), ogives by CRH, other shapes by name."""
    shape = str(row["nose_shape"])
    crh = {"flat": 0.0, "hemispherical": 0.5}.get(shape, row["crh"] if shape == "ogive" else float("inf"))
    return (float(crh), nose_label(row))


def nose_label(row) -> str:
    return f"CRH {row['crh']:g}" if row["nose_shape"] == "ogive" else str(row["nose_shape"])


def pairs(shots: pd.DataFrame, predictions: dict) -> pd.DataFrame:
    """One row per measured nose pair and level: the shots, their noses, the measured depth ratio and the
    contrast error of each level. ``predictions``: level name -> column of predicted depth (m) in ``shots``.
    The sharper nose is a (sharpness: flat, hemisphere, ogives by CRH, other shapes by name)."""
    rows = []
    for key, group in shots.groupby(list(SERIES_KEYS), sort=True):
        group = group.sort_values("shot_id")
        for (_, p), (_, q) in itertools.combinations(group.iterrows(), 2):
            if nose_label(p) == nose_label(q):
                continue
            a, b = (p, q) if sharpness(p) > sharpness(q) else (q, p)
            base = {"series_diameter_m": key[0], "series_fc_MPa": key[1], "shot_a": a["shot_id"], "nose_a": nose_label(a),
                    "velocity_a_ms": a["velocity_ms"], "shot_b": b["shot_id"], "nose_b": nose_label(b),
                    "velocity_b_ms": b["velocity_ms"], "measured_ratio": a["dop_m"] / b["dop_m"]}
            for level, col in predictions.items():
                err = (a[col] / a["dop_m"]) / (b[col] / b["dop_m"]) - 1.0
                rows.append({**base, "level": level, "predicted_ratio": a[col] / b[col], "contrast_error": err})
    return pd.DataFrame(rows)


def summary(table: pd.DataFrame) -> pd.DataFrame:
    """Per level: pairs, shots and series they rest on, median and 90th percentile of |contrast error|, mean."""
    out = []
    for level, g in table.groupby("level", sort=False):
        e = g.contrast_error.to_numpy()
        shots = set(g.shot_a) | set(g.shot_b)
        out.append({"level": level, "pairs": len(g), "shots": len(shots),
                    "series": g[["series_diameter_m", "series_fc_MPa"]].drop_duplicates().shape[0],
                    "noses": "; ".join(sorted({f"{x} vs {y}" for x, y in zip(g.nose_a, g.nose_b)})),
                    "median_abs_contrast_error": float(np.median(np.abs(e))),
                    "p90_abs_contrast_error": float(np.quantile(np.abs(e), 0.9)),
                    "mean_contrast_error": float(e.mean())})
    return pd.DataFrame(out)
