"""DO1 at the FE level with the moving window or the target's radius changed, for workflow/records/damage_bands:
where do the periodic bands of damage in figures/fe/full/do1_fields.png come from?

Usage (from the repository root, after `snakemake -c2 results/fe/full/do1/double_ogive_835.json`, which builds the
inferred nose and the calibration):

    python workflow/records/damage_bands/run.py NAME WINDOW_AHEAD RADIUS [ACROSS FS]

WINDOW_AHEAD: m computed ahead of the tip ("none": the whole domain); RADIUS: the semi-infinite target's radius (m);
ACROSS, FS: elements across the 70 mm shank radius and the failure strain (default: the full profile's 8 and its
calibration). Every other setting is the full profile's. Writes NAME_fields.csv (damage at the initial element centres) and
NAME_histories.csv beside this file and prints one JSON line.
"""
import contextlib
import dataclasses
import io
import json
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import yaml

from penetration.concrete import material as concrete
from penetration.fe import state as fe_state
from penetration.fe.shot import RunSpec, Settings, TargetSpec, run_shot
from penetration.paper import reference
from penetration.pipeline.io import load_json
from penetration.shots.fields import expected_depth
from penetration.tasks.common import scene_from_inputs

HERE = Path(__file__).parent
cfg = yaml.safe_load(open("workflow/config.yaml"))
name, ahead, radius = sys.argv[1], sys.argv[2], float(sys.argv[3])
inputs = SimpleNamespace(do1="results/geometry/double_ogive_table4.json", fig4="results/geometry/double_ogive_fig4.json",
                         reference=cfg["reference"], scene="workflow/scenes/fe/do1.yaml",
                         schema="workflow/schemas/scene.schema.json")
refs = reference.load_reference(inputs.reference)
sc = scene_from_inputs(inputs, ("fe",))
nose = sc.noses["double_ogive"]
material = concrete.configured(refs, cfg["concrete"], **concrete.material_switches(sc.effects, sc.material, cfg["concrete"]))
across = float(sys.argv[4]) if len(sys.argv) > 4 else 8.0
fs = float(sys.argv[5]) if len(sys.argv) > 5 else load_json("results/fe/full/calibration_h0.00875.json")["fs"]
settings = Settings.from_config(cfg["fe"], "full", nose.radius / across).with_failure_strain(fs)
settings = dataclasses.replace(settings, window_ahead=None if ahead == "none" else float(ahead))
v = 835.0
with contextlib.redirect_stdout(io.StringIO()):
    r = run_shot(RunSpec(nose, sc.mass, v, material, settings, TargetSpec("semi_infinite", radius),
                         expected_depth(nose, sc.mass, v, sc.target.fc, sc.target.rho), sc.friction), keep_model=True)
m = r.model
g = m.grid
conn = g.connectivity()
fields = pd.DataFrame({"r0": g.R.ravel()[conn].mean(axis=1), "z0": g.Z.ravel()[conn].mean(axis=1),
                       "damage": m.E[fe_state.DMG], "state": m.alive})
fields = fields[(fields.r0 < 0.6) & (fields.z0 < r.depth + 0.5)]
fields.to_csv(HERE / f"{name}_fields.csv.gz", index=False, float_format="%.6g")
h = r.histories
pd.DataFrame({"t": h["t"], "depth": h["depth"], "velocity": h["velocity"]}).iloc[::20].to_csv(
    HERE / f"{name}_histories.csv.gz", index=False, float_format="%.6g")
print(json.dumps({"name": name, "window_ahead_m": ahead, "target_radius_m": radius, "elements_across_radius": across,
                  "failure_strain": fs, "depth_m": r.depth,
                  "status": r.status, "wall_time_s": round(r.wall_time, 1)}), flush=True)
