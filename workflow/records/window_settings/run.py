"""DO1 at the default mesh with other moving-window settings, for workflow/records/window_settings.

Usage (from the repository root, after `snakemake -c2 figures/fe/full/window_summary.csv`, which builds the
inferred nose and the calibration it reads):

    python workflow/records/window_settings/run.py AHEAD TAIL [MEMBERS [FIRST]]

AHEAD and TAIL in metres (fe.window_ahead, fe.window_tail) or `none`; members FIRST..FIRST+MEMBERS-1 are struck
at 835 m/s (1 + k 1e-9), as the window study's. Prints one JSON line per shot.
"""
import contextlib
import io
import json
import sys
from types import SimpleNamespace

import yaml

from penetration.tasks.fe import scene_shot

cfg = yaml.safe_load(open("workflow/config.yaml"))
ahead = None if sys.argv[1] == "none" else float(sys.argv[1])
tail = None if sys.argv[2] == "none" else float(sys.argv[2])
members = int(sys.argv[3]) if len(sys.argv) > 3 else 8
first = int(sys.argv[4]) if len(sys.argv) > 4 else 0
inputs = SimpleNamespace(do1="results/geometry/double_ogive_table4.json", fig4="results/geometry/double_ogive_fig4.json",
                         reference=cfg["reference"], cal="results/fe/full/calibration_h0.00875.json",
                         scene="workflow/scenes/fe/do1.yaml", schema="workflow/schemas/scene.schema.json")
shot = SimpleNamespace(cfg={**cfg["fe"], "window_ahead": ahead, "window_tail": tail}, hjc=cfg["concrete"],
                       profile="full", nose="double_ogive", velocity=835.0)
for k in range(first, first + members):
    with contextlib.redirect_stdout(io.StringIO()):
        _, r, _, _ = scene_shot(inputs, shot, 1.0 + k * 1e-9)
    print(json.dumps({"ahead": ahead, "tail": tail, "k": k, "depth": r.depth, "status": r.status,
                      "wall": round(r.wall_time, 1)}), flush=True)
