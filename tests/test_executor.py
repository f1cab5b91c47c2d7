"""Part of the DAG through a non-local executor: rules share nothing but their declared inputs and outputs.

Snakemake's generic cluster executor hands every job to a submit command as a
job script, which runs it in a process of its own (here: a local submit
command that records the script and runs it, as a batch system would on a
node). A rule that relied on state left in the scheduler's process, or on a
file it did not declare, would fail or differ here. The outputs must equal
the committed ones byte for byte.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TARGETS = ["figures/fig01.png", "figures/table1.csv"]   # resistance_shares -> fig01 (a chain), table1 (on its own)
COMPARED = ["figures/fig01.csv", "figures/table1.csv"]


@pytest.fixture(scope="module")
def cluster_run(tmp_path_factory):
    work = tmp_path_factory.mktemp("cluster")
    for name in ("Snakefile", "workflow", "src", "profiles"):
        src = ROOT / name
        (shutil.copytree if src.is_dir() else shutil.copy)(src, work / name)
    submit = work / "submit.sh"
    submit.write_text('#!/bin/sh\necho "$1" >> submitted.txt\nexec bash "$1"\n')
    submit.chmod(0o755)
    snakemake = Path(sys.executable).with_name("snakemake")
    res = subprocess.run([str(snakemake), "--executor", "cluster-generic", "--cluster-generic-submit-cmd", str(submit),
                          "--jobs", "2", "--latency-wait", "5", "--seconds-between-status-checks", "1", *TARGETS], cwd=work, capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(work / "src")}, timeout=1200)
    return work, res


@pytest.mark.slow
def test_jobs_run_as_submitted_scripts(cluster_run):
    work, res = cluster_run
    assert res.returncode == 0, res.stderr[-3000:]
    submitted = (work / "submitted.txt").read_text().split()
    rules = sorted(Path(s).name.split(".")[1] for s in submitted)
    assert rules == ["fig01", "resistance_shares", "table1"]


@pytest.mark.slow
@pytest.mark.parametrize("path", COMPARED)
def test_outputs_equal_the_committed_ones(cluster_run, path):
    work, res = cluster_run
    assert res.returncode == 0, res.stderr[-3000:]
    from conftest import committed
    assert (work / path).read_text() == committed(path)
