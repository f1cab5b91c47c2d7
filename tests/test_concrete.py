"""The target concrete (penetration.concrete.material): Table 1 as the reference table states it, the configured conventions,
the scenes' material switches, the strength scaling and the calibration, built in one place for every level."""
import ast
import csv
import dataclasses
import json
import math
import re
from pathlib import Path
from types import SimpleNamespace

import pytest
import yaml

from penetration.concrete import material as concrete
from penetration.concrete.effects import MATERIAL_EFFECTS
from penetration.concrete.hjc import HJC
from penetration.errors import ParameterError
from penetration.paper.reference import load_reference

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "src/penetration"
CONFIG = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
REFS = load_reference(ROOT / CONFIG["reference"])
# HJC field -> the row of the reference table it comes from, as the paper states them: Table 1's column "K" is the
# shear modulus of the 1993 HJC set, and the reference strain rate is the text's 1/s (Table 1 misprints 6)
PAPER = {"rho0": "rho", "G": "K", "A": "A", "B": "B", "C": "C", "N": "N", "fc": "fc", "T": "T", "eps0": "eps0_text",
         "efmin": "efmin", "smax": "smax", "pc": "pc", "muc": "muc", "pl": "pl", "mul": "mul", "D1": "D1", "D2": "D2",
         "k1": "k1", "k2": "k2", "k3": "k3"}
SI = {"GPa": 1e9, "MPa": 1e6, "kg/m3": 1.0, "1": 1.0, "1/s": 1.0}


def table1_rows():
    """Table 1's rows of the reference CSV in SI, read here with the csv module and this file's unit factors."""
    with open(ROOT / CONFIG["reference"], newline="") as fh:
        return {r["id"]: float(r["value"]) * SI[r["unit"]] for r in csv.DictReader(fh) if r["item"] == "table1"
                and r["unit"] in SI}


def configured():
    return concrete.configured(REFS, CONFIG["concrete"])


# ------------------------------------------------------------------ Table 1 and the conventions
def test_the_built_set_carries_table1_as_the_reference_table_states_it():
    rows = table1_rows()
    m = configured()
    for field, quantity in PAPER.items():
        assert getattr(m, field) == pytest.approx(rows[f"table1.{quantity}"], rel=1e-15), field
    # the paper's numbers themselves, in SI
    assert (m.rho0, m.fc, m.G, m.T, m.pc, m.pl, m.k2) == (2440.0, 48e6, 14.86e9, 4e6, 16e6, 0.8e9, -171e9)


def test_each_field_is_read_from_its_own_row():
    """Every Table 1 row made distinct: each field carries the value of the row the paper names for it."""
    refs = {f"table1.{q}": SimpleNamespace(si=REFS[f"table1.{q}"].si * (1 + 1e-3 * (i + 1)))
            for i, q in enumerate(PAPER.values())}
    m = concrete.table1(refs)
    for field, quantity in PAPER.items():
        assert getattr(m, field) == refs[f"table1.{quantity}"].si, field


def test_the_conventions_are_the_config_sections_and_the_rest_is_hjc_default():
    m = configured()
    for key in concrete.CONVENTIONS:
        assert getattr(m, key) == CONFIG["concrete"][key]
    default = HJC()
    for f in dataclasses.fields(HJC):
        if f.name not in PAPER and f.name not in concrete.CONVENTIONS:
            assert getattr(m, f.name) == getattr(default, f.name), f.name


@pytest.mark.parametrize("lock", ["offset", "literal", "extended"])
@pytest.mark.parametrize("tension", ["openradioss", "sphinxsys"])
@pytest.mark.parametrize("rate_floor", [True, False])
def test_every_allowed_convention_is_carried(lock, tension, rate_floor):
    m = concrete.configured(REFS, {"lock": lock, "tension": tension, "rate_floor": rate_floor})
    assert (m.lock, m.tension, m.rate_floor) == (lock, tension, rate_floor)


