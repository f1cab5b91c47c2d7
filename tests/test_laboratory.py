"""Calibration on laboratory series: the protocol's folds and the fit of one factor (penetration.studies.laboratory)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from penetration.errors import ParameterError
from penetration.studies.laboratory import Protocol, errors_summary, fit_factor, interpolated_depths, slope

SERIES = {"s1994": "1994", "s2003": "2003"}
GROUPS = {"s2003": {"normal": (20.0, 50.0), "high": (80.0, 120.0)}}
GRID = tuple(np.geomspace(0.2, 2.0, 9))


def shots():
    sources = ["Forrestal 1994"] * 3 + ["Forrestal 2003"] * 5
    fcs = [39.0, 39.0, 23.0, 32.0, 40.0, 95.0, 101.0, 36.0]
    return sources, fcs


def test_every_fold_holds_out_what_it_names_and_fits_on_nothing_it_scores():
    p = Protocol(SERIES, GROUPS, GRID)
    sources, fcs = shots()
    series = [p.series_of(s) for s in sources]
    groups = [p.group_of(s, f) for s, f in zip(series, fcs)]
    assert groups == ["", "", "", "normal", "normal", "high", "high", "normal"]
    folds = {name: (fit, held) for name, fit, held in p.folds(series, groups)}
    assert list(folds) == ["all", "series:s1994", "series:s2003", "fc_group:s2003:normal", "fc_group:s2003:high"]
    assert folds["all"][0].all() and not folds["all"][1].any()
    assert folds["series:s1994"][1].tolist() == [True] * 3 + [False] * 5
    assert folds["series:s2003"][0].tolist() == [True] * 3 + [False] * 5
    # inside the 2003 series: the other fc group only (the 1994 shots are in neither)
    assert folds["fc_group:s2003:high"][0].tolist() == [False] * 3 + [True, True, False, False, True]
    assert folds["fc_group:s2003:high"][1].tolist() == [False] * 5 + [True, True, False]
    for fit, held in folds.values():
        assert not np.any(fit & held)


def test_a_shot_in_no_series_or_two_groups_is_refused_and_bad_protocols_name_their_field():
    p = Protocol(SERIES, GROUPS, GRID)
    with pytest.raises(ValueError, match="names 0 series"):
        p.series_of("Hanchak 1992")
    with pytest.raises(ValueError, match="falls in 0 of its fc groups"):
        p.group_of("s2003", 65.0)
    with pytest.raises(ParameterError, match="series"):
        Protocol({"only": "1994"})
    with pytest.raises(ParameterError, match="fc_groups.s2003.high"):
        Protocol(SERIES, {"s2003": {"normal": (20.0, 50.0), "high": (120.0, 80.0)}})
    with pytest.raises(ParameterError, match="grid"):
        Protocol(SERIES, GROUPS, (1.0, 0.5, 2.0, 3.0))


def test_the_fit_recovers_the_factor_of_exact_power_laws_and_its_fold_ignores_the_held_out_shots():
    """Depths c_i v^-p_i are straight lines in log-log, which the monotone cubic reproduces exactly: measured depths
    made at v* = 0.637 give back v* and zero error; corrupting the held-out shots does not move the fold's fit."""
    rng = np.random.default_rng(3)
    c, p = rng.uniform(0.2, 2.0, 8), rng.uniform(0.3, 0.9, 8)
    grid = np.asarray(GRID)
    depths = c[:, None] * grid[None, :] ** -p[:, None]
    v_star = 0.637
    measured = c * v_star ** -p
    mask = np.ones(8, bool)
    f = fit_factor(grid, depths, measured, mask)
    assert f.value == pytest.approx(v_star, rel=1e-7) and f.rms_log_error < 1e-7 and not f.at_grid_edge
    np.testing.assert_allclose(interpolated_depths(grid, depths, v_star), measured, rtol=1e-12)
    held = np.arange(8) >= 5
    corrupted = np.where(held, measured * 3.0, measured)
    assert fit_factor(grid, depths, corrupted, ~held).value == pytest.approx(v_star, rel=1e-7)
    assert fit_factor(grid, depths, corrupted, mask).value != pytest.approx(v_star, rel=1e-2)


