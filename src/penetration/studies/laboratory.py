"""Calibrations on laboratory series and their out-of-sample validation.

A level with one factor to calibrate (the cavity level's strength scale, the fe level's failure strain at a mesh)
is fitted on characterised laboratory shots, never on the shots it is scored on. The protocol is data
(``Protocol``, from the config's ``validation.laboratory`` section, written before any fit):

- the shots fall in series (by a text of their source) and, inside a series, in fc groups;
- the fitted value minimises the sum over the fit's shots of ln(predicted / measured)^2 (the least-squares
  estimate of a relative error, unbiased in the geometric mean);
- the folds: ``all`` (every shot: the calibration users get), leave-one-series-out (``series:NAME`` fits on every
  other series and predicts NAME) and, inside a series with fc groups, leave-one-fc-group-out (``fc_group:SERIES:
  GROUP`` fits on the series' other groups and predicts GROUP);
- each fold is scored on its held-out shots only.

The level's depth is meant to be a smooth monotone function of the factor (the fe level's on a coarse mesh is not:
at 3 elements across a failure strain of 3.2 goes deeper than 1.6), so each shot's depth is computed once on a grid
of values (the task's grid, ``tasks.laboratory.calibrate_on_laboratory``) and a fold's fit interpolates it (monotone
cubic in ln value -> ln depth); the held-out shots are then computed directly at the fitted value, and the
interpolation's error at those shots is reported with them (``interpolation_error``), so that no reported
prediction is an interpolated one.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.interpolate import PchipInterpolator
from scipy.optimize import minimize_scalar

from ..errors import ParameterError
from ..levels import LEVELS
from .stats import slope, within_slope

# level -> (the Context attribute fitted, the record's parameter name, what it is)
FITTED = {
    "analytic": ("strength_factor_scale", "s_scale", "factor on the S of the strength law (Li & Chen's by default) of the "
                 "closed form (Eq 9), fitted on laboratory shots"),
    "cavity": ("strength_scale", "strength_scale", "HJC strength_scale: factor on the whole strength surface of every shot's concrete (the "
               "HJC set of Table 1 scaled to the shot's fc by the scaling rule), fitted on laboratory shots"),
    "fe": ("failure_strain", "fs", "erosion strain of the fe level's target at its mesh (the same elements across every "
           "shot's shank radius), fitted on laboratory shots"),
}


@dataclass(frozen=True)
class Protocol:
    """Series (name -> a text of the shot's ``source`` naming it) and fc groups (series -> group -> [lo, hi] MPa,
    inclusive) of the laboratory shots; the factor's grid (ascending values, at least 4)."""
    series: dict
    fc_groups: dict = field(default_factory=dict)
    grid: tuple = ()

    def __post_init__(self):
        if len(self.series) < 2:
            raise ParameterError("validation.laboratory", "series", self.series, "at least two series (name: text of "
                                 "the source)")
        for s, groups in self.fc_groups.items():
            if s not in self.series:
                raise ParameterError("validation.laboratory", f"fc_groups.{s}", groups,
                                     f"a series of validation.laboratory.series: {sorted(self.series)}")
            if len(groups) < 2:
                raise ParameterError("validation.laboratory", f"fc_groups.{s}", groups, "at least two groups")
            for g, (lo, hi) in groups.items():
                if not (0 < lo < hi):
                    raise ParameterError("validation.laboratory", f"fc_groups.{s}.{g}", [lo, hi], "0 < lo < hi (MPa)")
        g = np.asarray(self.grid, float)
        if g.size and (g.size < 4 or np.any(g <= 0) or np.any(np.diff(g) <= 0)):
            raise ParameterError("validation.laboratory", "grid", list(self.grid), "at least 4 ascending values > 0")

    @classmethod
    def from_config(cls, section, grid=()):
        return cls(dict(section["series"]), {s: {g: tuple(r) for g, r in groups.items()}
                                             for s, groups in section.get("fc_groups", {}).items()}, tuple(grid))

    def series_of(self, source: str) -> str:
        hits = [name for name, text in self.series.items() if text in source]
        if len(hits) != 1:
            raise ValueError(f"a shot's source {source[:60]!r}... names {len(hits)} series of "
                             f"{sorted(self.series)} (each shot must belong to exactly one)")
        return hits[0]

    def group_of(self, series: str, fc_mpa: float) -> str:
        groups = self.fc_groups.get(series, {})
        hits = [g for g, (lo, hi) in groups.items() if lo <= fc_mpa <= hi]
        if groups and len(hits) != 1:
            raise ValueError(f"a shot of series {series} at fc = {fc_mpa:g} MPa falls in {len(hits)} of its fc groups "
                             f"{groups}")
        return hits[0] if hits else ""

    def folds(self, series, groups) -> list:
        """(name, fit mask, held-out mask) of every fold, ``all`` first (its held-out mask is empty)."""
        series, groups = np.asarray(series), np.asarray(groups)
        out = [("all", np.ones(series.size, bool), np.zeros(series.size, bool))]
        for s in self.series:
            held = series == s
            out.append((f"series:{s}", ~held, held))
        for s, gs in self.fc_groups.items():
            for g in gs:
                held = (series == s) & (groups == g)
                out.append((f"fc_group:{s}:{g}", (series == s) & ~held, held))
        for name, fit, held in out:
            if not fit.any():
                raise ValueError(f"fold {name}: no shot to fit on")
            if np.any(fit & held):
                raise ValueError(f"fold {name}: a shot is both fitted and held out")
        return out


