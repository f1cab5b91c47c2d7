"""The command line's runs: the FE cost before a run and the refusal above --max-minutes, progress on a pipe, an
interrupted run's partial record, and each answer's validated accuracy with warnings outside its range (read from
the committed validation under figures/, which is what these check)."""
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
SHOT = ("ogive", "crh=3", "diameter_m=0.0269", "mass_kg=0.9", "length_m=0.2424", "velocity_ms=800", "fc_MPa=35",
        "target_density_kgm3=2300")


def cli(*args, **kw):
    return subprocess.run([sys.executable, "-m", "penetration", *args], capture_output=True, text=True, cwd=ROOT,
                          env=ENV, **kw)


def test_an_answer_carries_its_accuracy_and_a_warning_outside_the_validated_range():
    inside = json.loads(cli("dop", *SHOT, "--model", "trajectory", "--json").stdout)
    assert inside["warnings"] == [] and "25 development shots" in inside["validated_accuracy"]
    fast = cli("dop", *SHOT[:-3], "velocity_ms=1500", "fc_MPa=35", "target_density_kgm3=2300", "--model", "analytic",
               "--json")
    rec = json.loads(fast.stdout)
    assert rec["warnings"] == ["striking velocity (velocity_ms) 1500 m/s is outside the validated 139.3-800 m/s"]
    assert "warning: striking velocity" in fast.stderr


def test_the_fe_level_prints_its_cost_first_and_refuses_above_the_limit():
    out = cli("dop", *SHOT, "--model", "fe", "--failure-strain", "1.0", "--max-minutes", "0.01")
    assert out.returncode == 2
    first = out.stderr.splitlines()[0]
    assert first.startswith("estimated cost:") and "elements" in first and "steps" in first
    assert "raise --max-minutes" in out.stderr and out.stdout == ""



def test_an_estimate_made_before_the_probe_is_a_lower_bound_and_says_so():
    """A shot refused before the machine was probed (its bound at 5 ns per element-step already above the limit)
    prints a lower bound, never a time of this machine."""
    from penetration.fe.level import CostEstimate
    unprobed = CostEstimate(1000, 500, 2000, 0.01, 0.0, 5.0, 2 ** 20).describe()
    probed = CostEstimate(1000, 500, 2000, 0.01, 60.0, 60.0, 2 ** 20).describe()
    assert "at least 0.083 min" in unprobed and "not probed" in unprobed and "measured now" not in unprobed
    assert "= 1 min on this machine (60 ns per element-step measured now" in probed and "at least" not in probed


def test_progress_reaches_a_pipe(tmp_path):
    shots = tmp_path / "shots.csv"
    lines = (ROOT / "workflow/data/experiments-dev.csv").read_text().splitlines()
    shots.write_text("\n".join(lines[:3]) + "\n")
    out = cli("predict", str(shots), "--model", "cavity", "--strength-scale", "0.5", "--out", str(tmp_path / "p.csv"))
    assert out.returncode == 0, out.stderr
    assert "cavity: shot 2/2 done" in out.stderr


def test_an_interrupted_fe_run_says_where_it_stopped_and_leaves_a_partial_record(tmp_path):
    out = tmp_path / "h.csv"
    # --max-minutes: the shot must run (about 0.7 min estimated) even where a busy machine's probe of the kernels
    # would estimate it above the default refusal
    proc = subprocess.Popen([sys.executable, "-m", "penetration", "simulate", *SHOT, "--model", "fe",
                             "--failure-strain", "1.0", "--max-minutes", "600", "--out", str(out)], cwd=ROOT, env=ENV,
                            stderr=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    lines = []
    for line in proc.stderr:           # the FE run's progress lines come every ~2 s
        lines.append(line)
        if line.startswith("t "):
            break
    proc.send_signal(signal.SIGTERM)
    rest = proc.stderr.read()
    assert proc.wait(timeout=60) == 130, "".join(lines) + rest
    assert "interrupted after" in rest and "last progress: t " in rest
    rec = json.loads(Path(f"{out}.partial.json").read_text())
    assert rec["status"] == "interrupted" and rec["signal"] == "SIGTERM" and rec["last_progress"].startswith("t ")
    assert not out.exists()