def test_a_minimum_beyond_the_grid_is_flagged_at_its_edge():
    grid = np.asarray(GRID)
    depths = np.outer(np.ones(3), grid ** -0.5)
    f = fit_factor(grid, depths, np.full(3, 5.0 ** -0.5), np.ones(3, bool))   # the exact value 5 is beyond 2
    assert f.at_grid_edge and f.value == pytest.approx(2.0)


def test_the_summary_and_the_slope_against_hand_values():
    s = errors_summary([0.05, -0.20, 0.10, -0.02])
    assert s == {"shots": 4, "median_abs_rel_err": pytest.approx(0.075), "p90_abs_rel_err": pytest.approx(0.17),
                 "mean_rel_err": pytest.approx(-0.0175), "within_10pct": 3}
    x = np.log([30.0, 40.0, 90.0, 100.0])
    b, lo, hi, n = slope(x, 0.3 - 0.25 * x)
    assert (b, n) == (pytest.approx(-0.25), 4) and lo == pytest.approx(b) and hi == pytest.approx(b)
    assert math.isnan(slope([1.0, 1.0, 1.0], [0.0, 1.0, 2.0])[0])


def test_the_within_series_slope_ignores_an_offset_between_series_that_the_pooled_slope_takes_for_a_trend():
    """Two series with the same slope -0.2 in ln fc but offsets 0 and +0.5, the second at higher fc: the pooled slope
    is biased upward by the offset, the within-series one is exactly -0.2 (a zero-width interval: no scatter)."""
    from penetration.studies.laboratory import within_slope
    x = np.log([25.0, 35.0, 40.0, 60.0, 90.0, 110.0])
    groups = np.array(["a", "a", "a", "b", "b", "b"])
    y = -0.2 * x + np.where(groups == "b", 0.5, 0.0)
    b, lo, hi, n = within_slope(x, y, groups)
    assert (b, lo, hi, n) == (pytest.approx(-0.2), pytest.approx(-0.2), pytest.approx(-0.2), 6)
    assert slope(x, y)[0] > 0
    noisy = y + np.array([0.01, -0.01, 0.0, 0.02, -0.02, 0.0])
    b, lo, hi, _ = within_slope(x, noisy, groups)
    assert lo < b < hi and lo < -0.2 < hi


def test_the_validation_summary_scores_each_calibration_on_its_held_out_shots_with_its_slopes():
    """Residuals made as exp(-0.2 ln fc + series offset) - 1: every row's within-series slope is -0.2; the fc-group
    row scores only the shots its folds held out; one primary row per (level, calibration)."""
    import pandas as pd

    from penetration.studies.laboratory import ROWS, summary_rows, users_rows

    fc = np.array([39.0, 39.0, 23.0, 32.0, 40.0, 95.0, 101.0, 36.0])
    d = np.array([0.0762] * 3 + [0.0269] * 5)
    series = np.array(["s1994"] * 3 + ["s2003"] * 5)
    r = np.expm1(-0.2 * np.log(fc) + np.where(series == "s1994", 0.3, 0.0))
    shots = pd.DataFrame({"shot_id": [f"x{i}" for i in range(8)], "fc_MPa": fc, "diameter_m": d,
                          "series_cavity_laboratory": series})
    for *_, key in ROWS:
        shots[f"rel_err_{key}"] = r
    for key in ("cavity_laboratory_fc_group", "fe_laboratory_fc_group"):
        shots.loc[:2, f"rel_err_{key}"] = np.nan      # 1994 shots: in no fc-group fold
    s = summary_rows(shots, "li_chen")
    assert list(zip(s.level, s.calibration)) == [("analytic", "none: S from li_chen"), ("trajectory", "none: S from li_chen"),
                                                 ("cavity", "do1"), ("cavity", "laboratory"), ("cavity", "laboratory"),
                                                 ("fe", "do1"), ("fe", "laboratory"), ("fe", "laboratory")]
    assert s.shots.tolist() == [8, 8, 8, 8, 5, 8, 8, 5]
    assert s.primary.tolist() == [True, True, True, True, False, True, True, False]
    assert s.predictions.tolist() == [key for *_, key in ROWS]
    np.testing.assert_allclose(s.slope_ln_fc_within_series, -0.2, rtol=1e-9)
    # the fc-group row has one series: its pooled and within-series slopes agree
    assert s.slope_ln_fc[4] == pytest.approx(-0.2)
    # users get each level's laboratory calibration where it has one
    assert users_rows(s).predictions.tolist() == ["analytic", "trajectory", "cavity_laboratory", "fe_laboratory"]
    # a level without laboratory predictions (a mesh not calibrated on them) has no laboratory rows
    s = summary_rows(shots.drop(columns=["rel_err_fe_laboratory", "rel_err_fe_laboratory_fc_group"]), "li_chen")
    assert list(zip(s.level, s.calibration))[-2:] == [("cavity", "laboratory"), ("fe", "do1")]
    assert users_rows(s).predictions.tolist() == ["analytic", "trajectory", "cavity_laboratory", "fe"]


