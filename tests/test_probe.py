"""Inputs and outputs that cannot be handled for sure are refused, naming what and why.

Writes never replace what is not a regular file; dop, simulate and predict
speak the shots CSV's vocabulary; numbers are read in one form everywhere;
no level extrapolates past its sigma_n table.
"""
import json
import os
import stat
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from penetration.io import TargetError, write_csv

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "workflow/data/experiments-dev.csv"


def cli(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "penetration", *args], capture_output=True, text=True, cwd=cwd,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "src")})


def shots_file(tmp_path, text, name="shots.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def header():
    return SHOTS.read_text().splitlines()[0]


def good_row():
    return SHOTS.read_text().splitlines()[1]


# ------------------------------------------------------- writes never replace a non-regular file
@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "pipe"
    os.mkfifo(path)
    return path


def test_write_csv_refuses_a_fifo(fifo):
    with pytest.raises(TargetError, match="FIFO.*allowed: a regular file or a new path"):
        write_csv(pd.DataFrame({"x": [1.0]}), fifo)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert sorted(p.name for p in fifo.parent.iterdir()) == ["pipe"]  # no temporary left


def test_write_csv_judges_a_symlink_by_its_target(tmp_path, fifo):
    link = tmp_path / "link.csv"
    link.symlink_to(fifo)
    with pytest.raises(TargetError, match="FIFO"):
        write_csv(pd.DataFrame({"x": [1.0]}), link)
    assert link.is_symlink() and stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_predict_refuses_a_fifo_as_out(tmp_path, fifo):
    path = shots_file(tmp_path, f"{header()}\n{good_row()}\n")
    out = cli("predict", str(path), "--out", str(fifo))
    assert out.returncode == 2, out.stderr
    assert out.stderr.startswith("error: ") and "--out" in out.stderr and "FIFO" in out.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_simulate_refuses_a_fifo_as_out(fifo):
    out = cli("simulate", "ogive", "psi=3", "radius=0.07", "mass=81.1", "velocity=835", "fc=48e6",
              "--model", "trajectory", "--out", str(fifo))
    assert out.returncode == 2, out.stderr
    assert out.stderr.startswith("error: ") and "--out" in out.stderr and "FIFO" in out.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
