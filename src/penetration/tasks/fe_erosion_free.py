"""Task of the erosion-free target's grid-convergence study (`snakemake studies`): Table 3's rows on meshes refined by
one constant ratio at pilot holes halved in turn; per hole, depth and contrast the observed order, Richardson
extrapolation and GCI, the same over the holes to zero hole (``grid_study``), what each mesh cost, and the
figure."""
from __future__ import annotations

from .. import grid_study
from ..figures.fe_convergence import grid_convergence_figure
from ..io import load_json, task, write_csv
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
