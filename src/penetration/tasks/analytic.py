"""Tasks of the analytic stage: Eq 9 calibrations and inferences, Fig 1 shares, validation predictions and figure."""
from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from ..analytic.fits import (calibrate_strength, cell_strength, fit_nstar_and_strength, fit_strength, infer_diameter,
                             resistance_shares as shares)
from ..analytic.resistance import Target, strength_factor
from ..figures.validation import validation_eq9_figure
from ..nose.geometry import Ogive
from ..nose.nstar import nstar
from ..paper import reference
from ..pipeline.io import load_json, read_rows, task, write_csv, write_json, write_rows
from ..shots.fields import eq9_columns, output_fields, row_predictions
from ..studies.laboratory import errors_summary
from .common import PLAIN, scene_from_inputs


@task
def calibrate_do1(inputs, outputs, params):
    """S fitted so that Eq 9 gives the measured DO1 depth (Table 2)."""
    refs = reference.load_reference(inputs.reference)
    sc = scene_from_inputs(inputs, PLAIN)
    nose = sc.noses["double_ogive"]
    depth, vs = refs[params.shot["depth"]].si, refs[params.shot["velocity"]].si
    fit = calibrate_strength(sc.mass, sc.radius, nstar(nose), sc.target.rho, sc.target.fc, vs, depth)
    stated = float(strength_factor(sc.target.fc, "li_chen"))
    write_json({"calibration": "do1", "fitted_quantity": "S, static resistance factor (A of Eq 6; S fc is the static resistance)",
                "data": {"mass": sc.mass, "radius": sc.radius, "nstar": nstar(nose), "rho": sc.target.rho,
                         "fc": sc.target.fc, "vs": vs, "measured_depth": depth,
                         "sources": [refs[params.shot[q]].source for q in ("depth", "velocity")]},
                "model": "Eq 9 (Forrestal crater + tunnel), nose inferred from Table 4",
                "S_stated_li_chen": stated, "S_ratio_to_stated": fit["S"] / stated, **fit}, outputs.json)


@task
def calibrate_table3_calc(inputs, outputs, params):
    """S fitted by least squares to Table 3's 12 calculated DOPs."""
    refs = reference.load_reference(inputs.reference)
    sc = scene_from_inputs(inputs, PLAIN)
    cells = []
    for v in reference.VELOCITIES:
        for n in reference.TABLE3_NOSES:
            ref = refs[f"table3.calc.{v}.{n}"]
            cells.append({"velocity": v, "nose": n, "mass": sc.mass, "radius": sc.radius,
                          "nstar": nstar(sc.noses[n]), "vs": float(v), "depth": ref.si, "id": ref.id})
    fit = fit_strength(cells, sc.target.rho, sc.target.fc)
    for c, r in zip(cells, fit["relative_residuals"]):
        c["relative_residual"] = r
        c["S_fitting_this_cell"] = cell_strength(c, sc.target.rho, sc.target.fc)
    half_unit = 0.5 * 10.0 ** -3  # m: Table 3 prints depths to 1 mm
    rows = []
    for n in reference.TABLE3_NOSES:
        row = fit_nstar_and_strength([c for c in cells if c["nose"] == n], sc.target.rho, sc.target.fc)
        rows.append({"nose": n, "nstar_of_nose": nstar(sc.noses[n]), **row,
                     "fits_within_print": row["max_abs_residual_m"] <= 2 * half_unit})
    write_json({"calibration": "table3_calc", "fitted_quantity": "S (one value for all 12 cells)",
                "model": "Eq 9", "cells": cells, **{k: v for k, v in fit.items() if k != "relative_residuals"},
                "S_per_cell_range": [min(c["S_fitting_this_cell"] for c in cells),
                                     max(c["S_fitting_this_cell"] for c in cells)],
                "row_fits": {"what": "inference: (N*, S) of Eq 9 fitted to each nose's four cells alone; "
                                     "fits_within_print: every residual within twice the half unit of Table 3's "
                                     "printed depths (1 mm)", "rows": rows}},
               outputs.json)


# Table 3's two depth columns: the paper's simulations (LS-DYNA) and its calculations (Eq 9)
TABLE3_COLUMNS = (("sim", "simulation"), ("calc", "calculation"))


