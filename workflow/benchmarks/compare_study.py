"""A user's whole nose study as one command, timed: ``python workflow/benchmarks/compare_study.py``.

Runs ``python -m penetration compare --study workflow/compare/nose_study.yaml`` (four noses including the double
ogive by nose length and the cone, 7 velocities, the analytic, cavity and fe levels at the ci mesh, 2 members) in a
fresh interpreter, from a cold start of the command (the kernels' compilation cache as it is), and prints its wall
time against the 10-minute goal with the machine (CPU model, cores, load average before and after). With
``--record`` it appends a row to figures/timing/compare_study.csv.
"""
from __future__ import annotations

import csv
import datetime
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "src"))

from penetration.pipeline.config import cpu_model  # noqa: E402

GOAL_S = 600.0
STUDY = "workflow/compare/nose_study.yaml"


def main() -> int:
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        res = subprocess.run([sys.executable, "-m", "penetration", "compare", "--study", STUDY, "--out", out],
                             cwd=ROOT, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        rows = list(csv.DictReader(open(Path(out) / "compare.csv"))) if res.returncode == 0 else []
    load1 = os.getloadavg()[0]
    head = res.stderr.splitlines()
    runs = next((line for line in head if line.startswith("compare: ") and "runs" in line), "")
    machine = f"{cpu_model()}, {os.cpu_count()} CPUs"
    print(f"machine: {machine}; load average {load0:.2f} before, {load1:.2f} after")
    print(f"{STUDY}: status {res.returncode}, {runs.removeprefix('compare: ')}, {len(rows)} rows")
    print(f"wall time {wall:.1f} s = {wall / GOAL_S:.2f} of the 10-minute goal")
    if res.returncode != 0:
        print("\n".join(head[-10:]), file=sys.stderr)
    if "--record" in sys.argv:
        path = ROOT / "figures/timing/compare_study.csv"
        new = not path.exists()
        commit = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=ROOT, capture_output=True,
                                text=True).stdout.strip()
        with open(path, "a", newline="") as fh:
            w = csv.writer(fh)
            if new:
                w.writerow(["date", "commit", "machine", "load_before", "load_after", "study", "status", "rows",
                            "wall_time_s", "goal_s"])
            w.writerow([datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"), commit, machine,
                        f"{load0:.2f}", f"{load1:.2f}", STUDY, res.returncode, len(rows), f"{wall:.1f}", f"{GOAL_S:g}"])
    return res.returncode


if __name__ == "__main__":
    sys.exit(main())
