"""The erosion-free target's DO1 strength-scale calibration: the secant finds a known scale, a scene takes the scale
only from a record of its own mesh and target, and the calibrated depths table compares one change."""
import json
from pathlib import Path
from types import SimpleNamespace

import pytest
import yaml

from penetration.fe import level as fe_level
from penetration.fe.shot import RunSpec
from penetration.nose.geometry import Ogive
from penetration.paper import reference
from penetration.pipeline.dispatch import fe_calibrated_scenes
from penetration.pipeline.scenes import read_scene, resolve

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow/schemas/scene.schema.json"
CONFIG = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
REFS = reference.load_reference(ROOT / CONFIG["reference"])


def fake_depths(monkeypatch, calls):
    """run_shot replaced by a depth that falls with the strength scale k as a power law with a 0.3 % wobble,
    5.1 (0.55 / k)^0.7: the root is k = 0.55 (the material of each trial is read from its spec)."""
    import math

    def run_shot(spec, **kw):
        k = spec.material.strength_scale
        calls.append(k)
        depth = 5.1 * (0.55 / k) ** 0.7 * (1 + 0.003 * math.sin(40 * k))
        return SimpleNamespace(depth=depth, wall_time=1.0, status="rest", peak_deceleration=1.0, elements=10, steps=10,
                               summary=lambda: {"energy_error_max": 0.0})

    monkeypatch.setattr(fe_level, "run_shot", run_shot)


def test_the_strength_scale_secant_finds_a_known_scale_and_refuses_a_bracket_that_misses(monkeypatch):
    from penetration.concrete import material as concrete
    calls = []
    fake_depths(monkeypatch, calls)
    material = lambda k: concrete.configured(REFS, CONFIG["concrete"], strength_scale=k)
    spec = RunSpec(None, 81.1, 835.0, material(1.0))
    fit = fe_level.calibrate_strength_scale(spec, 5.1, material, bracket=(0.2, 2.0), tol_m=0.02)
    assert fit["converged"] and abs(fit["residual_m"]) <= 0.02
    assert fit["strength_scale"] == pytest.approx(0.55, rel=0.02)
    assert calls[:2] == pytest.approx([0.2, 2.0]) and len(calls) <= 10
    assert [r["strength_scale"] for r in fit["runs"]] == pytest.approx(calls)
    with pytest.raises(ValueError, match="no strength_scale in"):
        fe_level.calibrate_strength_scale(spec, 5.1, material, bracket=(1.0, 2.0))


def _scene(name):
    data = read_scene(ROOT / f"workflow/scenes/fe/{name}.yaml", SCHEMA, ("fe",))
    return resolve(name, data, {"table4_do1": Ogive(4.5, 0.07)}, {}, {})


def _fe_cfg(h):
    """The fe config slice of a profile of element size h (as the Snakefile's fe_cfg joins one)."""
    return {**CONFIG["fe"], "profiles": {f"free{round(0.07 / h * 100)}": {"element_size": h, "mesh_study_sizes": [h]}}}


def _record(h, hole=0.125, formulation="erosion_free", scale=0.6, domain="whole"):
    return {"strength_scale": scale, "element_size": h, "domain": domain,
            "data": {"target": {"formulation": formulation, "pilot_hole": hole}}}


def test_a_scene_takes_the_strength_scale_only_from_a_record_of_its_own_mesh_and_target():
    sc = _scene("table3_erosion_free_calibrated")
    h = 0.07 / 16.0
    args = (sc, "crh3", 500.0, REFS, CONFIG["concrete"], _fe_cfg(h), "free1600", 2.0)
    spec, notes = fe_level.scene_spec(*args, _record(h))
    assert spec.material.strength_scale == 0.6 and notes["strength_scale"] == 0.6
    assert spec.target.formulation == "erosion_free" and spec.target.pilot_hole == 0.125
    assert spec.settings.controls.erosion == "none"
    # the stated scene: the same material but for the scale
    stated, notes0 = fe_level.scene_spec(_scene("table3_erosion_free_hole125"), *args[1:])
    assert stated.material.strength_scale == 1.0 and notes0["strength_scale_provenance"].startswith("none")
    assert stated.material == spec.material.__class__(**{**vars(spec.material), "strength_scale": 1.0})
    with pytest.raises(ValueError, match="needs the DO1 calibration"):
        fe_level.scene_spec(*args)
    with pytest.raises(ValueError, match="element size"):
        fe_level.scene_spec(*args, _record(0.07 / 12.8))
    with pytest.raises(ValueError, match="pilot_hole"):
        fe_level.scene_spec(*args, _record(h, hole=0.25))
    # a scale fitted with the moving window belongs to another run than the scene's whole domain
    with pytest.raises(ValueError, match="'domain': 'window'"):
        fe_level.scene_spec(*args, _record(h, domain="window"))
    assert fe_level.scene_spec(*args, _record(h, domain="window"), domain="window")[0].settings.window_ahead == 1.5


