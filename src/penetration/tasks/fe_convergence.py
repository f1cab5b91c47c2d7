"""Task of the FE nose contrasts' limit at zero element size (a study).

Each contrast of Table 3 (a ratio of two FE depths, each mesh with its own DO1 calibration) is fitted
against the element size over the meshes of the bands (penetration.mesh_convergence.size_regression) and
extrapolated to h = 0 with its interval. The single meshes of the convergence profiles (3, 8, 10 and 12
elements across the shank radius) are shown beside it: whether their series is monotone says whether a
sequence of four meshes could have been read as convergence.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..figures.fe_convergence import contrast_extrapolation_figure
from ..io import task, write_csv
from ..mesh_convergence import size_regression

MM = 1e-3


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
    """One row per Table 3 cell (velocity, nose): the FE depth over the meshes (``tables``: each mesh's
    table3.csv) fitted against the element size and extrapolated to zero, with its interval."""
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


@task
def fe_contrast_extrapolation(inputs, outputs, params):
    """The FE nose contrasts and depths at zero element size: regression over the band meshes, beside the single
    meshes."""
    meshes = pd.read_csv(inputs.meshes)
    singles = pd.read_csv(inputs.singles)
    t = extrapolation_rows(meshes, singles, params.confidence)
    write_csv(t, outputs.csv)
    write_csv(depth_rows([pd.read_csv(f) for f in inputs.tables], params.confidence), outputs.depths)
    contrast_extrapolation_figure(t, meshes, singles, outputs.png, params.dpi)
    for r in t.itertuples():
        print(f"{r.contrast:14s} {r.velocity_ms:5d} m/s: {r.ratio_at_zero_size:.3f} [{r.interval_low:.3f}, "
              f"{r.interval_high:.3f}], scatter {r.scatter_points:.1f} points, paper {r.paper_sim_ratio:.3f}")
