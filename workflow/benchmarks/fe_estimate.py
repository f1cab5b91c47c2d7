"""The fe level's cost estimate against the measured time: ``python workflow/benchmarks/fe_estimate.py``.

For each shot (the README's example and two more of the development shots' kind, at the default mesh with the
committed DO1 calibration), prints the estimate `python -m penetration dop --model fe` prints before it runs
(fe_level.estimate_cost: elements x steps, an element-step timed by a probe on this machine now), the measured
wall time of the run, and their ratio; the goal is a ratio within a factor of 2 either way. The machine (CPU model,
cores) and the load average are printed beside it: a busy host slows the run and the probe alike.
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "src"))

from penetration.fe.level import estimate_cost  # noqa: E402
from penetration.fe.shot import run_shot  # noqa: E402
from penetration.nose.geometry import Ogive  # noqa: E402
from penetration.pipeline.config import cpu_model  # noqa: E402
from penetration.shots import ladder as L  # noqa: E402
from penetration.shots.records import context_from_pipeline  # noqa: E402

SHOTS = {
    "README example (0.9 kg, 26.9 mm CRH 3, 800 m/s, 35 MPa)": L.UserShot(Ogive(3.0, 0.01345), 0.9, 800.0, 35e6, 2300.0, 0.2424),
    "DZ39-like (0.904 kg, CRH 2, 800 m/s, 32.4 MPa)": L.UserShot(Ogive(2.0, 0.01345), 0.904, 800.0, 32.4e6, 2370.0, 0.2424),
    "76 mm CRH 3, 13 kg at 400 m/s, 50 MPa": L.UserShot(Ogive(3.0, 0.0381), 13.0, 400.0, 50e6, 2300.0, 0.53),
}


def machine():
    return f"{cpu_model()}, {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}"


def main() -> int:
    ctx = context_from_pipeline(ROOT, "full")
    print(f"machine: {machine()}")
    print(f"{'shot':55s} {'estimate s':>10s} {'measured s':>10s} {'ratio':>6s}")
    for name, shot in SHOTS.items():
        spec, _ = L.fe_spec(shot, ctx)
        est = estimate_cost(spec)
        t0 = time.perf_counter()
        r = run_shot(spec)
        wall = time.perf_counter() - t0
        print(f"{name:55s} {est.seconds:10.1f} {wall:10.1f} {est.seconds / wall:6.2f}   "
              f"({r.elements} elements, {r.steps} steps; estimated {est.steps})", flush=True)
    print(f"after: {machine()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
