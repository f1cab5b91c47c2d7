"""Fig 9: Pd/d histories of the 450 kg projectiles, with the paper's axis limits."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import load_json, task, write_csv
from .fig08 import panels, s_choice_note


@task
def fig09(inputs, outputs, params):
    hist = pd.read_csv(inputs.histories)
    dop = pd.read_csv(inputs.dop)
    refs = load_reference(inputs.reference)
    d = 2 * dop.drop_duplicates(["nose", "radius_case"]).set_index(["nose", "radius_case"]).radius
    hist["pd_over_d"] = hist.z / [d[(n, c)] for n, c in zip(hist.nose, hist.radius_case)]
    write_csv(hist[["nose", "radius_case", "velocity", "t", "pd_over_d"]], outputs.csv)
    axis = {v: (refs[f"fig09.t_axis_max.{v:.0f}"].value, refs[f"fig09.pd_axis_max.{v:.0f}"].value)
            for v in hist.velocity.unique()}
    panels(hist, dop, "pd_over_d", outputs, params, "Pd/d", "Fig 9", axis, legend_loc="lower right",
           note=s_choice_note(load_json(inputs.diameter)))
