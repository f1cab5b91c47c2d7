"""The scale effect's validation read off the laboratory calibrations (tables in, tables out).

A level's factor fitted on one series alone against the other's says whether the level carries the two calibres
(26.9 mm and 76.2 mm) with one constant: their ratio is 1 for a level that does. The leave-one-series-out
predictions, pooled over both held-out series, score the level out of sample; DO1 (140 mm) is a test no fit saw.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .laboratory import errors_summary

VARIANT = ["variant", "mechanisms", "beyond", "aggregate_m", "lambda0", "transitional_size_m"]


def split_summary(fits, predictions, do1, series):
    """One row per (level, variant): the factor fitted on each series alone (the folds whose fit holds one series),
    their ratio (largest over smallest), the pooled held-out errors of the leave-one-series-out folds with each
    series' mean signed error, and DO1's error at the factor of all shots."""
    rows = []
    keys = ["level", "variant"]
    for (level, variant), f in fits.groupby(keys, sort=False):
        p = predictions[(predictions.level == level) & (predictions.variant == variant)
                        & predictions.fold.str.startswith("series:")]
        alone = {s: f.loc[f.fit_series == s, "value"] for s in series}
        values = {s: float(v.iloc[0]) for s, v in alone.items() if len(v)}
        d = do1[(do1.level == level) & (do1.variant == variant)]
        row = {"level": level, **{c: f[c].iloc[0] for c in VARIANT}, "parameter": f.parameter.iloc[0],
               "value_all": float(f.loc[f.fold == "all", "value"].iloc[0]),
               **{f"value_{s}": values.get(s, np.nan) for s in series},
               "split_ratio": max(values.values()) / min(values.values()) if len(values) == len(series) else np.nan}
        loso = errors_summary(p.rel_error.to_numpy())
        row.update({f"loso_{k}": v for k, v in loso.items()})
        row.update({f"mean_rel_err_{s}": float(p.loc[p.series == s, "rel_error"].mean()) for s in series})
        row.update({"do1_pred_m": float(d.dop_pred_m.iloc[0]) if len(d) else np.nan,
                    "do1_rel_error": float(d.rel_error.iloc[0]) if len(d) else np.nan})
        rows.append(row)
    return pd.DataFrame(rows)


# the targets the scale effect's validation is read against: a physics level's leave-one-series-out errors (median
# and 90th percentile of |error|, pooled), the two series' fitted factors (their ratio), DO1 without a DO1 calibration
GOALS = {"loso_median": 0.07, "loso_p90": 0.20, "split_ratio": 1.20, "do1": 0.10}


def goals_met(row) -> dict:
    """Which goals a row of the validation summary (split_summary's columns) meets: goal -> bool."""
    return {"loso_median": float(row["loso_median_abs_rel_err"]) <= GOALS["loso_median"],
            "loso_p90": float(row["loso_p90_abs_rel_err"]) <= GOALS["loso_p90"],
            "split_ratio": float(row["split_ratio"]) <= GOALS["split_ratio"],
            "do1": abs(float(row["do1_rel_error"])) <= GOALS["do1"]}


def best_variant(rows):
    """The row (a dict of the validation summary) of the smallest held-out median |error| among ``rows``, None for
    none."""
    return min(rows, key=lambda r: float(r["loso_median_abs_rel_err"])) if rows else None


def recommended_variant(rows):
    """The variant of the effect a user's shot gets by default: among the validation summary's rows (dicts) with
    the effect that meet every goal, the one of the smallest held-out median |error|; None where none does."""
    best = best_variant([r for r in rows if r["variant"] != "none" and all(goals_met(r).values())])
    return best["variant"] if best else None


def do1_gap(values, points, do1_point="do1"):
    """How much calibre dependence DO1 asks of a level, beside what the laboratory series show and what each published
    mechanism supplies. ``values``: one row per source (a dict with ``kind`` level or mechanism, ``name``,
    ``quantity`` and its value at each point, ``value_POINT``); ``points``: point name -> (calibre m, velocity m/s),
    the laboratory series in any order and ``do1_point``. Per row: the ratio of the value at the larger series
    calibre over the smaller (``ratio_series``), DO1's over the larger series' (``ratio_do1``), each as a power of
    calibre (``exponent_series``, ``exponent_do1``: ln ratio / ln calibre ratio), and the larger series' value
    carried to DO1's calibre by the series' power (``series_trend_at_do1``)."""
    series = sorted((p for p in points if p != do1_point), key=lambda p: points[p][0])
    if len(series) != 2:
        raise ValueError(f"do1_gap needs two laboratory series, got {series}")
    small, large = series
    d_small, d_large, d_do1 = points[small][0], points[large][0], points[do1_point][0]
    rows = []
    for v in values:
        a, b, c = (float(v[f"value_{p}"]) for p in (small, large, do1_point))
        ratio_series, ratio_do1 = b / a, c / b
        exponent_series = np.log(ratio_series) / np.log(d_large / d_small)
        rows.append({**v, "ratio_series": ratio_series, "ratio_do1": ratio_do1, "exponent_series": exponent_series,
                     "exponent_do1": np.log(ratio_do1) / np.log(d_do1 / d_large),
                     "series_trend_at_do1": b * (d_do1 / d_large) ** exponent_series})
    out = pd.DataFrame(rows)
    for p in (small, large, do1_point):
        out[f"calibre_{p}_m"], out[f"velocity_{p}_ms"] = points[p]
    return out
