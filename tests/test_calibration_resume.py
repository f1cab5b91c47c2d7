"""An interrupted failure-strain calibration resumes where it stopped: its finished trials are kept on disk."""
import json
from types import SimpleNamespace

import pytest

import penetration.fe.level as fe_level
from penetration.tasks.fe import TrialMemo


def fake_runs(monkeypatch, calls, stop_after=None):
    """run_shot replaced by a depth that falls with fs (a cubic in log fs, so that the secant needs several
    trials), counting the runs; the run after ``stop_after`` raises, as a killed job would stop."""
    import math

    def run_shot(spec, **kw):
        if stop_after is not None and len(calls) >= stop_after:
            raise KeyboardInterrupt
        fs = spec.settings.controls.erosion_value
        calls.append(fs)
        u = math.log(fs / 1.0263)
        depth = 5.1 - 0.8 * (u + 0.6 * u ** 3)
        return SimpleNamespace(depth=depth, wall_time=1.0, status="rest", peak_deceleration=1.0, elements=10, steps=10,
                               summary=lambda: {"energy_error_max": 0.0})

    monkeypatch.setattr(fe_level, "run_shot", run_shot)


def calibrate(memo):
    from penetration.fe.shot import RunSpec
    return fe_level.calibrate_failure_strain(RunSpec(None, 81.1, 835.0, None), 5.1, bracket=(0.3, 3.0), tol_m=1e-4,
                                             memo=memo)


def test_an_interrupted_calibration_runs_no_finished_trial_again(monkeypatch, tmp_path):
    whole = []
    fake_runs(monkeypatch, whole)
    reference = calibrate(None)
    assert reference["fs"] == pytest.approx(1.0263, rel=1e-4) and len(whole) >= 4
    first = []
    fake_runs(monkeypatch, first, stop_after=3)
    with pytest.raises(KeyboardInterrupt):
        calibrate(TrialMemo(tmp_path, "shot", 1))
    assert len(first) == 3
    resumed = []
    fake_runs(monkeypatch, resumed)
    again = calibrate(TrialMemo(tmp_path, "shot", 1))
    assert resumed == whole[3:]                       # only the trials not yet finished
    assert again["fs"] == reference["fs"] and [r["fs"] for r in again["runs"]] == whole


def test_trials_of_another_definition_are_not_reused_and_a_cut_line_is_skipped(tmp_path):
    memo = TrialMemo(tmp_path, "shot", 1)
    memo[repr(0.5)] = {"fs": 0.5, "depth_m": 4.0, "status": "rest"}
    with open(memo.path, "a") as fh:
        fh.write('{"fs": 0.7, "dep')                  # killed while writing
    assert list(TrialMemo(tmp_path, "shot", 1)) == [repr(0.5)]
    assert len(TrialMemo(tmp_path, "shot", 2)) == 0  # another shot: another file
    assert json.loads(memo.path.read_text().splitlines()[0])["depth_m"] == 4.0
