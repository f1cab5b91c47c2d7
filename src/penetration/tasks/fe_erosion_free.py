"""Task of the erosion-free target's grid-convergence study (`snakemake studies`): Table 3's rows on meshes refined by
one constant ratio at pilot holes halved in turn; per hole, depth and contrast the observed order, Richardson
extrapolation and GCI, the same over the holes to zero hole (``grid_study``), what each mesh cost, and the
figure; and the quasi-static check of the target (``fe.quasi_static``): the steady force of a slowly driven ogive
against the cavity stresses, under mesh refinement."""
from __future__ import annotations

import numpy as np
import pandas as pd

from .. import grid_study
from ..mesh_convergence import grid_refinement
from ..figures.fe_convergence import grid_convergence_figure
from ..io import load_json, task, write_csv, write_json
from ..reference import TABLE3_NOSES, VELOCITIES, load_reference


@task
def fe_erosion_free_convergence(inputs, outputs, params):
    """The study's tables (convergence per depth and contrast, each shot, each mesh's cost) and its figure."""
    refs = load_reference(inputs.reference)
    paper = {(float(v), n): refs[f"table3.sim.{v}.{n}"].si for v in VELOCITIES for n in TABLE3_NOSES}
    shots = grid_study.shot_rows([load_json(p) for p in inputs.shots], params.across)
    conv = grid_study.convergence_rows(shots, paper, params.goal_depth, params.goal_contrast)
    write_csv(shots, outputs.depths)
    write_csv(conv, outputs.csv)
    holes = grid_study.hole_rows(conv, params.goal_depth, params.goal_contrast)
    write_csv(holes, outputs.holes)
    write_csv(grid_study.cost_rows(shots), outputs.cost)
    grid_convergence_figure(conv, holes, outputs.png, params.dpi)


@task
def fe_quasi_static_run(inputs, outputs, params):
    """One driven run of the quasi-static check (its mesh and hole from the wildcards)."""
    from ..fe.quasi_static import driven_force

    write_json(driven_force(float(params.across), float(params.hole), float(params.velocity)), outputs.json)


@task
def fe_quasi_static(inputs, outputs, params):
    """Per hole: the force over pi a^2 on each mesh (coarse first), its grid refinement (observed order, Richardson,
    GCI), the cavity stresses it is set against and whether the refined force lies within the band set beforehand
    (``params.band``, relative) of the cavity level's sigma_n."""
    from ..fe.quasi_static import references

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
        # the finest three meshes that ran: an oscillating sequence is judged on its whole range, not on an
        # extrapolation (Celik et al. 2008)
        last3 = g.force_over_area_pa.to_numpy()[:upto][-3:] if upto >= 3 else np.array([np.nan])
        low, high = (float(last3.min()), float(last3.max())) if status == "oscillatory" else (ext, ext)
        rows.append({"pilot_hole": hole, "velocity_ms": float(params.velocity),
                     **{f"force_over_area_at_{n:g}_across_pa": x for n, x in zip(across, g.force_over_area_pa)},
                     "meshes_stopped": int((g.status == "stopped").sum()), "observed_order": order, "status": status,
                     "extrapolated_pa": ext, "gci_fine_relative": gci, **ref,
                     "finest_run_over_cavity_level": fine / sigma, "extrapolated_over_cavity_level": ext / sigma,
                     "judged_low_pa": low, "judged_high_pa": high, "band": float(params.band),
                     "within_band": bool(abs(low / sigma - 1.0) <= params.band and abs(high / sigma - 1.0) <= params.band),
                     "eroded_mass_kg": float(g.eroded_mass_kg.max())})
    write_csv(runs, outputs.runs)
    write_csv(pd.DataFrame(rows), outputs.csv)