def log_interpolants(grid, depths):
    """Per shot, ln depth as a monotone cubic in ln value over the grid (depths: shots x grid, every one > 0)."""
    grid, depths = np.asarray(grid, float), np.asarray(depths, float)
    if depths.ndim != 2 or depths.shape[1] != grid.size:
        raise ValueError(f"depths of shape {depths.shape}: expected (shots, {grid.size})")
    if not np.all(np.isfinite(depths) & (depths > 0)):
        raise ValueError("a depth on the grid is not a finite positive number")
    return [PchipInterpolator(np.log(grid), np.log(row)) for row in depths]


@dataclass(frozen=True)
class Fit:
    value: float
    rms_log_error: float       # root mean square of ln(predicted / measured) over the fit's shots
    shots: int
    at_grid_edge: bool         # the minimum lies at an end of the grid: the grid does not bracket it


def fit_factor(grid, depths, measured, mask) -> Fit:
    """The value on [grid[0], grid[-1]] minimising sum over ``mask``'s shots of ln(depth(value)/measured)^2, the
    depths interpolated from the grid (log_interpolants)."""
    grid = np.asarray(grid, float)
    rows = np.flatnonzero(mask)
    curves = log_interpolants(grid, np.asarray(depths, float)[rows])
    target = np.log(np.asarray(measured, float)[rows])

    def sse(x):
        return float(sum((c(x) - t) ** 2 for c, t in zip(curves, target)))

    lo, hi = math.log(grid[0]), math.log(grid[-1])
    xs = np.linspace(lo, hi, 8 * grid.size)                 # a scan first: the bounded search then stays local
    k = int(np.argmin([sse(x) for x in xs]))
    a, b = xs[max(k - 1, 0)], xs[min(k + 1, xs.size - 1)]
    res = minimize_scalar(sse, bounds=(a, b), method="bounded", options={"xatol": 1e-10})
    x = float(res.x) if res.fun <= sse(xs[k]) else float(xs[k])
    edge = min(x - lo, hi - x) < 1e-6 * (hi - lo)
    return Fit(math.exp(x), math.sqrt(sse(x) / rows.size), int(rows.size), bool(edge))


def interpolated_depths(grid, depths, value):
    """Every shot's depth at ``value`` from the grid (log_interpolants)."""
    return np.exp([c(math.log(value)) for c in log_interpolants(grid, depths)])


def errors_summary(rel):
    """Median and 90th percentile of |relative error|, mean signed error, count within 10 %."""
    rel = np.asarray(rel, float)
    a = np.abs(rel)
    return {"shots": int(rel.size), "median_abs_rel_err": float(np.median(a)) if a.size else math.nan,
            "p90_abs_rel_err": float(np.percentile(a, 90)) if a.size else math.nan,
            "mean_rel_err": float(rel.mean()) if a.size else math.nan, "within_10pct": int((a <= 0.10).sum())}


# The validation of every level on the development shots (tasks.levels.validation_levels): per row the level, its
# calibration, how it is scored and the key of its predictions' columns (rel_err_KEY) in the shots table.
ROWS = [("analytic", "none: S from {law}", "all shots (the S law's authors fitted it on data that include them)",
         "analytic"),
        ("trajectory", "none: S from {law}", "all shots (the S law's authors fitted it on data that include them)",
         "trajectory"),
        ("cavity", "do1", "all shots (fitted on DO1 only)", "cavity"),
        ("cavity", "laboratory", "leave one series out", "cavity_laboratory"),
        ("cavity", "laboratory", "leave one fc group out (2003 series)", "cavity_laboratory_fc_group"),
        ("fe", "do1", "all shots (fitted on DO1 only)", "fe"),
        ("fe", "laboratory", "leave one series out", "fe_laboratory"),
        ("fe", "laboratory", "leave one fc group out (2003 series)", "fe_laboratory_fc_group")]
CONFIDENCE = 0.90


def summary_rows(shots, law):
    """One row per (level, calibration, scoring) of ROWS whose predictions the shots table has (its column
    rel_err_KEY, KEY named in the row's ``predictions``): the errors of the shots scored and the residual's slopes.
    The primary row of a level is its DO1 or its leave-one-series-out one."""
    rows = []
    series = shots.series_cavity_laboratory.to_numpy()
    for level, calibration, scoring, key in ROWS:
        if f"rel_err_{key}" not in shots:
            continue
        err = shots[f"rel_err_{key}"]
        m = err.notna().to_numpy()
        r = np.log1p(err.to_numpy()[m])
        ln_fc, ln_d = np.log(shots.fc_MPa.to_numpy()[m]), np.log(shots.diameter_m.to_numpy()[m])
        b = slope(ln_fc, r, CONFIDENCE)
        w = within_slope(ln_fc, r, series[m], CONFIDENCE)
        c = slope(ln_d, r, CONFIDENCE)
        rows.append({"level": level, "calibration": calibration.format(law=law), "scoring": scoring,
                     "predictions": key, "primary": key in LEVELS or key.endswith("_laboratory"),
                     **errors_summary(err.to_numpy()[m]),
                     "slope_ln_fc": b[0], "slope_ln_fc_low": b[1], "slope_ln_fc_high": b[2],
                     "slope_ln_fc_within_series": w[0], "slope_ln_fc_within_series_low": w[1],
                     "slope_ln_fc_within_series_high": w[2],
                     "slope_ln_calibre": c[0], "slope_ln_calibre_low": c[1], "slope_ln_calibre_high": c[2]})
    return pd.DataFrame(rows)


def users_rows(summary):
    """The primary validation row of each level at the calibration users get by default: the level's laboratory row
    where it has one, else its only primary row (a level not calibrated on the laboratory shots)."""
    p = summary[summary.primary.astype(bool)]
    with_laboratory = set(p.level[p.calibration == "laboratory"])
    return p[(p.calibration == "laboratory") | ~p.level.isin(with_laboratory)]
