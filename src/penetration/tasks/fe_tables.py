"""Tasks of the FE level's tables (rule all): Table 3 and its contrasts, the contrasts over Fig 15's sweep, the audit
summary and the FE rows of the diff.

Each reads the per-shot summaries of ``tasks.fe`` and the committed tables, computes with ``penetration.studies.fe_results``
and ``penetration.paper.diff``, and writes under figures/fe/{profile}/.
"""
from __future__ import annotations

import pandas as pd

from ..figures.fe_level import contrasts_figure, shots_frame
from ..paper import diff as D
from ..paper.reference import TABLE3_NOSES, VELOCITIES, load_reference
from ..pipeline.io import committed_study, load_json, task, write_csv, write_json, write_text
from ..pipeline.scenes import scene_data
from ..studies import fe_results as fe_studies


def _paper_table3(refs):
    """(velocity, nose) -> the paper's simulated Table 3 depth (m)."""
    return {(v, n): refs[f"table3.sim.{v}.{n}"].si for v in VELOCITIES for n in TABLE3_NOSES}


@task
def fe_table3(inputs, outputs, params):
    """Table 3 at the FE level: depth per cell, deviation from the paper's simulation, the nose ratios.

    Each cell carries its distance from the DO1 calibration (inputs.cal): whether its nose is the calibration
    shot's (the scene's nose inferred as the shot's) and its velocity minus the shot's. A cell of the calibrated
    nose near the shot's velocity agrees largely by construction.
    """
    refs = load_reference(inputs.reference)
    shots = shots_frame(inputs.shots)
    cal = load_json(inputs.cal)["data"]
    noses = scene_data(inputs.scene)["noses"]   # the scene with the paper's case it extends
    calibrated = {n for n, spec in noses.items() if spec.get("inferred") == cal["nose"]}
    t = fe_studies.table3_rows(shots, _paper_table3(refs), calibrated, cal["vs"])
    write_csv(t, outputs.csv)
    write_csv(fe_studies.table3_ratios(t), outputs.ratios)


@task
def fe_contrasts(inputs, outputs, params):
    """Nose contrasts at the FE level over Fig 15's sweep: depth ratios and gains of each pair of noses."""
    t = fe_studies.sweep_contrasts(shots_frame(inputs.shots))
    write_csv(t, outputs.csv)
    refs = load_reference(inputs.reference)
    contrasts_figure(t, fe_studies.paper_sweep_contrasts(_paper_table3(refs)), refs, outputs.png, params.dpi)


@task
def fe_summary(inputs, outputs, params):
    """Audit and checks over every FE shot of a profile: energy errors, hourglass share, nose pressure, rear face;
    the DO1 shot's wall time goes to a timing file of its own (it changes from run to run, the summary does not)."""
    shots = shots_frame(inputs.shots)
    do1, block = load_json(inputs.do1), load_json(inputs.block)
    cal = load_json(inputs.cal)
    out = {"profile": params.profile, "element_size_m": cal["element_size"], "failure_strain": cal["fs"],
           "calibration_residual_m": cal["residual_m"], "shots": int(len(shots)),
           "energy_error_max": float(shots.energy_error_max.abs().max()),
           "hourglass_over_internal_max": float(shots.hourglass_over_internal.max()),
           "momentum_error_max": float(shots.momentum_error_final.abs().max()),
           "nose_pressure": load_json(inputs.pressure),
           "do1_depth_semi_infinite_m": do1["depth_m"], "do1_depth_block_m": block["depth_m"],
           "rear_face_effect_m": block["depth_m"] - do1["depth_m"],
           "do1_eroded_mass_kg": do1["eroded_mass_kg"], "do1_tunnel_eroded_share": do1["tunnel_eroded_share"],
           "do1_element_steps": do1["element_steps"],
           "do1_status": do1["status"], "block_status": block["status"]}
    write_json(out, outputs.json)
    # (no time per element-step: element_steps counts every element of the mesh at every step, and the moving
    # window computes only those near the nose; workflow/benchmarks/fe_speed.py times the step itself)
    write_json({"profile": params.profile, "element_size_m": cal["element_size"], "do1_wall_time_s": do1["wall_time_s"],
                "do1_steps": do1["steps"], "do1_mesh_elements": do1["elements"]}, outputs.timing)


@task
def fe_diff(inputs, outputs, params):
    """The FE level's rows of the diff (Table 3 cells and increments, 1200 m/s gains, Fig 14, DO1, fs) and a summary."""
    refs = load_reference(inputs.reference)
    t3 = pd.read_csv(inputs.table3).to_dict("records")
    ratios = pd.read_csv(inputs.ratios).to_dict("records")
    do1, cal = load_json(inputs.do1), load_json(inputs.cal)
    rows = D.fe_rows(refs, t3, ratios, do1["depth_m"], cal["fs"], cal["element_size"])
    rows += D.fe_limit_rows(refs, committed_study(params.limit).to_dict("records"))
    frame = pd.DataFrame([r.__dict__ for r in rows], columns=list(D.COLUMNS))
    write_csv(frame, outputs.csv)
    counts = ", ".join(f"{s} {int((frame.status == s).sum())}" for s in D.STATUSES)
    lines = [f"# FE level ({params.profile} profile, h = {cal['element_size'] * 1e3:.3g} mm, fs = {cal['fs']:.4g} "
             f"calibrated on DO1)", "", f"Status counts: {counts}", "",
             "| item | quantity | case | paper | ours | status |", "|---|---|---|---|---|---|"]
    lines += [f"| {r.item} | {r.quantity} | {r.case} | {r.paper:.4g} | {r.ours:.4g} | {r.status} |" for r in rows]
    write_text(outputs.summary, "\n".join(lines) + "\n")
