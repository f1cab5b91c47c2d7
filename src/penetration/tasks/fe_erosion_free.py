"""Task of the erosion-free target's grid-convergence study (`snakemake studies`): Table 3's rows on meshes refined by
one constant ratio at pilot holes halved in turn; per hole, depth and contrast the observed order, Richardson
extrapolation and GCI, the same over the holes to zero hole (``grid_study``), what each mesh cost, and the
figure; and the quasi-static check of the target (``fe.quasi_static``): the steady force of a slowly driven ogive
against the cavity stresses, under mesh refinement."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..figures.fe_convergence import grid_convergence_figure
from ..paper.reference import TABLE3_NOSES, VELOCITIES, load_reference
from ..pipeline.io import load_json, task, write_csv, write_json
from ..studies import grid as grid_study
from ..studies.mesh_convergence import grid_refinement
from .common import calibration_row


@task
def fe_erosion_free_piece(inputs, outputs, params):
    """One piece of the study: the summaries of its shots (one scene at one mesh profile, or the eroding level's
    Table 3 at its default mesh), a committed record the convergence reads. A committed piece is not rebuilt: the rule then has no
    shots, and forcing it is refused (delete the piece to recompute it)."""
    if len(inputs.shots) != params.expected:
        raise ValueError(f"piece {params.piece}: {len(inputs.shots)} shots given, {params.expected} expected (a "
                         f"committed piece is a record: delete {outputs.json} to recompute it)")
    write_json({"piece": params.piece, "shots": [load_json(p) for p in inputs.shots]}, outputs.json)


@task
def fe_erosion_free_convergence(inputs, outputs, params):
    """The study's tables (convergence per depth and contrast, each shot, each mesh's cost) and its figure, from every
    piece (``params.pieces``, ``params.eroding``: path and digest; the inputs are only the pieces built in this run)."""
    refs = load_reference(inputs.reference)
    paper = {(float(v), n): refs[f"table3.sim.{v}.{n}"].si for v in VELOCITIES for n in TABLE3_NOSES}
    shots = grid_study.shot_rows([s for p in params.pieces for s in load_json(p["path"])["shots"]], params.across)
    conv = grid_study.convergence_rows(shots, paper, params.goal_depth, params.goal_contrast)
    write_csv(shots, outputs.depths)
    write_csv(conv, outputs.csv)
    holes = grid_study.hole_rows(conv, params.goal_depth, params.goal_contrast)
    write_csv(holes, outputs.holes)
    eroding = [s for s in load_json(params.eroding["path"])["shots"] if float(s["velocity"]) in set(shots.velocity_ms)]
    write_csv(grid_study.cost_rows(shots, eroding, params.eroding_across), outputs.cost)
    grid_convergence_figure(conv, holes, outputs.png, params.dpi)


@task
def fe_erosion_free_calibrated(inputs, outputs, params):
    """The erosion-free Table 3 shots with the DO1 strength scale (a calibration) beside the same shots on the same
    mesh and target with Table 1's HJC as stated, and the paper's simulated depths; and the calibration's row (its
    fitted quantity, data and residual)."""
    refs = load_reference(inputs.reference)
    cal = load_json(inputs.cal)
    stated = {(s["nose"], float(s["velocity"])): s for s in map(load_json, inputs.stated)}
    rows = []
    for shot in map(load_json, inputs.shots):
        key = (shot["nose"], float(shot["velocity"]))
        if key not in stated:
            raise ValueError(f"calibrated shot {key} has no shot with the stated HJC among {sorted(stated)}")
        base = stated[key]
        for a, b, name in ((shot, cal, "element_size"), (shot["target"], base["target"], "pilot_hole"),
                           (shot["target"], base["target"], "formulation")):
            if a[name] != b[name]:
                raise ValueError(f"calibrated shot {key}: {name} {a[name]} differs from {b[name]} (stated HJC or "
                                 f"calibration): the depths would not compare one change")
        paper = refs[f"table3.sim.{int(key[1])}.{key[0]}"].si
        rows.append({"nose": key[0], "velocity_ms": key[1], "elements_across_radius": cal["elements_across_radius"],
                     "pilot_hole": shot["target"]["pilot_hole"], "strength_scale": shot["strength_scale"],
                     "depth_stated_hjc_m": base["depth_m"], "depth_calibrated_m": shot["depth_m"],
                     "paper_depth_m": paper, "stated_over_paper": base["depth_m"] / paper,
                     "calibrated_over_paper": shot["depth_m"] / paper, "status": shot["status"],
                     "energy_error_max": shot["energy_error_max"]})
    write_csv(pd.DataFrame(rows).sort_values(["velocity_ms", "nose"], ignore_index=True), outputs.csv)
    row = calibration_row(cal, "strength_scale", "results/fe/" + "/".join(str(inputs.cal).split("/")[-3:]))
    write_csv(pd.DataFrame([{**row, "elements_across_radius": cal["elements_across_radius"],
                             "pilot_hole": cal["data"]["target"]["pilot_hole"], "converged": cal["converged"],
                             "trials": len(cal["runs"])}]), outputs.calibration)


@task
def fe_quasi_static_run(inputs, outputs, params):
    """One driven run of the quasi-static check (its mesh and hole from the wildcards)."""
    from ..fe.verification.quasi_static import driven_force

    write_json(driven_force(float(params.across), float(params.hole), float(params.velocity), guide=bool(params.guide)),
               outputs.json)


@task
def fe_quasi_static(inputs, outputs, params):
    """Per hole: the force over pi a^2 on each mesh (coarse first), its grid refinement (observed order, Richardson,
    GCI), the cavity stresses it is set against and whether the refined force lies within the band set beforehand
    (``params.band``, relative) of the cavity level's sigma_n."""
    from ..fe.verification.quasi_static import references

    runs = pd.DataFrame([load_json(p) for p in inputs.runs]).sort_values(["pilot_hole", "elements_across"],
                                                                           ascending=[False, True], ignore_index=True)
    rows = []
    for hole, g in runs.groupby("pilot_hole", sort=False):
        ref = references(float(hole), float(params.velocity))
        across = g.elements_across.to_numpy()
        ratio = grid_study.refinement_ratio(across)
        sigma = ref["cavity_level_sigma_n_pa"]
        ran = g[g.status != "stopped"]
        # the refinement needs the finest meshes' runs: the finished meshes up to the first that stopped
        upto = int(np.argmax((g.status == "stopped").to_numpy())) if (g.status == "stopped").any() else len(g)
        if upto >= 3:
            r = grid_refinement(g.force_over_area_pa.to_numpy()[:upto], ratio)
            order, status, ext, gci = r.order, r.status, r.extrapolated, r.gci_fine_relative
        else:
            order, status, ext, gci = np.nan, f"incomplete: {upto} meshes ran before one stopped", np.nan, np.nan
        fine = float(ran.force_over_area_pa.iloc[-1]) if len(ran) else np.nan
        # the finest three meshes that ran: only a sequence in the asymptotic range is judged on its extrapolation;
        # an oscillating or a not-asymptotic one (its Richardson value is no estimate) on the range of those three
        # (Celik et al. 2008)
        last3 = g.force_over_area_pa.to_numpy()[:upto][-3:] if upto >= 3 else np.array([np.nan])
        low, high = (ext, ext) if status == "asymptotic" else (float(last3.min()), float(last3.max()))
        rows.append({"pilot_hole": hole, "pilot_guide": bool(g.pilot_guide.all()), "velocity_ms": float(params.velocity),
                     **{f"force_over_area_at_{n:g}_across_pa": x for n, x in zip(across, g.force_over_area_pa)},
                     "meshes_stopped": int((g.status == "stopped").sum()), "observed_order": order, "status": status,
                     "extrapolated_pa": ext, "gci_fine_relative": gci, **ref,
                     "finest_run_over_cavity_level": fine / sigma, "extrapolated_over_cavity_level": ext / sigma,
                     "judged_low_pa": low, "judged_high_pa": high, "band": float(params.band),
                     "within_band": bool(abs(low / sigma - 1.0) <= params.band and abs(high / sigma - 1.0) <= params.band),
                     "eroded_mass_kg": float(g.eroded_mass_kg.max())})
    write_csv(runs, outputs.runs)
    write_csv(pd.DataFrame(rows), outputs.csv)
