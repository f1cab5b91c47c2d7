"""Task of accuracy against cost as prediction errors (a study): every level at each setting that predicts, its
errors on what it was not fitted to, beside its wall time per shot (figures/timing/accuracy_cost.csv).

Three prediction errors, each against data no level was calibrated on:

- Table 3 of the paper's simulation, the cells of the noses other than the calibration shot's (CRH 4.5 and CRH 3:
  the double ogive's cells share the DO1 shot's nose and mass, so a level calibrated on DO1 meets them largely by
  construction): the mean |deviation|;
- the nose contrasts of the paper's simulated Table 3 (DO/CRH 4.5, CRH 4.5/CRH 3, DO/CRH 3 at 500-1200 m/s),
  which no calibration on one shot can set: the mean |difference| in points;
- the 25 published development shots (the validation): the median |error| of the depth, out of sample (the cavity
  and fe levels at their default laboratory calibrations, leaving one series out; a mesh without one at DO1's; the
  analytic and trajectory levels with a published S).

A level's residual on its own calibration shot is not an accuracy and is not shown here (it stays in
figures/accuracy_cost.csv, with each solver's convergence against its own finest setting).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..figures.accuracy_cost import accuracy_cost_drawing
from ..pipeline.io import task, write_csv
from ..studies.laboratory import users_rows

OTHER_NOSES = ("crh45", "crh3")
CONTRASTS = ("DO/CRH 4.5", "CRH 4.5/CRH 3", "DO/CRH 3")


def _cells(table, column):
    t = table[table.nose.isin(OTHER_NOSES)]
    return float(np.mean(np.abs(t[column] / t.paper_sim_m - 1))), int(len(t))


def _contrasts(table, column):
    t = table[table.contrast.isin(CONTRASTS)]
    return float(np.mean(np.abs(t[column] - t.paper_sim_ratio))) * 100, int(len(t))


def prediction_rows(t3, contrasts, fe_tables, fe_ratios, validation):
    """Rows per (level, setting): Table 3's other noses, the contrasts, the validation (NaN where not computed).

    t3: figures/table3.csv; contrasts: figures/nose_contrasts_table.csv; fe_tables, fe_ratios: {setting:
    figures/fe/{profile}/table3.csv, _ratios.csv}; validation: {(level, setting): median |error|}.
    """
    c = contrasts.rename(columns={"velocity": "velocity_ms"})
    sources = [("analytic", "S stated (Li & Chen)", t3, "analytic_stated_S_m", c, "analytic_stated_S_ratio"),
               ("analytic", "S calibrated on DO1", t3, "analytic_m", c, "analytic_ratio"),
               ("trajectory", "DOP853 rtol 1e-08", None, None, c, "trajectory_ratio"),
               ("cavity", "100 zones", t3, "cavity_m", c, "cavity_ratio")]
    sources += [("fe", setting, fe_tables[setting], "fe_m", fe_ratios[setting], "fe_ratio") for setting in fe_tables]
    rows = []
    for level, setting, table, column, ratios, ratio in sources:
        cell, n_cells = _cells(table, column) if table is not None else (np.nan, 0)
        points, n_contrasts = _contrasts(ratios, ratio)
        rows.append({"level": level, "setting": setting, "table3_other_noses_mean_abs_rel_dev": cell,
                     "table3_other_noses_cells": n_cells, "contrast_mean_abs_points": points, "contrasts": n_contrasts,
                     "validation_median_abs_rel_err": validation.get((level, setting), np.nan)})
    return pd.DataFrame(rows)


def _fe_setting(timing, profile):
    """The FE setting's name in the timing records ("8 elements across (full)") of a mesh profile."""
    names = [s for s in timing[timing.level == "fe"].setting if s.endswith(f"({profile})")]
    if len(names) != 1:
        raise ValueError(f"figures/timing/accuracy_cost.csv: {len(names)} fe settings of profile {profile!r}; allowed: 1")
    return names[0]


@task
def accuracy_prediction(inputs, outputs, params):
    """Prediction errors of every level at each setting (figures/accuracy_prediction.csv) and the figure of them
    against the wall time per shot (figures/timing/accuracy_cost.png)."""
    timing = pd.read_csv(inputs.timing)
    setting = {p: _fe_setting(timing, p) for p in params.fe_profiles}
    fe_tables = {setting[p]: pd.read_csv(f) for p, f in zip(params.fe_profiles, inputs.fe_tables)}
    fe_ratios = {setting[p]: pd.read_csv(f) for p, f in zip(params.fe_profiles, inputs.fe_ratios)}
    plain = {"analytic": ("analytic", "S stated (Li & Chen)"), "trajectory": ("trajectory", "DOP853 rtol 1e-08"),
             "cavity": ("cavity", "100 zones")}
    validation = {}
    for p, path in zip(params.validation_profiles, inputs.validation):
        v = pd.read_csv(path)
        # each level's out-of-sample error at the calibration users get (laboratory where the level has it)
        for r in users_rows(v).itertuples():
            validation.setdefault(plain.get(r.level, ("fe", setting[p])), r.median_abs_rel_err)
    t = prediction_rows(pd.read_csv(inputs.table3), pd.read_csv(inputs.contrasts), fe_tables, fe_ratios, validation)
    write_csv(t, outputs.csv)
    accuracy_cost_drawing(t.merge(timing, on=["level", "setting"], how="left"), outputs.png, params.dpi)
