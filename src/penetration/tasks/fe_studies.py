"""Tasks of the FE level's studies on its result tables (`snakemake studies`): the DO1 calibration per mesh, the
nose contrasts against the mesh, over realisations of the erosion chaos, over bands of meshes and at zero element
size.

Each reads the committed Table 3 files and the shots' and calibrations' records, computes with
``penetration.studies.fe_results``, writes the CSVs and draws them with the drawing functions of ``figures.fe_level`` and
``figures.fe_convergence``.
"""
from __future__ import annotations

import pandas as pd

from ..figures.fe_convergence import contrast_extrapolation_figure
from ..figures.fe_level import (contrast_band_figure, contrast_convergence_figure, contrast_ensemble_figure,
                                mesh_study_figure)
from ..pipeline.io import load_json, task, write_csv
from ..studies import fe_results as fe_studies

CONTRASTS = list(fe_studies.CONTRASTS)


def _meshes(ratios_paths, table_paths, cal_paths):
    """Per mesh: its DO1 calibration, Table 3 and the contrasts of its ratios file, checked to belong to one mesh."""
    meshes = []
    for ratios_path, table_path, cal_path in zip(ratios_paths, table_paths, cal_paths):
        cal, t3 = load_json(cal_path), pd.read_csv(table_path)
        fe_studies.check_one_mesh(cal, t3, table_path, cal_path)
        meshes.append((cal, t3, fe_studies.table3_contrasts(pd.read_csv(ratios_path))))
    return meshes


@task
def fe_mesh_study(inputs, outputs, params):
    """Failure strain calibrated on DO1 at three element sizes: fs, depth, peak deceleration, wall time per size."""
    t = fe_studies.mesh_study_rows([load_json(p) for p in inputs.calibrations])
    write_csv(t, outputs.csv)
    mesh_study_figure(t, outputs.png, params.dpi)


@task
def fe_contrast_convergence(inputs, outputs, params):
    """The FE nose contrasts of Table 3 at several meshes (each with its own DO1 calibration): converged or not,
    beside the interval of the erosion chaos at the mesh of the ensemble (fe_contrast_ensemble)."""
    t = fe_studies.convergence_rows(_meshes(inputs.ratios, inputs.tables, inputs.calibrations))
    write_csv(t, outputs.csv)
    contrast_convergence_figure(t, pd.read_csv(inputs.ensemble), CONTRASTS, outputs.png, params.dpi)


@task
def fe_contrast_ensemble(inputs, outputs, params):
    """Realisations of the erosion chaos at the full mesh: the spread of each Table 3 depth and nose contrast.

    Member 0 is the Table 3 shot; members k >= 1 the same shot struck at
    v (1 + k step). Ratios pair the members of equal k. The interval of a mean
    is Student's t at the configured confidence over the realisations.
    """
    shots = [load_json(p) for p in [*inputs.shots, *inputs.members]]
    paper = {(r.nose, int(r.velocity_ms)): r.paper_sim_m for r in pd.read_csv(inputs.table).itertuples()}
    paper_ratio = {(r.contrast, int(r.velocity_ms)): r.paper_sim_ratio for r in pd.read_csv(inputs.ratios).itertuples()}
    d, t, members = fe_studies.ensemble_tables(shots, paper, paper_ratio, params.confidence)
    write_csv(d, outputs.depths)
    write_csv(t, outputs.csv)
    contrast_ensemble_figure(t, members, CONTRASTS, params.confidence, outputs.png, params.dpi)


@task
def fe_contrast_band(inputs, outputs, params):
    """Mesh realisations of Table 3 at the FE level: bands of meshes around a profile (its element size changed by a
    few per cent), each mesh with the failure strain calibrated on DO1 at its own size.

    Where a nose meets the element rows moves a depth by several per cent between meshes of nearly the same size;
    a band samples that, together with the calibration's own scatter. Per band, cell and contrast: the mean over
    the meshes, its Student-t interval at params.confidence, and the paper's simulated value against both.
    params.bands: (centre profile, number of meshes) per band, in the order of the inputs (centre first).
    """
    meshes = _meshes(inputs.ratios, inputs.tables, inputs.calibrations)
    m, d, t = fe_studies.bands_tables(meshes, params.bands, params.confidence)
    write_csv(m, outputs.meshes)
    write_csv(d, outputs.depths)
    write_csv(t, outputs.csv)
    contrast_band_figure(t, m, [b for b, _ in params.bands], CONTRASTS, params.confidence, outputs.png, params.dpi)


@task
def fe_contrast_extrapolation(inputs, outputs, params):
    """The FE nose contrasts and depths at zero element size: regression over the band meshes, beside the single
    meshes."""
    meshes = pd.read_csv(inputs.meshes)
    singles = pd.read_csv(inputs.singles)
    t = fe_studies.extrapolation_rows(meshes, singles, params.confidence)
    write_csv(t, outputs.csv)
    write_csv(fe_studies.depth_rows([pd.read_csv(f) for f in inputs.tables], params.confidence), outputs.depths)
    contrast_extrapolation_figure(t, meshes, singles, outputs.png, params.dpi)
    for r in t.itertuples():
        print(f"{r.contrast:14s} {r.velocity_ms:5d} m/s: {r.ratio_at_zero_size:.3f} [{r.interval_low:.3f}, "
              f"{r.interval_high:.3f}], scatter {r.scatter_points:.1f} points, paper {r.paper_sim_ratio:.3f}")
