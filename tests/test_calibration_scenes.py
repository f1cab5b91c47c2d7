"""Calibrations recover known values; scenes validate and resolve."""
from pathlib import Path

import numpy as np
import pytest
import yaml

from penetration.analytic.dop import penetration_depth
from penetration.analytic.fits import (calibrate_strength, diameter_interval, fit_nstar_and_strength, fit_strength,
                                      infer_diameter)
from penetration.analytic.resistance import Target
from penetration.nose.geometry import Ogive
from penetration.pipeline.config import ConfigError
from penetration.pipeline.scenes import read_scene, resolve, velocities

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow/schemas/scene.schema.json"


def test_calibration_recovers_a_known_strength():
    tg = Target(2440.0, 48e6, 7.3)
    depth = float(penetration_depth(81.1, 0.07, 0.0608, tg, 835.0))
    fit = calibrate_strength(81.1, 0.07, 0.0608, 2440.0, 48e6, 835.0, depth)
    assert fit["S"] == pytest.approx(7.3, rel=1e-10) and abs(fit["relative_residual"]) < 1e-12


def test_fit_recovers_strength_from_synthetic_cells():
    tg = Target(2440.0, 48e6, 5.5)
    cells = [{"mass": 81.1, "radius": 0.07, "nstar": n, "vs": v,
              "depth": float(penetration_depth(81.1, 0.07, n, tg, v))} for n in (0.06, 0.1) for v in (500, 1000)]
    fit = fit_strength(cells, 2440.0, 48e6)
    assert fit["S"] == pytest.approx(5.5, rel=1e-9) and fit["max_abs"] < 1e-9


@pytest.mark.parametrize("log", [False, True])
def test_row_fit_recovers_nstar_and_strength_of_a_synthetic_row(log):
    """Four depths of Table 3's projectile made by Eq 9 with a known (N*, S) give back that pair, in absolute or in
    ln-depth residuals; depths off by +-1 % at alternate velocities leave an rms ln residual of that size."""
    truth = (0.13, 5.2)
    cells = [{"mass": 81.1, "radius": 0.07, "vs": v,
              "depth": float(penetration_depth(81.1, 0.07, truth[0], Target(2440.0, 48e6, truth[1]), v))}
             for v in (500.0, 800.0, 1000.0, 1200.0)]
    fit = fit_nstar_and_strength(cells, 2440.0, 48e6, log=log)
    assert fit["nstar"] == pytest.approx(truth[0], rel=1e-7) and fit["S"] == pytest.approx(truth[1], rel=1e-7)
    if log:
        bent = [{**c, "depth": c["depth"] * (1.01 if k % 2 else 0.99)} for k, c in enumerate(cells)]
        rms = fit_nstar_and_strength(bent, 2440.0, 48e6, log=True)["rms_ln_residual"]
        assert 0.003 < rms <= 0.01005


def test_diameter_interval_ends_hit_the_axis_bounds():
    tg = Target(2500.0, 35e6, 12.17)
    lo, hi = diameter_interval(450.0, 0.0575, tg, 500.0, 16.0, 18.0)
    assert float(penetration_depth(450.0, lo / 2, 0.0575, tg, 500.0)) / lo == pytest.approx(18.0, rel=1e-9)
    assert float(penetration_depth(450.0, hi / 2, 0.0575, tg, 500.0)) / hi == pytest.approx(16.0, rel=1e-9)
    with pytest.raises(ValueError, match="no common diameter"):
        infer_diameter(450.0, 0.0575, tg, [(500.0, 16.0, 18.0), (1000.0, 5.0, 6.0)])


@pytest.mark.parametrize("path", sorted((ROOT / "workflow/scenes").glob("*.yaml")), ids=lambda p: p.stem)
def test_shipped_scenes_validate(path):
    read_scene(path, SCHEMA)


def test_scene_errors_name_the_field(tmp_path):
    data = yaml.safe_load((ROOT / "workflow/scenes/table3.yaml").read_text())
    data["effects"] = ["crater", "drag"]
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(data))
    with pytest.raises(ConfigError, match="effects.1") as err:
        read_scene(bad, SCHEMA)
    assert "allowed" in str(err.value)


def test_resolve_and_velocity_range():
    data = yaml.safe_load((ROOT / "workflow/scenes/fig15.yaml").read_text())
    v = velocities(data["velocities"])
    assert v[0] == 400.0 and v[-1] == 1400.0 and np.allclose(np.diff(v), 25.0)
    sc = resolve("fig15", data, {"table4_do1": Ogive(4.5, 0.07)}, {"do1": {"S": 6.7}}, {})
    assert sc.target.S == 6.7 and sc.noses["minimum_nstar"].length == pytest.approx(Ogive(4.5, 0.07).length)


def test_cavity_scene_effects_switch_hjc_terms():
    from penetration.concrete.material import material_switches
    cfg = {"lock": "offset", "tension": "openradioss", "rate_floor": True}
    assert material_switches(("crater", "cavity", "strain_rate", "damage", "strength_cap"), {}, cfg) == {}
    assert material_switches(("nose_entry", "cavity"), {"lock": "literal"}, cfg) == {
        "rate": False, "damage": False, "smax": 1e6, "lock": "literal"}
