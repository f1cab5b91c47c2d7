"""Each answer's validated accuracy and the range it holds for (penetration.shots.trust), against hand values."""
import csv

import pytest

from penetration.nose.geometry import Ogive, make_nose
from penetration.shots.ladder import UserShot
from penetration.shots.trust import ValidatedRange, accuracy_line, warnings

ROWS = [{"diameter_m": "0.0269", "mass_kg": "0.9", "fc_MPa": "23", "target_density_kgm3": "2300",
         "velocity_ms": "139.3", "nose_shape": "ogive", "crh": "2"},
        {"diameter_m": "0.0762", "mass_kg": "13.0", "fc_MPa": "108.3", "target_density_kgm3": "2370",
         "velocity_ms": "800", "nose_shape": "ogive", "crh": "6"}]


def test_the_range_is_the_development_shots_in_si():
    rng = ValidatedRange.from_rows(ROWS)
    assert rng.bounds["fc"] == (23e6, 108.3e6) and rng.bounds["diameter"] == (0.0269, 0.0762)
    assert rng.crh == (2.0, 6.0) and rng.shots == 2
    assert "striking velocity 139.3-800 m/s" in rng.describe()


def test_inside_the_range_no_warning_outside_one_per_quantity():
    rng = ValidatedRange.from_rows(ROWS)
    inside = UserShot(Ogive(3.0, 0.01345), 0.9, 800.0, 35e6, 2300.0, 0.24)
    assert warnings(inside, rng) == []
    fast = UserShot(Ogive(3.0, 0.01345), 0.9, 3000.0, 35e6, 2300.0, 0.24)
    assert warnings(fast, rng) == ["striking velocity (velocity_ms) 3000 m/s is outside the validated 139.3-800 m/s"]
    big = UserShot(make_nose("cone", radius=0.07, length=0.2), 81.1, 835.0, 48e6, 2440.0, 1.13)
    got = warnings(big, rng)
    assert len(got) == 5 and any("cone nose" in w for w in got) and any("calibre" in w and "140 mm" in w for w in got)
    assert warnings(UserShot(Ogive(0.5, 0.02), 1.0, 500.0, 40e6, 2300.0, 0.2), rng) == [
        "CRH 0.5 is outside the validated CRH 2-6"]


def test_the_development_shots_give_a_range():
    from conftest import ROOT
    with open(ROOT / "workflow/data/experiments-dev.csv", newline="") as fh:
        rng = ValidatedRange.from_rows(csv.DictReader(fh))
    assert rng.shots == 25 and rng.bounds["velocity"][1] == 800.0


def test_a_range_needs_shots_of_ogives():
    with pytest.raises(ValueError, match="at least one"):
        ValidatedRange.from_rows([])
    with pytest.raises(ValueError, match="flat"):
        ValidatedRange.from_rows([{**ROWS[0], "nose_shape": "flat"}])


def test_the_accuracy_line_states_the_errors():
    line = accuracy_line("fe", {"shots": 25, "median_abs_rel_err": 0.344, "p90_abs_rel_err": 0.539,
                                "mean_rel_err": 0.317, "within_10pct": 2})
    assert "median 34 %" in line and "mean +32 % (too deep" in line and "2 of 25 within 10 %" in line


def test_a_default_outside_the_range_is_said_once_and_not_warned():
    """The command line's default density (the paper's concrete, 2440 kg/m^3) lies outside the development shots'
    range (here 2300-2370): a shot that left it to the default gets no warning for it, but one note; a density the user gave
    outside the range is warned."""
    from penetration.shots.ladder import shot_from_keywords
    from penetration.shots.trust import defaults_note
    rng = ValidatedRange.from_rows(ROWS)   # densities 2300-2370 kg/m^3
    keys = {"diameter_m": "0.0269", "mass_kg": "0.9", "velocity_ms": "500", "fc_MPa": "40"}
    default = shot_from_keywords("ogive", {**keys, "crh": "3"})
    given = shot_from_keywords("ogive", {**keys, "crh": "3", "target_density_kgm3": "2440"})
    assert default.defaults == ("target_density_kgm3",) and given.defaults == ()
    assert warnings(default, rng) == [] and defaults_note(given, rng) == ""
    assert defaults_note(default, rng) == ("target_density_kgm3 not given: its default 2440 kg/m^3 lies outside the "
                                           "validated 2300-2370 kg/m^3")
    assert warnings(given, rng) == ["concrete density (target_density_kgm3) 2440 kg/m^3 is outside the validated "
                                    "2300-2370 kg/m^3"]
