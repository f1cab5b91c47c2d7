import math
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

if os.environ.get("PYTEST_XDIST_WORKER"):
    # `make test` runs one worker per core (pytest-xdist): each worker's parallel kernels then run on one thread,
    # or two workers' thread pools would share the two cores four ways. A test may still ask for more
    # (numba.set_num_threads up to NUMBA_NUM_THREADS, the machine's cores).
    import numba

    numba.set_num_threads(1)


def committed(path):
    """Text of ``path`` (relative to the repository) as committed at git HEAD: tests of the committed outputs read
    these, never the working tree's copies, which an interrupted rebuild may have replaced. Falls back to the file
    where the tree is not a git checkout."""
    import subprocess
    out = subprocess.run(["git", "show", f"HEAD:{path}"], capture_output=True, text=True, cwd=ROOT)
    return out.stdout if out.returncode == 0 else (ROOT / path).read_text()


def committed_files(prefix):
    """Paths under ``prefix`` committed at git HEAD (the working tree's files where it is not a git checkout)."""
    import subprocess
    out = subprocess.run(["git", "ls-tree", "-r", "--name-only", "HEAD", prefix], capture_output=True, text=True, cwd=ROOT)
    if out.returncode == 0:
        return out.stdout.split()
    return [p.relative_to(ROOT).as_posix() for p in (ROOT / prefix).rglob("*") if p.is_file()]


def run_cli(*args, cwd=ROOT):
    """``python -m penetration ARGS`` run in this process (no interpreter start and imports per case, about 3 s
    each): the exit status, stdout and stderr as subprocess.run gives them. The signal handlers a run installs and
    the working directory are restored afterwards."""
    import contextlib
    import io
    import os
    import signal
    import subprocess
    from penetration.cli import main
    out, err = io.StringIO(), io.StringIO()
    handlers = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    here = os.getcwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main([str(a) for a in args])
            except SystemExit as stop:
                code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
    finally:
        os.chdir(here)
        for s, h in handlers.items():
            signal.signal(s, h)
    return subprocess.CompletedProcess(list(args), code, out.getvalue(), err.getvalue())


# Oracles written out by hand (independent of the package's own formulas), shared by the tests that need them.

def v1_squared_by_hand(mass, radius, nstar, rho, resistance, velocity):
    """Forrestal's squared velocity at the crater's end (z = 4a), with its a^3 terms: (m V^2 - 4 pi a^3 S fc) /
    (m + 4 pi a^3 N* rho); ``resistance`` is S fc in Pa."""
    k = 4 * math.pi * radius**3
    return (mass * velocity**2 - k * resistance) / (mass + k * nstar * rho)


def eq9_by_hand(mass, radius, nstar, rho, resistance, velocity):
    """Eq 9's depth (m) for a shot past the crater: m / (2 pi a^2 rho N*) ln(1 + N* rho V1^2 / (S fc)) + 4a."""
    v1sq = v1_squared_by_hand(mass, radius, nstar, rho, resistance, velocity)
    return mass / (2 * math.pi * radius**2 * rho * nstar) * math.log(1 + nstar * rho * v1sq / resistance) + 4 * radius


def recorded_work(tr, mass):
    """The work of a trajectory's recorded deceleration history over its recorded path, m * integral of a dz
    (trapezoid over the samples, 200 a smooth piece: about 2e-4 relative). The integrator's own work state,
    W' = F v beside v' = -F/m, equals m vs^2 / 2 for any force law, so it checks nothing but the integration; the
    recorded history is computed from the effects afresh, and misses the kinetic energy if it drops or misstates one."""
    import numpy as np
    return mass * np.trapezoid(tr.deceleration, tr.z)
