"""The erosion-chaos ensemble and the mesh band of the FE level: their statistics against hand-computed values, and
their input checks."""
import json
import math
from types import SimpleNamespace

import pandas as pd
import pytest

from penetration.tasks.fe_studies import fe_contrast_band, fe_contrast_ensemble
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


def _band_inputs(tmp_path, meshes):
    """Table 3 files of one velocity (500 m/s) per mesh: meshes lists (elements across, fs, {nose: depth})."""
    paper = {"double_ogive": 2.454, "crh45": 2.255, "crh3": 2.174}
    ratios, tables, cals = [], [], []
    for across, fs, depth in meshes:
        h = 0.07 / across
        t = tmp_path / f"table3_{across}.csv"
        pd.DataFrame({"velocity_ms": [500] * 3, "nose": list(NOSES), "fe_m": [depth[n] for n in NOSES],
                      "paper_sim_m": [paper[n] for n in NOSES], "element_size_m": [h] * 3}).to_csv(t, index=False)
        r = tmp_path / f"ratios_{across}.csv"
        rows = [(name, depth[a] / depth[b], paper[a] / paper[b]) for name, a, b in
                (("DO/CRH 4.5", "double_ogive", "crh45"), ("CRH 4.5/CRH 3", "crh45", "crh3"), ("DO/CRH 3", "double_ogive", "crh3"))]
        pd.DataFrame({"velocity_ms": [500] * 3, "contrast": [x[0] for x in rows], "fe_ratio": [x[1] for x in rows],
                      "paper_sim_ratio": [x[2] for x in rows]}).to_csv(r, index=False)
        c = tmp_path / f"cal_{across}.json"
        c.write_text(json.dumps({"element_size": h, "elements_across_radius": across, "fs": fs, "residual_m": 0.001}))
        tables.append(str(t)), ratios.append(str(r)), cals.append(str(c))
    outputs = SimpleNamespace(png=str(tmp_path / "b.png"), csv=str(tmp_path / "b.csv"), depths=str(tmp_path / "bd.csv"),
                              meshes=str(tmp_path / "bm.csv"))
    return SimpleNamespace(ratios=ratios, tables=tables, calibrations=cals), outputs


def test_band_statistics_against_hand_values(tmp_path):
    # four meshes; DO/CRH 4.5 ratios 1.0, 1.1, 1.2, 1.1 (mean 1.1, sample standard deviation sqrt(0.02/3));
    # CRH 4.5 and CRH 3 equal at every mesh
    inputs, outputs = _band_inputs(tmp_path, [(7.5, 1.0, {"double_ogive": 2.0, "crh45": 2.0, "crh3": 2.0}),
                                              (8.0, 1.1, {"double_ogive": 2.2, "crh45": 2.0, "crh3": 2.0}),
                                              (8.5, 1.2, {"double_ogive": 2.4, "crh45": 2.0, "crh3": 2.0}),
                                              (9.0, 0.9, {"double_ogive": 2.2, "crh45": 2.0, "crh3": 2.0})])
    fe_contrast_band(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95, bands=[("full", len(inputs.ratios))]))
    t = pd.read_csv(outputs.csv).set_index("contrast")
    r = t.loc["DO/CRH 4.5"]
    sd = math.sqrt(0.02 / 3)
    assert r.meshes == 4 and r.mean_ratio == pytest.approx(1.1) and r.std_ratio == pytest.approx(sd)
    half = 3.182446305284263 * sd / 2  # Student's t, 3 degrees of freedom, 97.5 % quantile, over sqrt(4)
    assert r.interval_low == pytest.approx(1.1 - half) and r.interval_high == pytest.approx(1.1 + half)
    assert r.mean_minus_paper_points == pytest.approx(100 * (1.1 - 2.454 / 2.255))
    assert bool(r.paper_inside_interval) and bool(r.within_2_points_goal)  # paper 1.088: 1.2 points under the mean
    assert (r.failure_strain_min, r.failure_strain_max) == (0.9, 1.2)
    c = t.loc["CRH 4.5/CRH 3"]
    assert c.std_ratio == 0.0 and not bool(c.paper_inside_interval) and not bool(c.within_2_points_goal)
    d = pd.read_csv(outputs.depths).set_index("nose")
    assert d.loc["double_ogive", "mean_m"] == pytest.approx(2.2)
    assert d.loc["double_ogive", "mean_rel_dev_pct"] == pytest.approx(100 * (2.2 / 2.454 - 1))
    assert bool(d.loc["double_ogive", "within_5pct_goal"]) is False  # -10.4 %
    m = pd.read_csv(outputs.meshes)
    assert len(m) == 12 and sorted(m.elements_across_radius.unique()) == [7.5, 8.0, 8.5, 9.0]
    assert set(t.band) == {"full"} and set(t.centre_elements_across) == {7.5}  # the first mesh is the centre


def test_bands_are_kept_apart(tmp_path):
    """Two bands of two meshes each: each band's statistics are its own meshes'."""
    inputs, outputs = _band_inputs(tmp_path, [(8.0, 1.0, {"double_ogive": 2.0, "crh45": 2.0, "crh3": 2.0}),
                                              (8.5, 1.0, {"double_ogive": 2.2, "crh45": 2.0, "crh3": 2.0}),
                                              (10.0, 1.1, {"double_ogive": 3.0, "crh45": 2.0, "crh3": 2.0}),
                                              (10.5, 1.1, {"double_ogive": 3.2, "crh45": 2.0, "crh3": 2.0})])
    fe_contrast_band(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95, bands=[("full", 2), ("fine", 2)]))
    t = pd.read_csv(outputs.csv)
    r = t[t.contrast == "DO/CRH 4.5"].set_index("band")
    assert r.loc["full", "mean_ratio"] == pytest.approx(1.05) and r.loc["fine", "mean_ratio"] == pytest.approx(1.55)
    assert r.loc["fine", "centre_elements_across"] == 10.0 and r.loc["full", "meshes"] == 2
    with pytest.raises(ValueError, match="bands"):
        fe_contrast_band(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95, bands=[("full", 2)]))


def test_band_rejects_a_table_of_another_mesh(tmp_path):
    inputs, outputs = _band_inputs(tmp_path, [(7.5, 1.0, dict.fromkeys(NOSES, 2.0)), (8.0, 1.0, dict.fromkeys(NOSES, 2.0))])
    t = pd.read_csv(inputs.tables[1])
    t["element_size_m"] = 0.007
    t.to_csv(inputs.tables[1], index=False)
    with pytest.raises(ValueError, match="element sizes"):
        fe_contrast_band(inputs, outputs, SimpleNamespace(dpi=50, confidence=0.95, bands=[("full", len(inputs.ratios))]))
