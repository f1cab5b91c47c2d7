"""Progress with an end (penetration.build) and jobs that end with their Snakemake (pipeline.end_with_parent)."""
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from penetration.build import Estimate, Progress, _profile

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}

LOG = """\
Job stats:
job         count
--------  -------
fe_shot         3
fig01           1
all             1
total           5

[Wed Nov 25 22:26:22 2026]
localrule fe_shot:
    output: results/fe/ci/table3/crh3_500.json
    jobid: 7
    reason: Missing output files
    wildcards: profile=ci, scene=table3, nose=crh3, velocity=500
    threads: 2
[Wed Nov 25 22:26:23 2026]
Finished jobid: 7 (Rule: fe_shot)
"""


def test_time_left_is_the_records_of_the_jobs_left_scaled_by_the_speed_so_far():
    records = {("fe [ci]", "fe_shot"): (2, 4.0), ("fe [full]", "fe_shot"): (1, 20.0), ("figures", "fig01"): (1, 1.0)}
    est = Estimate(records, profile="ci")
    assert est.job("fe_shot") == 2.0 and est.job("fe_shot", "full") == 20.0 and est.job("fig01") == 1.0
    assert est.job("all") == est.median          # no record: the median job
    p = Progress(est, start=0.0)
    notes = [p.feed(line, now=10.0) for line in LOG.splitlines()]
    assert p.counts == {"fe_shot": 3, "fig01": 1, "all": 1}
    assert p.started["7"] == ("fe_shot", "ci")
    # one ci shot done (2 s expected) in 10 s: speed 5; left: 2 shots (4 s) + fig01 (1 s) + all (median 2 s) = 7 s
    assert notes[-1] == "[progress] 1/5 jobs done, 10 s elapsed, about 35 s left"
    assert [n for n in notes[:-1] if n] == []


def test_the_profile_comes_from_the_command_line_or_the_config():
    assert _profile(["-c2", "all", "--config", "fe_profile=ci"]) == "ci"
    assert _profile(["-c2"]) in ("full", "ci")


def ends_within(pid, seconds):
    """Whether process ``pid`` is gone within ``seconds``."""
    t_end = time.monotonic() + seconds
    while time.monotonic() < t_end:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.05)
    return False


def test_a_job_ends_when_its_parent_is_killed(tmp_path):
    """The parent (Snakemake's place) is SIGKILLed while its child job runs: the child ends within seconds and never
    writes the output it would have written later."""
    marker = tmp_path / "late_output"
    child = textwrap.dedent(f"""
        import time
        from penetration.pipeline import end_with_parent
        end_with_parent(poll_s=0.05)
        time.sleep(6)
        open({str(marker)!r}, "w").write("late")
    """)
    parent = textwrap.dedent(f"""
        import subprocess, sys, time
        p = subprocess.Popen([sys.executable, "-c", {child!r}])
        print(p.pid, flush=True)
        time.sleep(60)
    """)
    proc = subprocess.Popen([sys.executable, "-c", parent], stdout=subprocess.PIPE, text=True, env=ENV)
    pid = int(proc.stdout.readline())
    time.sleep(1.0)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert ends_within(pid, 5.0), "the orphaned child is still running"
    time.sleep(6)
    assert not marker.exists()


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_killing_the_build_ends_snakemake_and_its_jobs(tmp_path, sig):
    """SIGTERM is forwarded to Snakemake, once, and ends it by itself, before the SIGKILL that follows GRACE_S later
    (a second SIGTERM stalled Snakemake's shutdown in most runs); SIGKILL cannot be forwarded, and Snakemake ends by
    its parent-death signal."""
    from penetration.build import GRACE_S
    proc, job = _build_with_a_slow_job(tmp_path, "")
    proc.send_signal(sig)
    assert proc.wait(timeout=0.8 * GRACE_S if sig == signal.SIGTERM else 30) != 0
    assert ends_within(job, 10.0), "the job outlived the build"
    assert not (tmp_path / "out.txt").exists()


def _build_with_a_slow_job(tmp_path, prefix):
    """The build running a one-job workflow whose job (a shell started by ``prefix``) sleeps 60 s; (the build's
    process, the job's pid) once the job runs."""
    (tmp_path / "Snakefile").write_text(textwrap.dedent(f"""
        rule all:
            input: "out.txt"
        rule slow:
            output: "out.txt"
            shell: "{prefix}echo $$ > pid.txt; sleep 60; touch {{output}}"
    """))
    proc = subprocess.Popen([sys.executable, "-m", "penetration.build", "-c1"], cwd=tmp_path, env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    pid_file = tmp_path / "pid.txt"
    for _ in range(600):
        if pid_file.exists() and pid_file.read_text().strip():
            break
        time.sleep(0.05)
    return proc, int(pid_file.read_text())


@pytest.mark.slow
def test_a_job_that_ignores_sigterm_is_killed_after_the_grace_period(tmp_path):
    from penetration.build import GRACE_S
    proc, job = _build_with_a_slow_job(tmp_path, "trap '' TERM; ")
    t0 = time.monotonic()
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=GRACE_S + 20) != 0
    assert ends_within(job, 5.0), "the job outlived the build"
    assert time.monotonic() - t0 >= 0.9 * GRACE_S   # it ignored the SIGTERM: the SIGKILL ended it


def test_a_committed_record_survives_a_job_that_refuses_to_rebuild_it(tmp_path):
    """The pieces of the long studies are committed records: a job that a change of the rule's metadata starts
    anyway, and whose task refuses (no runs given), must leave the record as it was. Every rule fed by
    record_inputs flags its output update(), and Snakemake then restores the record of a failed job instead of
    removing it (checked here on a rule of that form)."""
    import re

    rules = "".join((ROOT / "workflow/rules" / name).read_text() for name in ("figures.smk", "fe_studies.smk"))
    pieces = re.findall(r"input: \*\*[A-Z_]+_PIECE_INPUTS,\n\s+output: (\w+=[^\n]+)", rules)
    assert len(pieces) == 5 and all(re.match(r"\w+=update\(", p) for p in pieces), pieces
    (tmp_path / "Snakefile").write_text(textwrap.dedent("""\
        rule piece:
            output: csv=update("pieces/p{v}.csv")
            shell: "exit 1"   # the task's refusal: a committed piece is not rebuilt
        """))
    (tmp_path / "pieces").mkdir()
    (tmp_path / "pieces/p1.csv").write_text("committed\n")
    run = subprocess.run([sys.executable, "-m", "snakemake", "-c1", "--forcerun", "piece", "--", "pieces/p1.csv"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode != 0
    assert (tmp_path / "pieces/p1.csv").read_text() == "committed\n"
