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
