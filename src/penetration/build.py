"""Run Snakemake with progress that has an end: ``python -m penetration.build [snakemake arguments]``.

Snakemake's own output passes through unchanged; after each finished job a line

    [progress] 37/101 jobs done, 6.2 min elapsed, about 9.5 min left

goes to stderr (flushed, terminal or not). The time left is the committed per-rule records
(``figures/timing/pipeline_rules.csv``: each rule's mean job wall time, per mesh profile where the rule has one)
summed over the jobs not yet finished, scaled by how fast this run has gone so far (elapsed time over the records'
time of the jobs finished), so that it holds on a slower or busier machine and with two jobs at a time. A rule
with no record counts as the median job.

Killing this process (SIGTERM, SIGINT, SIGHUP) ends Snakemake and its jobs: they run in a process group of their
own, whose leader passes the signal on to the group as a whole, once, and the group is killed (SIGKILL) if any of it
is still there GRACE_S seconds later; SIGKILL, which cannot be passed on, ends them too, through the group's leader (a
child of this process that Linux signals when its parent dies). Snakemake's exit status is this command's.
"""
from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

RECORDS = Path("figures/timing/pipeline_rules.csv")
GRACE_S = 10.0   # s from a forwarded signal to the group's SIGKILL
_STATS_ROW = re.compile(r"^(\w+)\s+(\d+)$")
_JOB_START = re.compile(r"^(?:local)?rule (\w+):$")
_JOBID = re.compile(r"^\s+jobid: (\d+)$")
_WILDCARDS = re.compile(r"^\s+wildcards: (.*)$")
_FINISHED = re.compile(r"^Finished jobid: (\d+) \(Rule: (\w+)\)")


def read_records(path=RECORDS) -> dict:
    """(stage, rule) -> (jobs, summed wall time in s) from a per-rule timing file; {} when there is none."""
    import csv
    try:
        with open(path, newline="") as fh:
            return {(r["stage"], r["rule"]): (int(r["jobs"]), float(r["wall_total_s"])) for r in csv.DictReader(fh)}
    except (OSError, KeyError, ValueError):
        return {}


