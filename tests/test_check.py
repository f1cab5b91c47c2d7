"""The reproduction check fails on drift (run in a scratch git repository)."""
import os
import subprocess

import pytest

from penetration.tasks import reproduction_problems

HEAD = "item,quantity,case,paper,ours,rel_err,tol,status\n"


@pytest.fixture
def repo(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    env = {**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@t"}
    (tmp_path / "fig.csv").write_text("x,y,name\n0,1.0,a\n1,2.0,b\n")
    (tmp_path / "diff.csv").write_text(HEAD + "table4,nstar,cone,0.0553,0.0556,0.005,0.01,reproduced\n")
    for cmd in (["git", "init", "-q"], ["git", "add", "."], ["git", "commit", "-qm", "x"]):
        subprocess.run(cmd, check=True, env=env, capture_output=True)
    return tmp_path


def test_unchanged_passes(repo):
    problems, compared = reproduction_problems(["fig.csv"], "diff.csv", 1e-6, 1e-12)
    assert problems == [] and compared == 1


def test_tiny_noise_passes(repo):
    (repo / "fig.csv").write_text("x,y,name\n0,1.0000000001,a\n1,2.0,b\n")
    assert reproduction_problems(["fig.csv"], "diff.csv", 1e-6, 1e-12)[0] == []


def test_numeric_drift_fails(repo):
    (repo / "fig.csv").write_text("x,y,name\n0,1.001,a\n1,2.0,b\n")
    problems, _ = reproduction_problems(["fig.csv"], "diff.csv", 1e-6, 1e-12)
    assert len(problems) == 1 and "column y row 2" in problems[0]


def test_text_and_shape_changes_fail(repo):
    (repo / "fig.csv").write_text("x,y,name\n0,1.0,a\n1,2.0,c\n")
    assert "column name" in reproduction_problems(["fig.csv"], "diff.csv", 1e-6, 1e-12)[0][0]
    (repo / "fig.csv").write_text("x,y,name\n0,1.0,a\n")
    assert "row count" in reproduction_problems(["fig.csv"], "diff.csv", 1e-6, 1e-12)[0][0]


def test_lost_reproduction_fails(repo):
    (repo / "diff.csv").write_text(HEAD + "table4,nstar,cone,0.0553,0.06,0.08,0.01,deviates\n")
    problems, _ = reproduction_problems([], "diff.csv", 1e-6, 1e-12)
    assert len(problems) == 1 and "was reproduced, now deviates" in problems[0]