def test_the_calibration_scores_each_fold_on_direct_runs_at_its_fitted_value(monkeypatch, tmp_path):
    """A fake cavity level whose depth is c_i s^-0.5 with c_i from the shot: measured depths made at s* = 0.8 for the
    1994 series and 0.6 for the 2003 series. The fold fitted on 2003 finds 0.6 and predicts the 1994 shots deeper by
    exactly (0.8/0.6)^0.5 - 1, from runs at its fitted value (the interpolation's error is nil on power laws)."""
    from types import SimpleNamespace

    import penetration.tasks.laboratory as L

    c = {f"x{i}": 0.3 + 0.1 * i for i in range(8)}
    calls = []

    def fake_run(shot, level, ctx):
        calls.append(ctx.strength_scale)
        return SimpleNamespace(depth_m=c[shot.label] * ctx.strength_scale ** -0.5, status="rest", wall_time_s=0.0)

    monkeypatch.setattr(L, "run", fake_run)
    monkeypatch.setattr(L, "user_shot", lambda r: SimpleNamespace(label=r["shot_id"]))
    sources, fcs = shots()
    truth = [0.8 if "1994" in s else 0.6 for s in sources]
    rows = [{"shot_id": f"x{i}", "source": s, "fc_MPa": f, "diameter_m": 0.0762 if "1994" in s else 0.0269,
             "velocity_ms": 500.0, "dop_m": c[f"x{i}"] * t ** -0.5} for i, (s, f, t) in enumerate(zip(sources, fcs, truth))]
    ctx = SimpleNamespace(strength_scale=None)
    fits, preds, grid, timing = L.calibrate_on_laboratory("cavity", ctx, rows, Protocol(SERIES, GROUPS, GRID), "data.csv",
                                                          log=lambda m: None)
    f = fits.set_index("fold")
    assert f.loc["series:s1994", "value"] == pytest.approx(0.6, rel=1e-6)      # fitted on the 2003 series
    assert f.loc["series:s2003", "value"] == pytest.approx(0.8, rel=1e-6)
    held = preds[preds.fold == "series:s1994"]
    np.testing.assert_allclose(held.rel_error, (0.8 / 0.6) ** 0.5 - 1, rtol=1e-5)
    assert np.abs(preds.interpolation_error).max() < 1e-9
    assert set(held.shot_id) == {"x0", "x1", "x2"} and (held.status == "rest").all()
    assert len(grid) == 8 * len(GRID) and len(calls) == 8 * len(GRID) + 3 + 5 + 3 + 2   # the grid, then each fold's held-out shots

    # the grid's runs made before, in pieces (one CSV per grid value, its rows in any order), give the same
    # calibration, and only the held-out shots run
    import pandas as pd
    paths = []
    for k, value in enumerate(GRID):
        piece = grid[grid.strength_scale == value].assign(fs=value, wall_time_s=1.0).iloc[::-1]
        paths.append(tmp_path / f"fs_{value:g}.csv")
        piece.to_csv(paths[-1], index=False)
    calls.clear()
    again = L.calibrate_on_laboratory("cavity", ctx, rows, Protocol(SERIES, GROUPS, GRID), "data.csv", log=lambda m: None,
                                      grid_runs=lambda rows: L.grid_runs_from(paths, rows, GRID))
    pd.testing.assert_frame_equal(again[0], fits)
    assert len(calls) == 3 + 5 + 3 + 2 and again[3].wall_time_s[0] == 8 * len(GRID)
    pd.read_csv(paths[0]).assign(fs=9.0).to_csv(paths[0], index=False)
    with pytest.raises(ValueError, match="not the runs of every laboratory shot"):
        L.grid_runs_from(paths, rows, GRID)

    # the calibration's own grid table (every shot at every value, as the cavity calibration writes it) and its
    # timing record give the same calibration again (the scale effect's variant without the effect reads these)
    grid.iloc[::-1].to_csv(tmp_path / "grid.csv", index=False)
    pd.DataFrame([{"wall_time_s": 12.5}]).to_csv(tmp_path / "timing.csv", index=False)
    calls.clear()
    table = L.calibrate_on_laboratory("cavity", ctx, rows, Protocol(SERIES, GROUPS, GRID), "data.csv", log=lambda m: None,
                                      grid_runs=lambda rows: L.grid_runs_from_table(tmp_path / "grid.csv",
                                                                                    tmp_path / "timing.csv", rows, GRID,
                                                                                    "strength_scale"))
    pd.testing.assert_frame_equal(table[0], fits)
    assert len(calls) == 3 + 5 + 3 + 2 and table[3].wall_time_s[0] == 12.5
    grid[grid.shot_id != "x0"].to_csv(tmp_path / "grid.csv", index=False)
    with pytest.raises(ValueError, match="not the runs of every laboratory shot"):
        L.grid_runs_from_table(tmp_path / "grid.csv", tmp_path / "timing.csv", rows, GRID, "strength_scale")


