"""A Table 3 shot at the FE level on a mesh of another element size, the failure strain held fixed, for
workflow/records/mesh_alignment.

Usage (from the repository root, after `snakemake -c2 figures/fe/full/table3.csv`, which builds the inferred
nose and the calibration):

    python workflow/records/mesh_alignment/run.py NOSE VELOCITY ACROSS [FS]

NOSE: a nose of workflow/scenes/fe/table3.yaml; VELOCITY in m/s; ACROSS: elements across the 70 mm shank
radius (element size 0.07/ACROSS m, every other setting the full profile's); FS: the failure strain (default:
the full profile's calibration). Prints one JSON line.
"""
import contextlib
import io
import json
import sys
from types import SimpleNamespace

import yaml

from penetration.concrete import material as concrete
from penetration.fe.shot import RunSpec, Settings, TargetSpec, run_shot
from penetration.paper import reference
from penetration.pipeline.io import load_json
from penetration.shots.fields import expected_depth
from penetration.tasks.common import scene_from_inputs

cfg = yaml.safe_load(open("workflow/config.yaml"))
nose_name, v, across = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
fs = float(sys.argv[4]) if len(sys.argv) > 4 else load_json("results/fe/full/calibration_h0.00875.json")["fs"]
inputs = SimpleNamespace(do1="results/geometry/double_ogive_table4.json", fig4="results/geometry/double_ogive_fig4.json",
                         reference=cfg["reference"], scene="workflow/scenes/fe/table3.yaml",
                         schema="workflow/schemas/scene.schema.json")
refs = reference.load_reference(inputs.reference)
sc = scene_from_inputs(inputs, ("fe",))
nose = sc.noses[nose_name]
material = concrete.configured(refs, cfg["concrete"], **concrete.material_switches(sc.effects, sc.material, cfg["concrete"]))
settings = Settings.from_config(cfg["fe"], "full", nose.radius / across).with_failure_strain(fs)
with contextlib.redirect_stdout(io.StringIO()):
    r = run_shot(RunSpec(nose, sc.mass, v, material, settings,
                         TargetSpec.from_scene(sc.fe, cfg["fe"]["target_radius"], cfg["fe"]["block_depth"]),
                         expected_depth(nose, sc.mass, v, sc.target.fc, sc.target.rho), sc.friction))
print(json.dumps({"nose": nose_name, "velocity_ms": v, "elements_across_radius": across,
                  "element_size_m": settings.element_size, "failure_strain": fs, "depth_m": r.depth, "status": r.status,
                  "wall_time_s": round(r.wall_time, 1)}), flush=True)
