"""The erosion-chaos ensemble of the FE level: its statistics against hand-computed values, and its input checks."""
import json
import math
from types import SimpleNamespace

import pandas as pd
import pytest

from penetration.figures.fe_level import fe_contrast_ensemble, fe_rear_face
from penetration.tasks.fe import fe_ensemble_shot

NOSES = ("double_ogive", "crh45", "crh3")


def _inputs(tmp_path, depths, size=0.00875):
    """Shot JSONs for one velocity (500 m/s): depths[nose] lists the depth of members 0, 1, 2, ..."""
    shots, members = [], []
    for nose, ds in depths.items():
        for k, d in enumerate(ds):
            p = tmp_path / f"{nose}_m{k}.json"
            s = {"nose": nose, "velocity": 500.0, "depth_m": d, "element_size": size}
            if k:
                s["member"] = k
            p.write_text(json.dumps(s))
            (members if k else shots).append(str(p))
    ratios = tmp_path / "ratios.csv"
    pd.DataFrame({"velocity_ms": [500] * 3, "contrast": ["DO/CRH 4.5", "CRH 4.5/CRH 3", "DO/CRH 3"],
                  "paper_sim_ratio": [1.088, 1.037, 1.129]}).to_csv(ratios, index=False)
    table = tmp_path / "table3.csv"
    pd.DataFrame({"velocity_ms": [500] * 3, "nose": list(NOSES), "paper_sim_m": [2.454, 2.255, 2.174]}).to_csv(table, index=False)
    outputs = SimpleNamespace(png=str(tmp_path / "e.png"), csv=str(tmp_path / "e.csv"), depths=str(tmp_path / "d.csv"))
    return SimpleNamespace(shots=shots, members=members, ratios=str(ratios), table=str(table)), outputs


def test_ensemble_statistics_against_hand_values(tmp_path):
    # DO/CRH 4.5 ratios 1.0, 1.1, 1.2 (mean 1.1, standard deviation 0.1); CRH 3 equal to CRH 4.5 (ratio 1 exactly)
    inputs, outputs = _inputs(tmp_path, {"double_ogive": [2.0, 2.2, 2.4], "crh45": [2.0] * 3, "crh3": [2.0] * 3})
    fe_contrast_ensemble(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95))
    t = pd.read_csv(outputs.csv).set_index("contrast")
    r = t.loc["DO/CRH 4.5"]
    assert r.realisations == 3 and r.ratio_member0 == pytest.approx(1.0) and r.element_size_m == 0.00875
    assert r.mean_ratio == pytest.approx(1.1) and r.std_ratio == pytest.approx(0.1)
    half = 4.302652729749464 * 0.1 / math.sqrt(3)  # Student's t, 2 degrees of freedom, 97.5 % quantile
    assert r.interval_low == pytest.approx(1.1 - half) and r.interval_high == pytest.approx(1.1 + half)
    assert r.mean_minus_paper_points == pytest.approx(100 * (1.1 - 1.088))
    assert bool(r.paper_inside_interval)
    c = t.loc["CRH 4.5/CRH 3"]
    assert c.std_ratio == 0.0 and not bool(c.paper_inside_interval)  # a zero-width interval at 1 misses 1.037
    d = pd.read_csv(outputs.depths).set_index("nose")
    assert d.loc["double_ogive", "mean_m"] == pytest.approx(2.2)
    assert d.loc["double_ogive", "rel_std_pct"] == pytest.approx(100 * 0.2 / 2.2)
    assert d.loc["crh45", "paper_sim_m"] == 2.255


def test_ensemble_rejects_mixed_meshes(tmp_path):
    inputs, outputs = _inputs(tmp_path, {"double_ogive": [2.0, 2.2], "crh45": [2.0] * 2, "crh3": [2.0] * 2})
    s = json.loads(open(inputs.members[0]).read())
    s["element_size"] = 0.007
    open(inputs.members[0], "w").write(json.dumps(s))
    with pytest.raises(ValueError, match="one mesh"):
        fe_contrast_ensemble(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95))


@pytest.mark.parametrize("member, step, field", [(0, 1e-9, "member"), (1, 0.0, "velocity_step"),
                                                   (1, 1e-3, "velocity_step")])