def test_the_command_line_reports_the_validation_row_of_the_calibration_in_use(tmp_path):
    """validated_accuracy picks, per level, the primary row of the calibration asked for where a level has several;
    a level with one calibration keeps it whatever is asked."""
    import shutil

    import pandas as pd

    from penetration.shots.records import validated_accuracy

    root = Path(__file__).resolve().parents[1]
    (tmp_path / "workflow/data").mkdir(parents=True)
    shutil.copy(root / "workflow/config.yaml", tmp_path / "workflow/config.yaml")
    shutil.copy(root / "workflow/data/experiments-dev.csv", tmp_path / "workflow/data/experiments-dev.csv")
    rows = [("analytic", "none", True, 0.07), ("cavity", "do1", True, 0.34), ("cavity", "laboratory", True, 0.18),
            ("cavity", "laboratory", False, 0.12), ("fe", "do1", True, 0.34)]
    summary = pd.DataFrame([{"level": lv, "calibration": c, "scoring": "s", "primary": p, "shots": 25,
                             "median_abs_rel_err": m, "p90_abs_rel_err": 0.3, "mean_rel_err": 0.1, "within_10pct": 5}
                            for lv, c, p, m in rows])
    (tmp_path / "figures/fe/full").mkdir(parents=True)
    summary.to_csv(tmp_path / "figures/fe/full/validation_levels_summary.csv", index=False)
    _, lab = validated_accuracy(tmp_path, "full", "laboratory")
    _, do1 = validated_accuracy(tmp_path, "full", "do1")
    assert lab["cavity"]["median_abs_rel_err"] == 0.18 and do1["cavity"]["median_abs_rel_err"] == 0.34
    assert lab["fe"]["calibration"] == do1["fe"]["calibration"] == "do1"   # no fe laboratory record: DO1's
    assert set(lab) == {"analytic", "cavity", "fe"}
    # with the profile's fe laboratory record the fe level runs with it: its row, or none when the validation has none
    (tmp_path / "figures/fe/full/calibration_fe_laboratory.csv").write_text("fold\nall\n")
    assert "fe" not in validated_accuracy(tmp_path, "full", "laboratory")[1]
    assert validated_accuracy(tmp_path, "full", "do1")[1]["fe"]["calibration"] == "do1"
    summary.loc[len(summary)] = {**summary.iloc[-1].to_dict(), "calibration": "laboratory", "median_abs_rel_err": 0.13}
    summary.to_csv(tmp_path / "figures/fe/full/validation_levels_summary.csv", index=False)
    assert validated_accuracy(tmp_path, "full", "laboratory")[1]["fe"]["median_abs_rel_err"] == 0.13
    # a record of the user's own has no validation
    assert "cavity" not in validated_accuracy(tmp_path, "full", "my_record.csv")[1]


