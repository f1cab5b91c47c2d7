"""Tasks of the geometry stage: inferred double ogives, N* of the study's noses, Fig 3 bands."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd

from ..nose import inference
from ..nose.geometry import Cone, MinimumNstar, Ogive
from ..nose.nstar import cumulative_nstar, nstar, shape_rate
from ..paper import reference
from ..pipeline.io import nose_record, read_inference, task, write_csv, write_json
from .common import projectile


def _write_inference(result, out_json, out_family):
    family = pd.DataFrame(result.pop("family"))
    result["nose"] = nose_record(result["nose"])
    result["family_summary"] = {c: [float(family[c].min()), float(family[c].max())]
                                for c in ("nstar", "volume", "mass", "S1", "a1", "a2", "region2_length") if c in family}
    write_csv(family, out_family)
    write_json(result, out_json)


@task
def infer_fig4_design(inputs, outputs, params):
    rule = inference.Fig4Rule(**params.cfg)
    result = inference.infer_fig4(rule)
    result["described"] = inference.describe(result["nose"])
    _write_inference(result, outputs.json, outputs.family)


@task
def infer_table4_do1(inputs, outputs, params):
    cfg = params.cfg
    refs = reference.load_reference(inputs.reference)
    density, radius = projectile(refs, params.projectile)
    targets = {k: refs[cfg[k]] for k in ("nstar_target", "mass_target")}
    rule = inference.Table4Rule(radius=radius, density=density, psi_base=cfg["psi_base"],
                                psi_length=cfg["psi_length"], nstar_target=targets["nstar_target"].si,
                                mass_target=targets["mass_target"].si, middle_fraction=cfg["middle_fraction"],
                                family_points=cfg["family_points"])
    result = inference.infer_table4(rule)
    result["inference_inputs"] = {k: {"id": r.id, "value": r.value, "unit": r.unit, "source": r.source}
                                  for k, r in targets.items()}
    result["described"] = inference.describe(result["nose"], density)
    _write_inference(result, outputs.json, outputs.family)


def study_noses(fig4, do1, radius, psi_length):
    """The noses every geometry figure and Table 4 draw on, by name."""
    length = Ogive(psi_length, radius).length
    return {
        "fig4_crh3": Ogive(3.0, 1.0), "fig4_crh5": Ogive(5.0, 1.0), "fig4_double_ogive": fig4,
        "cone": Cone(radius, length), "minimum_nstar": MinimumNstar(radius, length),
        "double_ogive": do1, "crh45": Ogive(psi_length, radius), "crh3": Ogive(3.0, radius),
    }


@task
def geometry(inputs, outputs, params):
    """N*, sizes and cumulative N* curves of the study's noses; Fig 3 bands."""
    density, radius = projectile(reference.load_reference(inputs.reference), params.projectile)
    noses = study_noses(read_inference(inputs.fig4)["nose"], read_inference(inputs.do1)["nose"], radius,
                        params.table4["psi_length"])
    rows, curves = [], []
    for name, nose in noses.items():
        shape_only = name.startswith("fig4_")
        rows.append({"name": name, "kind": nose.kind, "radius": nose.radius, "length": nose.length,
                     "nstar": nstar(nose), "volume": nose.volume(),
                     "mass": np.nan if shape_only else nose.mass(density),
                     "params": json.dumps(nose_record(nose)["params"], sort_keys=True)})
        x, y, cum = cumulative_nstar(nose, params.points)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            k = shape_rate(nose, x)
        k[~np.isfinite(k)] = np.nan  # where y' is infinite (hemisphere tip)
        curves.append(pd.DataFrame({"name": name, "x": x, "y": y, "nstar_cum": cum, "k": k}))
    write_csv(pd.DataFrame(rows), outputs.noses)
    write_csv(pd.concat(curves, ignore_index=True), outputs.curves)
    crh3 = noses["fig4_crh3"]
    bands = []
    for conv in inference.K_CONVENTIONS:
        lo, hi, px, pk = inference.k_band(crh3, params.fig4["threshold"], conv)
        bands.append({"convention": conv, "adopted": conv == params.fig4["convention"], "peak_x_over_b": px,
                      "peak_k": pk, "lo": lo, "hi": hi, "width": None if lo is None else hi - lo})
    write_csv(pd.DataFrame(bands), outputs.bands)
