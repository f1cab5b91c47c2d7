"""What a new user waits for: a fresh clone, `make install`, then `make reproduce` (or `make test`), timed.

    python workflow/benchmarks/fresh_clone.py [--target reproduce|test|ci] [--keep DIR]

Clones this repository's HEAD into a temporary folder (or DIR), runs `make install` and then the target in it with
a fresh virtual environment (pip's download cache is the machine's, as for any user), and prints the wall time of
each step, the machine (CPU model, cores, memory) and whether `git status` is clean afterwards (timing files
aside). `--target ci` runs `CI=true bash .ci/run` instead of install + target. The record is appended to
figures/timing/fresh_clone.csv of this checkout (a machine-dependent file), one row per run, with whether uv's
download cache held anything before the install (`install_cache`: warm or cold; a warm cache installs in about a
third of the time), since a new machine starts cold.
"""
from __future__ import annotations

import argparse
import csv
import datetime
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RECORD = ROOT / "figures/timing/fresh_clone.csv"
# files a rebuild may change on another machine: timings, and the report that embeds them
MACHINE_DEPENDENT = ("figures/timing/", "figures/report.html")


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") / 2**30
    return f"{cpu}, {os.cpu_count()} CPUs, {mem:.0f} GiB, Python {platform.python_version()}"


def install_cache(env) -> str:
    """'warm' if uv's download cache (UV_CACHE_DIR, else XDG_CACHE_HOME/uv or ~/.cache/uv) holds anything, else
    'cold'."""
    folder = Path(env.get("UV_CACHE_DIR") or Path(env.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "uv")
    return "warm" if folder.is_dir() and any(folder.iterdir()) else "cold"


def append(record: Path, row: dict) -> None:
    """Append ``row`` to the CSV ``record``, adding any new column to the rows before (empty there); the file is
    rewritten through a temporary file and replaced at once, so that an interruption leaves the old one whole. Not
    penetration.pipeline.io's write_rows: this script runs on the bare python3 that builds the fresh environment, where
    the package's dependencies (pandas, which that module imports) are not installed."""
    rows, fields = [], []
    if record.is_file():
        with open(record, newline="") as fh:
            reader = csv.DictReader(fh)
            fields, rows = list(reader.fieldnames or []), list(reader)
    fields += [k for k in row if k not in fields]
    record.parent.mkdir(parents=True, exist_ok=True)
    tmp = record.with_suffix(".csv.tmp")
    with open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=fields, lineterminator="\n", restval="")
        w.writeheader()
        w.writerows(rows + [row])
    os.replace(tmp, record)


def timed(cmd, cwd, env) -> float:
    print(f"$ {' '.join(cmd)}", flush=True)
    t0 = time.monotonic()
    subprocess.run(cmd, cwd=cwd, env=env, check=True)
    return time.monotonic() - t0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--target", choices=["reproduce", "test", "ci"], default="reproduce")
    p.add_argument("--keep", help="clone into this folder and keep it (default: a temporary folder, removed)")
    args = p.parse_args(argv)
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="penetration-clone-"))
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH")}
    cache = install_cache(env)
    try:
        subprocess.run(["git", "clone", "--quiet", str(ROOT), str(work / "repo")], check=True)
        repo = work / "repo"
        if args.target == "ci":
            install, build = 0.0, timed(["bash", ".ci/run"], repo, {**env, "CI": "true"})
        else:
            install = timed(["make", "install"], repo, env)
            build = timed(["make", args.target], repo, env)
        status = subprocess.run(["git", "status", "--porcelain"], cwd=repo, capture_output=True, text=True).stdout.splitlines()
        changed = [line[3:] for line in status if not line[3:].startswith(MACHINE_DEPENDENT)]
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    row = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"), "commit": commit[:12],
           "target": args.target, "install_s": round(install, 1), "target_s": round(build, 1),
           "total_s": round(install + build, 1), "clean_but_timing": not changed, "machine": machine(),
           "install_cache": cache}
    print(f"fresh clone of {commit[:12]}: install {install / 60:.1f} min, {args.target} {build / 60:.1f} min, "
          f"total {(install + build) / 60:.1f} min on {row['machine']} (uv's cache {cache})")
    print("git status afterwards: " + ("clean (timing files aside)" if not changed else f"changed: {changed}"))
    append(RECORD, row)
    return 0


if __name__ == "__main__":
    sys.exit(main())
