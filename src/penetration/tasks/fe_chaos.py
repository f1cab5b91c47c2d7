"""Tasks of the studies on realisations of the FE chaos (config fe_realisations, `snakemake studies`): the committed
pieces, the erosion-free target's grid study with the chaos in its error model and the inputs the paper does not
state (nose friction on both FE targets, the paper's failure strain as stated)."""
from __future__ import annotations

from ..figures.fe_chaos import chaos_figure
from ..paper.reference import TABLE3_NOSES, VELOCITIES, load_reference
from ..pipeline.io import load_json, task, write_csv, write_json
from ..pipeline.scenes import scene_data, scene_name
from ..studies import chaos
from ..studies.fe_results import CONTRASTS


@task
def fe_realisation_piece(inputs, outputs, params):
    """One piece: the summaries of a cell's noses at one velocity, one member (a committed record the studies read;
    not rebuilt once committed: delete it to recompute it)."""
    if len(inputs.shots) != params.expected:
        raise ValueError(f"piece {params.piece}: {len(inputs.shots)} shots given, {params.expected} expected (a "
                         f"committed piece is a record: delete {outputs.json} to recompute it)")
    write_json({"piece": params.piece, "member": int(params.member), "velocity_step": float(params.velocity_step),
                "shots": [load_json(p) for p in inputs.shots]}, outputs.json)


def paper_values(path):
    """(velocity, quantity) -> the paper's simulated depth (m) of a nose or depth ratio of a contrast (Table 3)."""
    refs = load_reference(path)
    depth = {(float(v), n): refs[f"table3.sim.{v}.{n}"].si for v in VELOCITIES for n in TABLE3_NOSES}
    out = dict(depth)
    for name, (a, b) in CONTRASTS.items():
        for v in VELOCITIES:
            out[(float(v), name)] = depth[(float(v), a)] / depth[(float(v), b)]
    return out


def _pieces(records):
    return [load_json(p["path"]) for p in records]


@task
def fe_erosion_free_chaos(inputs, outputs, params):
    """The grid study with the chaos in its error model (studies.chaos): every realisation, every cell's mean and
    spread, per depth and contrast the estimate at zero size with its uncertainty against the goal, and the figure."""
    missing = [p["path"] for p in params.pieces if p["sha256"] == "missing"]
    if missing:
        raise FileNotFoundError(f"fe_erosion_free_chaos: {len(missing)} pieces missing, e.g. {missing[0]}; build them "
                                "(snakemake -c2 figures/fe/erosion_free/chaos.csv builds them first)")
    shots = chaos.shot_rows(_pieces(params.pieces), params.across)
    cells = chaos.cell_rows(shots, ("scene", "profile", "elements_across", "element_size_m", "velocity_ms"))
    paper = paper_values(inputs.reference)
    rows = chaos.chaos_rows(cells, paper, params.goals, float(params.noise_sigmas),
                            shots[["elements_across", "wall_time_s", "velocity_ms"]], int(params.members))
    write_csv(shots, outputs.shots)
    write_csv(cells, outputs.cells)
    write_csv(rows, outputs.csv)
    holes = sorted({float(s["target"]["pilot_hole"]) for p in _pieces(params.pieces[:1]) for s in p["shots"]})
    chaos_figure(cells, rows, outputs.png, params.dpi, ", pilot hole " + ", ".join(f"{h:g}" for h in holes)
                 + " of the shank radius")


def scene_setting(path):
    """(input, setting) a scene of the unstated-inputs study sets: its failure strain where it states one (a number,
    not calibrated), its lip's ejection scale (a numerical control of the erosion-free target) where it sets one, else
    its nose friction."""
    data = scene_data(path)
    fs = data.get("fe", {}).get("erosion_strain")
    if isinstance(fs, (int, float)):
        return "failure strain", float(fs)
    if "ejection_scale" in data.get("fe", {}):
        return "ejection scale", float(data["fe"]["ejection_scale"])
    return "friction", float(data.get("friction", 0.0))


@task
def fe_unstated_inputs(inputs, outputs, params):
    """Each scene of one target (its baseline first) at one velocity over its realisations: its contrasts and their
    change from the baseline, beside the paper's simulated values."""
    missing = [p["path"] for p in params.pieces if p["sha256"] == "missing"]
    if missing:
        raise FileNotFoundError(f"fe_unstated_inputs: {len(missing)} pieces missing, e.g. {missing[0]}")
    files = {scene_name(p): p for p in inputs.scenes}
    settings = {s: (params.target, *scene_setting(files[s])) for s in params.scenes}
    shots = chaos.shot_rows(_pieces(params.pieces)).assign(target=params.target)
    cells = chaos.cell_rows(shots, ("scene", "profile", "element_size_m", "velocity_ms"))
    rows = chaos.unstated_rows(cells, {params.target: params.scenes[0]}, settings, paper_values(inputs.reference))
    write_csv(shots, outputs.shots)
    write_csv(rows, outputs.csv)