def test_the_strength_scale_says_which_record_it_comes_from():
    """The source of the cavity level's strength scale is read from the record itself: a laboratory table (a fold
    column) or a DO1 record, whichever way the record was named."""
    from penetration.shots.records import CAVITY_CALIBRATION, CAVITY_LABORATORY, context_from_pipeline

    root = Path(__file__).resolve().parents[1]
    assert context_from_pipeline(root).strength_scale_source.startswith("fitted on the laboratory shots")
    assert context_from_pipeline(root, calibration="do1").strength_scale_source.startswith("calibrated on DO1")
    for record, label in ((CAVITY_LABORATORY, "fitted on the laboratory shots"), (CAVITY_CALIBRATION, "calibrated on DO1")):
        ctx = context_from_pipeline(root, calibration=str(root / record))
        assert ctx.strength_scale_source.startswith(label)


def test_the_fe_level_takes_the_laboratory_failure_strain_of_its_mesh_where_one_is_recorded(tmp_path):
    """Without a laboratory record at the profile's mesh the fe level carries DO1's failure strain over and says so;
    with one it takes its fold ``all``; --calibration do1 takes DO1's; a record of another mesh is refused."""
    import shutil

    import pandas as pd

    from penetration.shots.records import FE_CALIBRATION, FE_LABORATORY, context_from_pipeline

    root = Path(__file__).resolve().parents[1]
    for rel in ("workflow/config.yaml", "workflow/reference/paper_values.csv", FE_CALIBRATION.format(profile="full")):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(root / rel, tmp_path / rel)
    do1 = float(pd.read_csv(tmp_path / FE_CALIBRATION.format(profile="full")).value[0])
    ctx = context_from_pipeline(tmp_path)
    assert ctx.failure_strain == do1 and "no laboratory calibration: DO1's" in ctx.failure_strain_source
    size = ctx.fe_settings.element_size
    record = pd.DataFrame([{"level": "fe", "fold": f, "parameter": "fs", "value": v, "element_size_m": size,
                            "elements_across_radius": 0.07 / size} for f, v in (("all", 1.5), ("series:s1994", 1.2))])
    record.to_csv(tmp_path / FE_LABORATORY.format(profile="full"), index=False)
    ctx = context_from_pipeline(tmp_path)
    assert ctx.failure_strain == 1.5 and ctx.failure_strain_source.startswith("fitted on the laboratory shots at 8 ")
    assert context_from_pipeline(tmp_path, calibration="do1").failure_strain == do1
    record.assign(element_size_m=2 * size).to_csv(tmp_path / FE_LABORATORY.format(profile="full"), index=False)
    with pytest.raises(ValueError, match="calibrated at element size"):
        context_from_pipeline(tmp_path)