def test_the_erosion_free_scenes_compute_every_row_and_a_domain_override_restores_the_window():
    h = 0.07 / 8.192
    cfg = _fe_cfg(h)
    for name in CONFIG["fe_erosion_free"]["scenes"]:
        sc = _scene(name)
        whole = fe_level.scene_settings(sc, cfg, "free819")
        assert (whole.window_ahead, whole.window_tail) == (None, None) and fe_level.domain_of(whole) == "whole"
        window = fe_level.scene_settings(sc, cfg, "free819", "window")
        assert (window.window_ahead, window.window_tail) == (1.5, 0.5) and fe_level.domain_of(window) == "window"
        assert whole.element_size == window.element_size == h
    # the eroding Table 3 keeps the window; a domain that does not exist is refused by name
    eroding = read_scene(ROOT / "workflow/scenes/fe/table3.yaml", SCHEMA, ("fe",))
    sc = resolve("table3", eroding, {"table4_do1": Ogive(4.5, 0.07)}, {}, {})
    assert fe_level.domain_of(fe_level.scene_settings(sc, cfg, "free819")) == "window"
    with pytest.raises(ValueError, match="fe.domain = 'all'; allowed: window, whole"):
        fe_level.scene_settings(sc, cfg, "free819", "all")


def test_an_eroding_scene_cannot_take_a_strength_scale_calibration(tmp_path):
    data = read_scene(ROOT / "workflow/scenes/fe/table3_erosion_free_calibrated.yaml", SCHEMA, ("fe",))
    data["fe"] = {"target": "semi_infinite", "strength_scale": "calibrated"}
    sc = resolve("eroding", data, {"table4_do1": Ogive(4.5, 0.07)}, {}, {})
    with pytest.raises(ValueError, match="erosion_free target only"):
        fe_level.scene_spec(sc, "crh3", 500.0, REFS, CONFIG["concrete"], _fe_cfg(0.00875), "free800", 2.0,
                            _record(0.00875))


def test_the_shipped_calibrated_scene_is_found_and_differs_from_its_base_by_the_scale_only():
    folder = ROOT / "workflow/scenes/fe"
    assert fe_calibrated_scenes(folder, SCHEMA, "strength_scale") == {CONFIG["fe_erosion_free"]["calibration"]["scene"]}
    assert "table3_erosion_free_calibrated" not in fe_calibrated_scenes(folder, SCHEMA)
    a = read_scene(folder / "table3_erosion_free_calibrated.yaml", SCHEMA, ("fe",))
    b = read_scene(folder / "table3_erosion_free_hole125.yaml", SCHEMA, ("fe",))
    a["fe"].pop("strength_scale")
    assert {k: v for k, v in a.items() if k != "description"} == {k: v for k, v in b.items() if k != "description"}


def _shot(nose, v, depth, hole=0.125, h=0.004375, scale=None):
    s = {"nose": nose, "velocity": v, "depth_m": depth, "element_size": h, "status": "rest", "energy_error_max": 1e-4,
         "target": {"formulation": "erosion_free", "pilot_hole": hole}}
    if scale is not None:
        s["strength_scale"] = scale
    return s