def test_one_config_section_holds_the_conventions():
    """The schema's concrete section is the conventions, and no other section names one."""
    schema = json.loads((ROOT / "workflow/schemas/config.schema.json").read_text())
    assert set(schema["properties"]["concrete"]["properties"]) == set(concrete.CONVENTIONS)
    for name, section in schema["properties"].items():
        if name != "concrete" and isinstance(section, dict):
            assert not set(section.get("properties", {})) & set(concrete.CONVENTIONS), name


def test_every_rule_passes_the_concrete_section_as_its_material():
    text = "\n".join(p.read_text() for p in sorted((ROOT / "workflow/rules").glob("*.smk")))
    passed = re.findall(r"\bhjc=([^,\n]+)", text)
    assert passed and set(passed) == {'config["concrete"]'}


# ------------------------------------------------------------------ material switches
@pytest.mark.parametrize("effect", sorted(MATERIAL_EFFECTS))
def test_each_material_switch_changes_exactly_the_field_it_names(effect):
    others = [e for e in MATERIAL_EFFECTS if e != effect]
    switches = concrete.material_switches(("crater", "cavity", *others), {}, CONFIG["concrete"])
    assert switches == MATERIAL_EFFECTS[effect]
    before, after = dataclasses.asdict(configured()), dataclasses.asdict(concrete.configured(REFS, CONFIG["concrete"],
                                                                                             **switches))
    changed = {k for k in before if before[k] != after[k]}
    assert changed == set(MATERIAL_EFFECTS[effect])
    assert all(after[k] == v for k, v in MATERIAL_EFFECTS[effect].items())


def test_a_scene_listing_every_material_effect_gets_the_configured_concrete():
    assert concrete.material_switches(("crater", "cavity", *MATERIAL_EFFECTS), {}, CONFIG["concrete"]) == {}


@pytest.mark.parametrize("named,expected", [
    ({"lock": "literal"}, {"lock": "literal"}),
    ({"tension": "sphinxsys"}, {"tension": "sphinxsys"}),
    ({"lock": CONFIG["concrete"]["lock"]}, {}),   # the configured convention: no switch
])
def test_a_named_convention_changes_that_convention_only(named, expected):
    switches = concrete.material_switches(("crater", "cavity", *MATERIAL_EFFECTS), named, CONFIG["concrete"])
    assert switches == expected
    before = dataclasses.asdict(configured())
    after = dataclasses.asdict(concrete.configured(REFS, CONFIG["concrete"], **switches))
    assert {k for k in before if before[k] != after[k]} == set(expected)


# ------------------------------------------------------------------ strength scaling and calibration
@pytest.mark.parametrize("fc", [20e6, 32.4e6, 48e6, 101.4e6, 200e6])
def test_a_strength_scaling_gives_the_fc_and_density_asked_for(fc):
    m = concrete.shot_concrete(configured(), fc, 2300.0)
    assert m.fc == fc and m.rho0 == 2300.0 and m.strength_scale == 1.0
    assert m.pc == pytest.approx(fc / 3, rel=1e-14)  # Holmquist, Johnson & Cook (1993): pc = fc/3


def test_table1_comes_back_exactly_at_48_mpa_and_the_calibration_sets_only_the_strength_scale():
    base = configured()
    assert concrete.shot_concrete(base, 48e6, 2440.0) == base
    m = concrete.shot_concrete(base, 48e6, 2440.0, 0.55)
    assert m == dataclasses.replace(base, strength_scale=0.55)


def test_the_levels_build_the_pipelines_concrete():
    """The command line's cavity and fe levels, on Table 1's concrete, use the sets the pipeline's cavity and fe
    levels build from the same config section."""
    from penetration.nose.geometry import Ogive
    from penetration.shots.ladder import Context, UserShot, cavity_material, fe_material
    base = configured()
    ctx = Context(base=base, strength_scale=0.6)
    shot = UserShot(Ogive(3.0, 0.07), 81.1, 800.0, base.fc, base.rho0)
    assert cavity_material(shot, ctx) == concrete.configured(REFS, CONFIG["concrete"], strength_scale=0.6)
    assert fe_material(shot, ctx) == concrete.configured(REFS, CONFIG["concrete"])


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize("cfg,field,allowed", [
    ({"tension": "openradioss", "rate_floor": True}, "lock", "required"),
    ({"lock": "loose", "tension": "openradioss", "rate_floor": True}, "lock", "extended"),
    ({"lock": "offset", "tension": "mohr", "rate_floor": True}, "tension", "sphinxsys"),
    ({"lock": "offset", "tension": "openradioss", "rate_floor": "yes"}, "rate_floor", "true or false"),
    ({"lock": "offset", "tension": "openradioss", "rate_floor": True, "smax": 6.0}, "smax", "rate_floor"),
])
def test_a_bad_concrete_section_names_the_field_and_what_is_allowed(cfg, field, allowed):
    with pytest.raises(ParameterError) as err:
        concrete.configured(REFS, cfg)
    assert err.value.owner == "concrete" and err.value.name == field
    assert f"concrete.{field}" in str(err.value) and allowed in str(err.value)


