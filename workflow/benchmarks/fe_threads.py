"""One shot on two threads, or two shots side by side on one thread each: which does more per hour on this machine.

    python workflow/benchmarks/fe_threads.py [--shot results/fe/full/do1/double_ogive_835.json] [--record CSV]

Reruns the pipeline's DO1 shot (its element size, calibrated failure strain and mesh; `snakemake -c2
results/fe/full/do1/double_ogive_835.json` builds it) in fresh processes, each with NUMBA_NUM_THREADS set before
numba is imported: on two threads alone, on one thread alone, then two one-thread copies at once. Prints each
solver's wall time (the shot's own clock: mesh built, kernels loaded from numba's cache, output not written), checks
every depth against the pipeline's bit for bit, and the throughput of the side-by-side pair as a ratio to two
two-thread shots run one after the other (> 1: the pipeline's single-shot FE jobs should take one thread each).
Records the machine and the figures to CSV when asked (figures/timing/fe_threads.csv).
"""
from __future__ import annotations

import argparse
import csv
import datetime
import json
import os
import subprocess
import sys
import time
from pathlib import Path

from fe_speed import DO1
from nstar_speed import machine

CHILD = r"""
import json, sys
sys.path.insert(0, "workflow/benchmarks")
from fe_speed import do1_spec
from penetration.fe.shot import run_shot
spec, ref = do1_spec(sys.argv[1])
r = run_shot(spec)
print("RESULT " + json.dumps({"depth": r.depth, "wall": r.wall_time, "same": r.depth == ref["depth_m"]}))
"""

def launch(shot: str, threads: int) -> subprocess.Popen:
    env = dict(os.environ, NUMBA_NUM_THREADS=str(threads))
    return subprocess.Popen([sys.executable, "-c", CHILD, shot], env=env, stdout=subprocess.PIPE, text=True)


def result(proc: subprocess.Popen) -> dict:
    out, _ = proc.communicate()
    if proc.returncode != 0:
        raise SystemExit(f"the shot's process failed (exit {proc.returncode})")
    return json.loads(next(line[7:] for line in out.splitlines() if line.startswith("RESULT ")))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shot", default=DO1, help="a shot record of the fe level at the default mesh (default: DO1)")
    ap.add_argument("--record", help="append the figures to this CSV (figures/timing/fe_threads.csv)")
    args = ap.parse_args(argv)
    if not Path(args.shot).exists():
        raise SystemExit(f"--shot {args.shot} does not exist: `snakemake -c2 {args.shot}` builds it")
    print(f"machine: {machine()}")
    runs = {}
    for label, threads in (("two threads alone", 2), ("one thread alone", 1)):
        t0 = time.monotonic()
        r = result(launch(args.shot, threads))
        runs[label] = r | {"process": time.monotonic() - t0}
        same = "the pipeline's bit for bit" if r["same"] else "DIFFERENT from the pipeline"
        print(f"{label}: solver {r['wall']:.1f} s, process {runs[label]['process']:.1f} s, depth {r['depth']!r} m ({same})")
    t0 = time.monotonic()
    pair = [launch(args.shot, 1), launch(args.shot, 1)]
    rs = [result(p) for p in pair]
    together = time.monotonic() - t0
    for i, r in enumerate(rs):
        print(f"one thread, side by side ({i + 1} of 2): solver {r['wall']:.1f} s, depth {r['depth']!r} m "
              f"({'same' if r['same'] else 'DIFFERENT'})")
    two, one = runs["two threads alone"], runs["one thread alone"]
    speedup = one["wall"] / two["wall"]
    slowdown = max(r["wall"] for r in rs) / one["wall"]
    gain = 2 * two["process"] / together
    print(f"two threads run a shot {speedup:.2f} x as fast as one; side by side, each one-thread shot takes "
          f"{slowdown:.2f} x its time alone; two shots side by side finish in {together:.1f} s against "
          f"{2 * two['process']:.1f} s one after the other on two threads: {gain:.2f} x the throughput")
    if not all(r["same"] for r in [two, one, *rs]):
        print("a depth differs from the pipeline's: the thread count changed a result")
        return 1
    if args.record:
        path = Path(args.record)
        new = not path.exists()
        with path.open("a", newline="") as fh:
            w = csv.writer(fh)
            if new:
                w.writerow(["date", "machine", "shot", "solver_two_threads_s", "solver_one_thread_s", "speedup_two_threads",
                            "side_by_side_slowdown", "pair_wall_s", "sequential_two_thread_wall_s", "throughput_ratio"])
            w.writerow([datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"), machine(), args.shot,
                        f"{two['wall']:.2f}", f"{one['wall']:.2f}", f"{speedup:.3f}", f"{slowdown:.3f}", f"{together:.2f}",
                        f"{2 * two['process']:.2f}", f"{gain:.3f}"])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