def _run_table(tmp_path, shots, stated):
    from penetration.tasks.fe_erosion_free import fe_erosion_free_calibrated
    cal = {"calibration": "fe_strength_do1", "fitted_quantity": "HJC strength_scale", "strength_scale": 0.6,
           "element_size": 0.004375, "elements_across_radius": 16.0, "residual_m": 0.01, "relative_residual": 0.002,
           "converged": True, "runs": [{}, {}, {}],
           "data": {"measured_depth": 5.1, "vs": 835.0, "mass": 81.1, "nose": "table4_do1",
                    "target": {"formulation": "erosion_free", "pilot_hole": 0.125}}}
    paths = {}
    for name, items in (("cal", [cal]), ("shots", shots), ("stated", stated)):
        paths[name] = []
        for i, item in enumerate(items):
            p = tmp_path / f"{name}{i}.json"
            p.write_text(json.dumps(item))
            paths[name].append(str(p))
    inputs = SimpleNamespace(reference=str(ROOT / CONFIG["reference"]), cal=paths["cal"][0], shots=paths["shots"],
                             stated=paths["stated"])
    outputs = SimpleNamespace(csv=str(tmp_path / "calibrated.csv"), calibration=str(tmp_path / "calibration.csv"))
    fe_erosion_free_calibrated(inputs, outputs, SimpleNamespace())
    return outputs


def test_the_calibrated_depths_table_sets_each_shot_beside_its_stated_twin_and_the_paper(tmp_path):
    import pandas as pd
    out = _run_table(tmp_path, [_shot("crh3", 500.0, 2.0, scale=0.6), _shot("crh3", 1200.0, 7.0, scale=0.6)],
                     [_shot("crh3", 1200.0, 5.0), _shot("crh3", 500.0, 1.4)])
    t = pd.read_csv(out.csv)
    assert list(t.velocity_ms) == [500.0, 1200.0]
    assert list(t.depth_stated_hjc_m) == [1.4, 5.0] and list(t.depth_calibrated_m) == [2.0, 7.0]
    paper = [REFS["table3.sim.500.crh3"].si, REFS["table3.sim.1200.crh3"].si]
    assert list(t.paper_depth_m) == paper
    assert t.calibrated_over_paper.tolist() == pytest.approx([2.0 / paper[0], 7.0 / paper[1]], rel=1e-15)
    c = pd.read_csv(out.calibration)
    assert c.parameter[0] == "strength_scale" and c.value[0] == 0.6 and c.residual_m[0] == 0.01 and c.trials[0] == 3
    with pytest.raises(ValueError, match="pilot_hole"):
        _run_table(tmp_path, [_shot("crh3", 500.0, 2.0, scale=0.6)], [_shot("crh3", 500.0, 1.4, hole=0.25)])
    with pytest.raises(ValueError, match="no shot with the stated HJC"):
        _run_table(tmp_path, [_shot("crh3", 500.0, 2.0, scale=0.6)], [_shot("crh45", 500.0, 1.4)])


@pytest.mark.parametrize("formulation", ["erosion_free", "eroding"])
def test_a_stopped_erosion_free_shot_is_recorded_and_a_stopped_eroding_shot_fails(monkeypatch, tmp_path, formulation):
    """The grid study's shot that stops is its result (status stopped, the diagnostic, no depth, empty tables); an
    eroding shot that stops fails its job."""
    import math

    from penetration.fe.solver import Unstable
    from penetration.tasks import fe as tasks_fe

    def stop(inputs, params):
        raise Unstable("element 7 (i 0, j 3) at r = 0.01 m, z = 0.3 m lost its shape inside the target at t = 3e-4 s")

    fe = {"target": "semi_infinite", "formulation": formulation, "pilot_hole": 0.125}
    monkeypatch.setattr(tasks_fe, "scene_shot", stop)
    monkeypatch.setattr(tasks_fe, "scene_from_inputs", lambda inputs, levels, size=None: SimpleNamespace(name="s", mass=81.1, fe=fe))
    outputs = SimpleNamespace(**{k: str(tmp_path / f"{k}.csv") for k in ("histories", "fields", "audit")},
                              json=str(tmp_path / "shot.json"))
    params = SimpleNamespace(cfg=_fe_cfg(0.07 / 16), profile="free1600", nose="crh3", velocity="1200")
    if formulation == "eroding":
        with pytest.raises(Unstable):
            tasks_fe.fe_shot(SimpleNamespace(), outputs, params)
        return
    tasks_fe.fe_shot(SimpleNamespace(), outputs, params)
    rec = json.loads(Path(outputs.json).read_text())
    assert rec["status"] == "stopped" and "lost its shape" in rec["diagnostic"] and math.isnan(rec["depth_m"])
    assert rec["target"]["pilot_hole"] == 0.125 and rec["element_size"] == 0.07 / 16 and rec["eroded_mass_kg"] == 0.0
    import pandas as pd
    assert len(pd.read_csv(outputs.histories)) == 0 and list(pd.read_csv(outputs.fields).columns)[:2] == ["r0", "z0"]