def test_an_unknown_field_or_convention_is_refused_by_name():
    with pytest.raises(ParameterError, match="concrete.erosion = .*HJC field"):
        concrete.table1(REFS, erosion=0.5)
    with pytest.raises(ParameterError, match="scene.D1 = .*lock"):
        concrete.material_switches(("cavity",), {"D1": 0.05}, CONFIG["concrete"])


@pytest.mark.parametrize("fc", [10e6, 250e6, math.nan])
def test_a_strength_outside_the_rule_is_refused_with_its_range(fc):
    with pytest.raises(ParameterError) as err:
        concrete.shot_concrete(configured(), fc)
    assert err.value.name == "fc_MPa" and "20" in str(err.value) and "200" in str(err.value)


@pytest.mark.parametrize("scale", [0.0, -0.5, math.inf])
def test_a_strength_scale_outside_its_range_is_refused(scale):
    with pytest.raises(ParameterError, match="strength_scale"):
        concrete.shot_concrete(configured(), 48e6, strength_scale=scale)


# ------------------------------------------------------------------ where it sits
def _imports(path):
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            found.add((node.level, node.module or "", tuple(a.name for a in node.names)))
        elif isinstance(node, ast.Import):
            found.update((0, a.name, ()) for a in node.names)
    return found


def test_concrete_sits_below_the_levels_and_reads_no_file():
    """It composes hjc (and the material effects' registry) with the error type and the units, nothing else."""
    modules = {(level, m) for level, m, names in _imports(PKG / "concrete/material.py") if level}
    outside = {m.split(".")[0] for level, m, _ in _imports(PKG / "concrete/material.py") if not level}
    assert modules <= {(2, "errors"), (2, "units"), (1, "hjc"), (1, "effects")}
    assert outside <= {"__future__", "dataclasses", "math"}


def test_the_concrete_is_built_in_one_place():
    """Table 1 is read, the switches decided and the strength scaled only in concrete/material.py (hjc.from_table1 is the
    model's own constructor from a Table 1 look-up)."""
    for path in sorted(PKG.rglob("*.py")):
        if path.relative_to(PKG).as_posix() in ("concrete/material.py", "concrete/hjc.py"):
            continue
        tree = ast.parse(path.read_text())
        defined = {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
        assert not defined & {"material_switches", "hjc_for_strength", "configured_hjc", "table1_hjc"}, path
        calls = [n.func for n in ast.walk(tree) if isinstance(n, ast.Call)]
        called = {f.id for f in calls if isinstance(f, ast.Name)} | {f.attr for f in calls if isinstance(f, ast.Attribute)}
        assert "from_table1" not in called, path


def test_no_task_module_imports_a_sibling_for_the_concrete_or_the_do1_shot():
    physics = {"configured", "material_switches", "table1", "hjc_for_strength", "do1_shot", "calibration_row",
               "cavity_settings", "configured_hjc", "table1_hjc"}
    for path in sorted((PKG / "tasks").glob("*.py")):
        for level, module, names in _imports(path):
            if level == 1 and module and module != "common":
                assert not set(names) & physics, f"{path.name} imports {set(names) & physics} from tasks.{module}"
    for name in ("fe", "levels"):  # the FE level and the users' shots take nothing from the cavity stage's tasks
        assert not any(level == 1 and m == "cavity" for level, m, _ in _imports(PKG / f"tasks/{name}.py")), name
