"""One FE run spec, built once; a paper case written once, with per-level overlays (scene ``extends``)."""
import dataclasses
import math
from pathlib import Path

import pytest

from penetration.errors import ParameterError
from penetration.fe.spec import Controls, RunSpec, Settings, TargetSpec
from penetration.pipeline.config import read_yaml
from penetration.pipeline.scenes import SceneError, merge_patch, read_scene, scene_data, scene_files

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow/schemas/scene.schema.json"


# ------------------------------------------------------------------ the run spec
@pytest.mark.parametrize("field, value, allowed", [("velocity", 0.0, "0 < velocity <= 3000"),
                                                   ("velocity", math.nan, "0 < velocity <= 3000"),
                                                   ("mass", -1.0, "> 0 (kg)"),
                                                   ("expected_depth", 0.0, "> 0 (m)"),
                                                   ("friction", 1.5, "0 <= friction <= 1")])
def test_a_run_spec_refuses_a_field_out_of_range_naming_it(field, value, allowed):
    good = dict(nose=None, mass=81.1, velocity=835.0, material=None)
    with pytest.raises(ParameterError, match=field) as err:
        RunSpec(**{**good, field: value})
    assert allowed in str(err.value)


def test_settings_from_a_config_slice_take_what_it_names_and_the_defaults_for_the_rest():
    """The level's defaults live in the dataclasses: the pipeline's fe slice names only what differs from them."""
    fe = read_yaml(ROOT / "workflow/config.yaml")["fe"]
    s = Settings.from_config(fe, None, 0.01)
    named = {k for k in fe if k in {f.name for f in dataclasses.fields(Settings)} | {f.name for f in dataclasses.fields(Controls)}}
    for f in dataclasses.fields(Settings):
        if f.name not in ("element_size", "controls") and f.name not in named:
            assert getattr(s, f.name) == f.default
    assert s.controls.end_time == fe["end_time"] != Controls().end_time
    changed = Settings.from_config({**fe, "grading": 1.2, "q1": 1.0}, None, 0.01)
    assert changed.grading == 1.2 and changed.controls.q1 == 1.0 and s.grading == Settings().grading


def test_the_config_repeats_no_default_of_the_level():
    """A key of the fe slice that equals its dataclass default says nothing: the defaults are written once."""
    fe = read_yaml(ROOT / "workflow/config.yaml")["fe"]
    defaults = {f.name: f.default for cls in (Settings, Controls) for f in dataclasses.fields(cls)
                if f.default is not dataclasses.MISSING}
    assert not [k for k, v in fe.items() if k in defaults and defaults[k] == v]


def test_with_failure_strain_sets_erosion_on_the_plastic_strain_and_nothing_else():
    spec = RunSpec(None, 81.1, 835.0, None)
    new = spec.with_failure_strain(0.9)
    assert new.settings.controls.erosion == "plastic_strain" and new.settings.controls.erosion_value == 0.9
    assert dataclasses.replace(new.settings, controls=spec.settings.controls) == spec.settings
    assert spec.settings.controls.erosion == "none"


def test_a_scene_target_takes_its_kinds_size_unless_the_scene_sets_it():
    assert TargetSpec.from_scene({}, 1.2, 5.4) == TargetSpec("semi_infinite", 1.2, None)
    block = TargetSpec.from_scene({"target": "block"}, 1.2, 5.4)
    assert block.kind == "block" and block.radius == pytest.approx(3.6 / math.sqrt(math.pi)) and block.depth == 5.4
    assert block.boundary("lateral") == "free"
    s = TargetSpec.from_scene({"target": "block", "target_depth": 3.0, "bottom_boundary": "non_reflecting"}, 1.2, 5.4)
    assert s.depth == 3.0 and s.boundary("bottom") == "non_reflecting"