@dataclass
class Estimate:
    """Expected wall time of a job from the records: its rule's mean at its mesh profile (stage ``X [profile]``),
    else over all its stages, else the median job."""
    records: dict
    profile: str = "full"

    def __post_init__(self):
        per_job = sorted(w / j for j, w in self.records.values() if j)
        self.median = per_job[len(per_job) // 2] if per_job else 1.0

    def job(self, rule, profile=None) -> float:
        rows = {stage: v for (stage, r), v in self.records.items() if r == rule}
        at = [v for stage, v in rows.items() if stage.endswith(f"[{profile or self.profile}]")]
        plain = [v for stage, v in rows.items() if not stage.endswith("]")]
        use = at or plain or list(rows.values())
        jobs, wall = sum(j for j, _ in use), sum(w for _, w in use)
        return wall / jobs if jobs else self.median


@dataclass
class Progress:
    """Reads Snakemake's output line by line; ``line()`` returns a progress line after a finished job, else None."""
    estimate: Estimate
    start: float = field(default_factory=time.monotonic)
    counts: dict = field(default_factory=dict)      # rule -> planned jobs (Snakemake's job stats)
    started: dict = field(default_factory=dict)     # jobid -> (rule, profile)
    finished: dict = field(default_factory=dict)    # rule -> finished jobs
    done_expected: float = 0.0
    _in_stats: bool = False
    _current: tuple | None = None                  # (rule, jobid) of the job block being read

    def feed(self, text: str, now=None):
        text = text.rstrip("\n")
        if text.startswith("Job stats:"):
            self._in_stats, self.counts = True, {}
            return None
        if self._in_stats:
            m = _STATS_ROW.match(text.strip())
            if m and m.group(1) != "total":
                self.counts[m.group(1)] = int(m.group(2))
            elif text.strip().startswith("total"):
                self._in_stats = False
            return None
        if m := _JOB_START.match(text):
            self._current = (m.group(1), None)
            return None
        if self._current and (m := _JOBID.match(text)):
            self._current = (self._current[0], m.group(1))
            self.started[m.group(1)] = (self._current[0], None)
            return None
        if self._current and self._current[1] and (m := _WILDCARDS.match(text)):
            wc = dict(kv.split("=", 1) for kv in m.group(1).split(", ") if "=" in kv)
            self.started[self._current[1]] = (self._current[0], wc.get("profile"))
            return None
        if m := _FINISHED.match(text):
            rule, profile = self.started.get(m.group(1), (m.group(2), None))
            self.finished[rule] = self.finished.get(rule, 0) + 1
            self.done_expected += self.estimate.job(rule, profile)
            return self.report(time.monotonic() if now is None else now)
        return None

    def remaining_expected(self) -> float:
        return sum(max(0, n - self.finished.get(rule, 0)) * self.estimate.job(rule) for rule, n in self.counts.items())

    def report(self, now) -> str:
        total = sum(self.counts.values())
        done = sum(self.finished.values())
        elapsed = now - self.start
        speed = elapsed / self.done_expected if self.done_expected > 0 else 1.0
        left = self.remaining_expected() * speed
        return f"[progress] {done}/{total} jobs done, {_span(elapsed)} elapsed, about {_span(left)} left"


def _span(seconds) -> str:
    return f"{seconds:.0f} s" if seconds < 90 else f"{seconds / 60:.1f} min"


def _profile(argv) -> str:
    """The FE mesh profile of the run: --config fe_profile=X, else workflow/config.yaml's."""
    for i, a in enumerate(argv):
        for item in ([a] + (argv[i + 1:i + 4] if a == "--config" else [])):
            if item.startswith("fe_profile="):
                return item.split("=", 1)[1]
    try:
        for line in Path("workflow/config.yaml").read_text().splitlines():
            if line.startswith("fe_profile:"):
                return line.split(":", 1)[1].split("#")[0].strip()
    except OSError:
        pass
    return "full"


GROUP_LEADER = "--group-leader"
PARENT_ENV = "PENETRATION_BUILD_PARENT"   # the wrapper's pid, as the group leader checks it is still there


def _lead_group(argv) -> int:
    """The wrapper's child, leader of a new process group holding Snakemake and its jobs: it ends the whole group on
    SIGTERM, SIGINT or SIGHUP, and Linux sends it SIGTERM when the wrapper ends, even by SIGKILL, which the wrapper
    cannot pass on (prctl PR_SET_PDEATHSIG; a wrapper gone already ends it at once)."""
    parent = int(os.environ.get(PARENT_ENV, os.getppid()))

    def end_group(signum, _frame):
        signal.signal(signum, signal.SIG_DFL)
        os.killpg(0, signum)

    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, end_group)
    try:
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)   # 1: PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass   # not Linux: the signals the wrapper forwards are the only link
    if os.getppid() != parent:
        end_group(signal.SIGTERM, None)
    return subprocess.call([sys.executable, "-m", "snakemake", *argv])


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == [GROUP_LEADER]:
        return _lead_group(argv[1:])
    progress = Progress(Estimate(read_records(), _profile(argv)))
    proc = subprocess.Popen([sys.executable, "-m", "penetration.build", GROUP_LEADER, *argv], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, bufsize=1, start_new_session=True,
                            env={**os.environ, PARENT_ENV: str(os.getpid())})

    def kill_group():
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass

    def forward(signum, _frame):
        # to the group's leader, which signals the group once (Snakemake stalls in its shutdown when a second
        # SIGTERM reaches it); the whole group if the leader is gone
        try:
            os.kill(proc.pid, signum)
        except ProcessLookupError:
            kill_group()
            return
        killer = threading.Timer(GRACE_S, kill_group)
        killer.daemon = True
        killer.start()

    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, forward)
    for text in proc.stdout:
        sys.stderr.write(text)
        note = progress.feed(text)
        if note:
            sys.stderr.write(note + "\n")
        sys.stderr.flush()
    return proc.wait()


if __name__ == "__main__":
    sys.exit(main())
