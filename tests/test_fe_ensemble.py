"""The erosion-chaos ensemble of the FE level: its statistics against hand-computed values, and its input checks."""
import json
import math
from types import SimpleNamespace

import pandas as pd
import pytest

from penetration.figures.fe_level import fe_contrast_ensemble
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
