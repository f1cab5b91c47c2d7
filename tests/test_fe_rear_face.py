"""The rear-face study's task (penetration.tasks.fe_rear_face): one change a step, effects with Welch intervals."""
import json
from types import SimpleNamespace as NS

import numpy as np
import pandas as pd
import pytest

from penetration.tasks.fe_rear_face import fe_rear_face

TARGETS = {"semi": {"kind": "semi_infinite", "radius": 1.2, "depth": None},
           "cut": {"kind": "semi_infinite", "radius": 1.2, "depth": 5.4},
           "cut_free": {"kind": "semi_infinite", "radius": 1.2, "depth": 5.4, "bottom": "free"},
           "block": {"kind": "block", "radius": 2.031, "depth": 5.4}}


def _write(tmp_path, scene, depths, statuses=None, size=0.00875):
    shots, members = [], []
    for k, d in enumerate(depths):
        status = (statuses or {}).get(k, "rest")
        s = {"scene": scene, "member": k, "element_size": size, "velocity": 835.0, "depth_m": d, "status": status,
             "time_to_rest_s": 0.014, "final_velocity_m_s": 50.0 if status != "rest" else 0.0, "target": TARGETS[scene]}
        path = tmp_path / f"{scene}_m{k}.json"
        path.write_text(json.dumps(s))
        (shots if k == 0 else members).append(str(path))
    return shots, members


def _run(tmp_path, chain, depths, statuses=None, sizes=None):
    shots, members = [], []
    for scene in chain:
        a, b = _write(tmp_path, scene, depths[scene], (statuses or {}).get(scene), (sizes or {}).get(scene, 0.00875))
        shots += a
        members += b
    cal = tmp_path / "cal.json"
    cal.write_text(json.dumps({"data": {"measured_depth": 5.1}}))
    out = NS(png=str(tmp_path / "r.png"), csv=str(tmp_path / "r.csv"), members=str(tmp_path / "m.csv"),
             effects=str(tmp_path / "e.csv"))
    fe_rear_face(NS(shots=shots, members=members, cal=str(cal)), out, NS(dpi=50, confidence=0.95, chain=chain))
    return pd.read_csv(out.csv), pd.read_csv(out.effects)


def test_each_step_gets_its_change_and_the_difference_of_its_means(tmp_path):
    rng = np.random.default_rng(1)
    base = 5.1 + 0.03 * rng.standard_normal(8)
    depths = {"semi": base, "cut": base - 0.05, "cut_free": base - 0.05 + 0.2}
    t, e = _run(tmp_path, ["semi", "cut", "cut_free"], depths)
    assert list(e.changes) == ["the bottom's depth", "the bottom face", "the bottom's depth + the bottom face"]
    assert e.effect_m.to_numpy() == pytest.approx([-0.05, 0.2, 0.15])
    assert not e.zero_inside_interval.any()
    assert t.least_distance_to_bottom_m.iloc[2] == pytest.approx(5.4 - depths["cut_free"].max())


def test_a_step_that_changes_two_things_is_refused(tmp_path):
    x = np.array([5.1, 5.11, 5.12])
    with pytest.raises(ValueError, match="one change a step"):
        _run(tmp_path, ["semi", "block", "cut"], {"semi": x, "block": x - 0.1, "cut": x})


def test_an_effect_and_its_welch_interval_against_hand_values(tmp_path):
    """5.0, 5.1, 5.2 (mean 5.1, variance 0.01) against 5.2, 5.5, 6.5 (mean 5.7333, variance 0.4633), the last through
    the rear face: Welch-Satterthwaite 2.086 degrees of freedom, half-width t(0.975) sqrt(va + vb) = 1.6431."""
    import math
    t, e = _run(tmp_path, ["cut", "cut_free"], {"cut": np.array([5.0, 5.1, 5.2]), "cut_free": np.array([5.2, 5.5, 6.5])},
                statuses={"cut_free": {2: "perforated"}})
    step = e.iloc[0]
    assert step.changes == "the bottom face" and step.effect_m == pytest.approx(17.2 / 3 - 5.1)
    half = 1.6431
    assert step.interval_low_m == pytest.approx(17.2 / 3 - 5.1 - half, rel=1e-4)
    assert step.interval_high_m == pytest.approx(17.2 / 3 - 5.1 + half, rel=1e-4) and step.zero_inside_interval
    free = t.set_index("scene").loc["cut_free"]
    assert free.perforated == 1 and free.at_rest == 2 and free.least_distance_to_bottom_m == pytest.approx(5.4 - 6.5)
    assert math.isclose(free.std_m, math.sqrt(0.4633333333333333))


def test_realisations_of_two_meshes_are_refused(tmp_path):
    x = np.array([5.1, 5.11, 5.12])
    with pytest.raises(ValueError, match="one mesh"):
        _run(tmp_path, ["cut", "cut_free"], {"cut": x, "cut_free": x}, sizes={"cut_free": 0.007})
