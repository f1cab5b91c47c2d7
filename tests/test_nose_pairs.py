"""The nose-pair contrast error (studies.nose_pairs) against constructed oracles: a level that errs by a common
factor per series has zero contrast error; one that errs on one nose by e has error e (or 1/(1+e) - 1)."""
import pandas as pd
import pytest

from penetration.studies import nose_pairs


def _shots():
    return pd.DataFrame({
        "shot_id": ["a1", "a2", "b1", "c1", "c2"],
        "diameter_m": [0.0762, 0.0762, 0.0762, 0.0269, 0.0269],
        "fc_MPa": [39.0, 39.0, 39.0, 35.0, 35.0],
        "nose_shape": ["ogive"] * 5, "crh": [3.0, 3.0, 6.0, 2.0, 2.0],
        "velocity_ms": [300.0, 400.0, 350.0, 500.0, 600.0],
        "dop_m": [0.5, 0.8, 0.9, 0.4, 0.6]})


def test_a_series_bias_cancels_and_a_nose_error_is_measured():
    shots = _shots()
    shots["common"] = shots.dop_m * shots.diameter_m.map({0.0762: 1.3, 0.0269: 0.7})
    shots["nose"] = shots.dop_m * shots.crh.map({3.0: 1.0, 6.0: 1.25, 2.0: 1.0})
    table = nose_pairs.pairs(shots, {"common": "common", "nose": "nose"})
    # pairs: only different noses in one series (a1-b1, a2-b1); the 26.9 mm shots share a nose
    assert len(table) == 4 and set(table.shot_a) == {"b1"} and set(table.shot_b) == {"a1", "a2"}
    assert table[table.level == "common"].contrast_error.abs().max() < 1e-12
    assert table[table.level == "nose"].contrast_error.to_numpy() == pytest.approx([0.25, 0.25])
    s = nose_pairs.summary(table).set_index("level")
    assert s.loc["nose", "pairs"] == 2 and s.loc["nose", "shots"] == 3 and s.loc["nose", "series"] == 1
    assert s.loc["nose", "median_abs_contrast_error"] == pytest.approx(0.25)
    assert s.loc["nose", "noses"] == "CRH 6 vs CRH 3"


def test_the_sharper_nose_is_a_and_the_ratio_is_measured():
    shots = _shots()
    shots["p"] = shots.dop_m
    t = nose_pairs.pairs(shots, {"p": "p"})
    row = t[t.shot_b == "a1"].iloc[0]
    assert row.nose_a == "CRH 6" and row.measured_ratio == pytest.approx(0.9 / 0.5) and row.predicted_ratio == pytest.approx(1.8)


def test_other_shapes_are_ordered_blunt_to_sharp():
    shots = pd.DataFrame({"shot_id": ["f", "h", "o"], "diameter_m": [0.03] * 3, "fc_MPa": [40.0] * 3,
                          "nose_shape": ["flat", "hemispherical", "ogive"], "crh": [float("nan"), float("nan"), 2.0],
                          "velocity_ms": [300.0] * 3, "dop_m": [0.2, 0.3, 0.5]})
    shots["p"] = shots.dop_m
    t = nose_pairs.pairs(shots, {"p": "p"})
    assert {(r.nose_a, r.nose_b) for r in t.itertuples()} == {("hemispherical", "flat"), ("CRH 2", "flat"),
                                                              ("CRH 2", "hemispherical")}