# ------------------------------------------------------------------ a paper case written once
def test_merge_patch_follows_rfc_7386():
    """The examples of RFC 7386, section 3, and key order: a key keeps its place, new keys follow."""
    assert merge_patch({"a": "b"}, {"a": "c"}) == {"a": "c"}
    assert merge_patch({"a": "b"}, {"b": "c"}) == {"a": "b", "b": "c"}
    assert merge_patch({"a": "b"}, {"a": None}) == {}
    assert merge_patch({"a": "b", "b": "c"}, {"a": None}) == {"b": "c"}
    assert merge_patch({"a": ["b"]}, {"a": "c"}) == {"a": "c"}
    assert merge_patch({"a": {"b": "c"}}, {"a": {"b": "d", "c": None}}) == {"a": {"b": "d"}}
    assert merge_patch({"a": [{"b": "c"}]}, {"a": [1]}) == {"a": [1]}
    assert merge_patch({"e": None}, {"a": 1}) == {"e": None, "a": 1}
    assert merge_patch({"a": "foo"}, None) is None
    assert list(merge_patch({"x": 1, "y": 2}, {"z": 3, "x": 4})) == ["x", "y", "z"]


@pytest.mark.parametrize("case", ["table3", "do1", "fig15"])
def test_each_levels_scene_of_a_paper_case_extends_the_case(case):
    """The paper's case (projectile, noses, target) is written once; the cavity and fe scenes of it write only what
    their level changes, and read as the case with those changes."""
    base = read_scene(ROOT / f"workflow/scenes/{case}.yaml", SCHEMA)
    for level in ("cavity", "fe"):
        path = ROOT / f"workflow/scenes/{level}/{case}.yaml"
        assert [Path(f).resolve() for f in scene_files(path)] == [path.resolve(), (ROOT / f"workflow/scenes/{case}.yaml").resolve()]
        raw = read_yaml(path)
        assert "projectile" not in raw and "noses" not in raw
        scene = read_scene(path, SCHEMA)
        assert scene["level"] == level
        assert scene["projectile"] == base["projectile"] and scene["noses"] == base["noses"]
        assert {k: v for k, v in scene["target"].items() if k != "strength"} == \
            {k: v for k, v in base["target"].items() if k != "strength"}


def test_a_broken_extends_is_refused_naming_the_file(tmp_path):
    (tmp_path / "a.yaml").write_text("extends: b.yaml\nlevel: fe\n")
    with pytest.raises(SceneError, match="no such file"):
        scene_data(tmp_path / "a.yaml")
    (tmp_path / "b.yaml").write_text("extends: a.yaml\n")
    with pytest.raises(SceneError, match="cycle"):
        scene_data(tmp_path / "a.yaml")
    (tmp_path / "c.yaml").write_text("extends: [b.yaml]\n")
    with pytest.raises(SceneError, match="c.yaml: extends"):
        scene_data(tmp_path / "c.yaml")


def test_rules_take_the_files_a_scene_extends_as_inputs(monkeypatch):
    """A change to the paper's case reruns every level's scene of it."""
    from penetration.pipeline.dispatch import scene_input
    monkeypatch.chdir(ROOT)
    got = scene_input("workflow/scenes/fe/table3.yaml")
    assert got["scene"] == "workflow/scenes/fe/table3.yaml" and got["scene_bases"] == ["workflow/scenes/table3.yaml"]
    wild = scene_input("workflow/scenes/cavity/{scene}.yaml")

    class W(dict):
        pass
    assert wild["scene_bases"](W(scene="do1")) == ["workflow/scenes/do1.yaml"]
    assert scene_input("workflow/scenes/sec22_450kg.yaml")["scene_bases"] == []


def test_tasks_and_figures_read_scenes_and_configs_through_their_loaders():
    """A scene read as plain YAML misses the case it extends (a KeyError on its noses); every task and figure module
    reads scenes through penetration.pipeline.scenes and configs through penetration.pipeline.config, never yaml itself."""
    import ast
    pkg = ROOT / "src/penetration"
    readers = []
    for f in sorted((pkg / "tasks").glob("*.py")) + sorted((pkg / "figures").glob("*.py")):
        for node in ast.walk(ast.parse(f.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(n.split(".")[0] == "yaml" for n in names):
                readers.append(f.name)
    assert readers == []