def test_ensemble_shot_rejects_bad_members_and_steps(member, step, field):
    with pytest.raises(ValueError, match=field):
        fe_ensemble_shot(SimpleNamespace(), SimpleNamespace(), SimpleNamespace(member=member, velocity_step=step))


def _rear_inputs(tmp_path, semi, block, statuses=None, size=0.00875):
    """DO1 JSONs of both targets (member 0 first); block statuses default to 'rest'."""
    shots, members = [], []
    for kind, depths in (("semi_infinite", semi), ("block", block)):
        for k, d in enumerate(depths):
            st = (statuses or {}).get((kind, k), "rest")
            s = {"nose": "double_ogive", "velocity": 835.0, "depth_m": d, "element_size": size, "status": st,
                 "time_to_rest_s": 0.02, "final_velocity_m_s": 50.0 if st == "perforated" else 0.0,
                 "target": {"kind": kind, "radius": 1.2, "depth": 5.4 if kind == "block" else None}}
            if k:
                s |= {"member": k, "striking_velocity": 835.0 * (1 + k * 1e-9)}
            p = tmp_path / f"{kind}_m{k}.json"
            p.write_text(json.dumps(s))
            (members if k else shots).append(str(p))
    cal = tmp_path / "cal.json"
    cal.write_text(json.dumps({"data": {"measured_depth": 5.1}}))
    outputs = SimpleNamespace(png=str(tmp_path / "r.png"), csv=str(tmp_path / "r.csv"), members=str(tmp_path / "m.csv"))
    return SimpleNamespace(shots=shots, members=members, cal=str(cal)), outputs


def test_rear_face_statistics_against_hand_values(tmp_path):
    # semi-infinite 5.0, 5.1, 5.2 (mean 5.1, variance 0.01); block 5.2, 5.5, 6.5 (mean 5.7333, variance 0.4633),
    # the last perforated: two tips beyond the 5.4 m rear face, one perforation
    inputs, outputs = _rear_inputs(tmp_path, [5.0, 5.1, 5.2], [5.2, 5.5, 6.5], {("block", 2): "perforated"})
    fe_rear_face(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95))
    t = pd.read_csv(outputs.csv).set_index("target")
    b, s = t.loc["block"], t.loc["semi_infinite"]
    assert s.mean_m == pytest.approx(5.1) and s.std_m == pytest.approx(0.1) and s.perforated == 0
    assert b.mean_m == pytest.approx(17.2 / 3) and b.tip_beyond_rear_face == 2 and b.perforated == 1
    assert b.moving_at_end == 0 and s.moving_at_end == 0
    assert b.mean_minus_semi_infinite_m == pytest.approx(17.2 / 3 - 5.1)
    va, vb = 0.4633333333333333 / 3, 0.01 / 3
    dof = (va + vb) ** 2 / (va ** 2 / 2 + vb ** 2 / 2)  # Welch-Satterthwaite: 2.087...
    from scipy import stats
    half = stats.t.ppf(0.975, dof) * math.sqrt(va + vb)
    assert dof == pytest.approx(2.0863, rel=1e-4) and half == pytest.approx(1.6431, rel=1e-4)  # t(0.975, 2.086) = 4.137
    assert b.interval_low_m == pytest.approx(17.2 / 3 - 5.1 - half) and b.interval_high_m == pytest.approx(17.2 / 3 - 5.1 + half)
    assert b.measured_depth_m == 5.1 and b.block_depth_m == 5.4
    m = pd.read_csv(outputs.members)
    assert len(m) == 6 and list(m[m.target == "block"].final_velocity_ms) == [0.0, 0.0, 50.0]


def test_rear_face_needs_both_targets_on_one_mesh(tmp_path):
    inputs, outputs = _rear_inputs(tmp_path, [5.0, 5.1], [5.2, 5.3])
    s = json.loads(open(inputs.members[-1]).read())
    s["element_size"] = 0.007
    open(inputs.members[-1], "w").write(json.dumps(s))
    with pytest.raises(ValueError, match="one mesh"):
        fe_rear_face(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95))
    inputs, outputs = _rear_inputs(tmp_path, [5.0, 5.1], [])
    with pytest.raises(ValueError, match="both"):
        fe_rear_face(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95))