@pytest.mark.parametrize("task", ["calibrate_fe_strength_do1", "calibrate_fe_do1"])
def test_the_do1_calibration_tasks_record_their_fit_and_resume_from_their_trials(tmp_path, monkeypatch, task):
    """Both DO1 calibrations through their tasks, with the FE shot replaced by a depth law whose root is known
    (strength scale 0.55; failure strain 0.6): the record holds the fit, DO1's data, the mesh and what the value is
    bound to; run again, every trial comes from the kept trials and no shot runs."""
    import math

    from penetration.pipeline.io import nose_record
    from penetration.tasks import fe as fe_tasks
    calls = []

    def run_shot(spec, **kw):
        calls.append(spec)
        x = (spec.material.strength_scale / 0.55) ** 0.7 if task == "calibrate_fe_strength_do1" else \
            (spec.settings.controls.erosion_value / 0.6) ** 0.5
        return SimpleNamespace(depth=5.1 / x * (1 + 0.003 * math.sin(40 * x)), wall_time=1.0, status="rest",
                               peak_deceleration=1.0, elements=10, steps=10, summary=lambda: {"energy_error_max": 0.0})

    monkeypatch.setattr(fe_level, "run_shot", run_shot)
    nose = tmp_path / "do1.json"
    nose.write_text(json.dumps({"nose": nose_record(Ogive(4.5, 0.07))}))
    h = 0.07 / 16.0
    scene = ROOT / "workflow/scenes/fe/table3_erosion_free_calibrated.yaml"
    inputs = SimpleNamespace(reference=str(ROOT / CONFIG["reference"]), do1=str(nose), fig4=str(nose), scene=str(scene),
                             schema=str(SCHEMA))
    params = SimpleNamespace(cfg=_fe_cfg(h), hjc=CONFIG["concrete"], shot=CONFIG["calibration"]["do1"],
                             profile="free1600", bracket=[0.35, 0.75], size=h)
    outputs = SimpleNamespace(json=str(tmp_path / "out" / "calibration.json"))
    getattr(fe_tasks, task)(inputs, outputs, params)
    rec = json.loads(Path(outputs.json).read_text())
    key, root = ("strength_scale", 0.55) if task == "calibrate_fe_strength_do1" else ("fs", 0.6)
    assert rec[key] == pytest.approx(root, rel=0.03) and abs(rec["residual_m"]) <= CONFIG["fe"]["calibration_tol_m"]
    assert rec["element_size"] == h and rec["elements_across_radius"] == pytest.approx(16.0, rel=1e-12)
    mass, vs, depth = (REFS[CONFIG["calibration"]["do1"][q]].si for q in ("mass", "velocity", "depth"))
    assert rec["data"] | {"target": None} == {"measured_depth": depth, "vs": vs, "mass": mass, "nose": "table4_do1",
                                              "target": None}
    assert rec["profile"] == "free1600" and len(rec["runs"]) == len(calls) >= 2
    if key == "fs":
        assert rec["data"]["target"] == "semi_infinite" and rec["calibration"] == "fe_do1"
        assert "domain" not in rec and "scene" not in rec   # the eroding record as before
        assert all(s.target.formulation == "eroding" for s in calls)
    else:
        assert rec["data"]["target"]["pilot_hole"] == 0.125 and rec["domain"] == "whole"
        assert rec["scene"] == "table3_erosion_free_calibrated" and rec["calibration"] == "fe_strength_do1"
        assert all(s.settings.window_ahead is None and s.target.formulation == "erosion_free" for s in calls)
    n = len(calls)
    Path(outputs.json).unlink()
    getattr(fe_tasks, task)(inputs, outputs, params)
    assert len(calls) == n and json.loads(Path(outputs.json).read_text())[key] == rec[key]