@task
def paper_eq9_effective(inputs, outputs, params):
    """Inference on the paper's own numbers: Eq 9's effective (N*, S) per nose through each Table 3 column.

    For each column (simulation, calculation) and nose, (N*, S) fitted by least squares in ln depth to its four
    depths (500-1200 m/s), with Table 3's projectile and target (48 MPa). A frictionless rigid nose changes only
    N* between noses; an effective S that differs between noses says the column's nose effect acts like a change
    of the static resistance. Nothing of ours is compared: this diagnoses the paper's numbers."""
    refs = reference.load_reference(inputs.reference)
    sc = scene_from_inputs(inputs, PLAIN)
    rows = []
    for key, column in TABLE3_COLUMNS:
        fits = {}
        for n in reference.TABLE3_NOSES:
            cells = [{"mass": sc.mass, "radius": sc.radius, "vs": float(v), "depth": refs[f"table3.{key}.{v}.{n}"].si}
                     for v in reference.VELOCITIES]
            fits[n] = fit_nstar_and_strength(cells, sc.target.rho, sc.target.fc, log=True)
        for n, f in fits.items():
            rows.append({"column": column, "nose": n, "nstar_of_nose": nstar(sc.noses[n]), "nstar_effective": f["nstar"],
                         "nstar_effective_over_nose": f["nstar"] / nstar(sc.noses[n]), "S_effective": f["S"],
                         "S_effective_over_crh3": f["S"] / fits["crh3"]["S"],
                         "rms_ln_residual": f["rms_ln_residual"], "max_abs_ln_residual": f["max_abs_ln_residual"],
                         **{f"ln_residual_{v}_ms": r for v, r in zip(reference.VELOCITIES, f["ln_residuals"])}})
    write_csv(pd.DataFrame(rows), outputs.csv)
    for r in rows:
        print(f"{r['column']:11s} {r['nose']:12s} N* {r['nstar_effective']:.4f} (nose {r['nstar_of_nose']:.4f}) "
              f"S {r['S_effective']:.3f} ({r['S_effective_over_crh3']:.3f} of CRH 3's); rms {100 * r['rms_ln_residual']:.2f} %")


@task
def infer_diameter_450kg(inputs, outputs, params):
    """Diameter of the 450 kg projectiles from Fig 9's Pd/d axis ranges."""
    refs = reference.load_reference(inputs.reference)
    sc = scene_from_inputs(inputs, PLAIN, placeholder_diameter=1.0)
    n = nstar(sc.noses[params.nose])
    axes = [(a["velocity"], refs[a["top"]].value - a["tick"], refs[a["top"]].value) for a in params.axes]
    out = infer_diameter(sc.mass, n, sc.target, axes)
    out.update(rule="Pd/d of the deepest nose lies in the top tick interval of each Fig 9 panel",
               nose=params.nose, nstar=n, axes=[{"velocity": v, "lower": lo, "upper": hi} for v, lo, hi in axes],
               model="Eq 9 with the scene's target (S from its stated law)", S=sc.target.S,
               decision="Section 2.2 is the paper's analytic section: Eq 9 with Eq 7's stated S = 72 fc^-0.5 at its "
                        "35 MPa target. The DO1 calibration (48 MPa concrete, Table 3) is an inference about Table 3's "
                        "calculation column; the paper never applies it to Section 2.2, so it is a variant here.")
    cal = load_json(inputs.cal_do1)
    out["variants"] = []
    for label, S in ((f"S calibrated on DO1 as a factor {cal['S_ratio_to_stated']:.4g} on the stated law",
                      sc.target.S * cal["S_ratio_to_stated"]),
                     ("S calibrated on DO1 taken as is (fitted at fc = 48 MPa)", cal["S"])):
        try:
            alt = infer_diameter(sc.mass, n, dataclasses.replace(sc.target, S=S), axes)
        except ValueError as err:  # the axis ranges admit no common diameter with this S
            alt = {"diameter": None, "interval": None, "error": str(err)}
        out["variants"].append({"S_choice": label, "S": S, **alt})
    write_json(out, outputs.json)


@task
def resistance_shares(inputs, outputs, params):
    """Static and inertial shares of Eq 7 against velocity (Fig 1b)."""
    cfg = params.cfg
    n = nstar(Ogive(cfg["psi"], 1.0))
    v = np.linspace(0.0, cfg["v_max"], 151)
    rows = []
    for fc in cfg["strengths"]:
        tg = Target(cfg["rho"], fc, float(strength_factor(fc, cfg["law"])))
        st, ine = shares(n, tg, v)
        rows.append(pd.DataFrame({"fc": fc, "S": tg.S, "nstar": n, "velocity": v, "static_share": st,
                                  "inertial_share": ine}))
    write_csv(pd.concat(rows, ignore_index=True), outputs.csv)


@task
def validation_predictions(inputs, outputs, params):
    """Eq 9 depth of every development shot, S from the configured published law."""
    fields, rows = read_rows(inputs.shots)
    good, problems = row_predictions(rows, eq9_columns(params.law))
    print(f"predicted {len(good)} shots; skipped {len(problems)}")
    for p in problems:
        print(p)
    write_rows(outputs.csv, output_fields(fields), good)


@task
def validation(inputs, outputs, params):
    """Eq 9 on the development shots: each shot's relative error and the figure with its summary."""
    shots = pd.read_csv(inputs.predictions)
    shots["rel_err"] = shots.dop_pred_m / shots.dop_m - 1
    write_csv(shots[["shot_id", "mass_kg", "diameter_m", "nose_shape", "crh", "fc_MPa", "velocity_ms", "dop_m",
                     "dop_pred_m", "rel_err"]], outputs.csv)
    validation_eq9_figure(shots, errors_summary(shots.rel_err), outputs.png, params.dpi, params.law)
