"""Bad input never passes silently: each case is a clear error (field, value, allowed range), nothing written.

The command line exits with status 2; scene and config errors name the file
and the field before any computation starts.
"""
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from penetration.pipeline.config import ConfigError, check_config, load_check
from penetration.pipeline.scenes import SceneError, read_scene, scene_data

ROOT = Path(__file__).resolve().parents[1]
SCENE_SCHEMA = ROOT / "workflow/schemas/scene.schema.json"
SHOTS = ROOT / "workflow/data/experiments-dev.csv"


def cli(*args, cwd=ROOT):
    """The command line, run in this process (conftest.run_cli)."""
    from conftest import run_cli
    return run_cli(*args, cwd=cwd)


# ------------------------------------------------------------------ nstar
@pytest.mark.parametrize("args,needle", [
    (("ogive", "psi=1e16", "radius=0.07"), "0.5 <= psi <= 1e+06"),
    (("ogive", "psi=3", "radius=1e300"), "radius <= 1000 m"),
    (("ogive", "psi=3", "radius=1e-300"), "1e-06 <= radius"),
    (("ogive", "psi=3", "psi=4", "radius=0.07"), "each key once"),
    (("cone", "radius=0.07", "length=nan"), "length"),
    (("double_ogive", "radius=0.07", "S1=1e300", "S2=0.42", "a1=0.0397", "a2=0.0638"), "S1"),
])
def test_nstar_out_of_range(args, needle):
    out = cli("nstar", *args)
    assert out.returncode == 2 and needle in out.stderr and "allowed" in out.stderr and out.stdout == ""


def test_nstar_binary_table(tmp_path):
    path = tmp_path / "nose.csv"
    path.write_bytes(bytes(range(256)) * 4)
    out = cli("nstar", "table", f"path={path}")
    assert out.returncode == 2 and "UTF-8 text CSV" in out.stderr


# ----------------------------------------------------------------- predict
def shots_file(tmp_path, text):
    path = tmp_path / "shots.csv"
    path.write_text(text)
    return path


def header():
    return SHOTS.read_text().splitlines()[0]


def good_row():
    return SHOTS.read_text().splitlines()[1]


def test_predict_refuses_to_overwrite_its_input(tmp_path):
    path = shots_file(tmp_path, f"{header()}\n{good_row()}\n")
    before = path.read_text()
    out = cli("predict", str(path), "--out", str(path))
    assert out.returncode == 2 and "--out" in out.stderr and path.read_text() == before


def test_predict_writes_nothing_when_every_row_is_bad(tmp_path):
    path = shots_file(tmp_path, f"{header()}\n" + good_row().replace(",ogive,", ",spike,") + "\n")
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 2 and "nose_shape" in out.stderr and "nothing written" in out.stderr
    assert not (tmp_path / "out.csv").exists()


def test_predict_rows_with_extra_or_missing_fields_are_skipped_without_leftovers(tmp_path):
    path = shots_file(tmp_path, f"{header()}\n{good_row()}\n{good_row()},surplus\nDZ1,short\n")
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 0 and "row 3: 14 fields, the header has 13" in out.stderr
    assert "row 4: 2 fields, the header has 13" in out.stderr
    assert len((tmp_path / "out.csv").read_text().splitlines()) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.csv", "shots.csv"]  # no temporary file left


def test_predict_unwritable_out_is_blamed_on_out(tmp_path):
    path = shots_file(tmp_path, f"{header()}\n{good_row()}\n")
    deep = tmp_path / "missing" / "dir" / "x.csv" / "y.csv"
    out = cli("predict", str(path), "--out", str(deep))      # missing folders are made, not blamed
    assert out.returncode == 0 and len(deep.read_text().splitlines()) == 2, out.stderr
    blocked = tmp_path / "blocked"
    blocked.write_text("a file, not a directory")
    out = cli("predict", str(path), "--out", str(blocked / "out.csv"))
    assert out.returncode == 2 and "cannot write --out" in out.stderr and "shots file" not in out.stderr


@pytest.mark.parametrize("text", ["", "\n"])
def test_predict_empty_input_writes_nothing(tmp_path, text):
    path = shots_file(tmp_path, text)
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 2 and "empty" in out.stderr and not (tmp_path / "out.csv").exists()


# ------------------------------------------------------------------ scenes
BASE = yaml.safe_load((ROOT / "workflow/scenes/table3.yaml").read_text())


def scene_file(tmp_path, text=None, **changes):
    data = {**BASE, **changes}
    path = tmp_path / "scene.yaml"
    path.write_text(text if text is not None else yaml.safe_dump(data))
    return path


@pytest.mark.parametrize("changes,needle", [
    ({"velocities": {"start": 800.0, "stop": 500.0, "step": 50.0}}, "stop >= start"),
    ({"velocities": [float("nan")]}, "finite"),
    ({"velocities": {"start": 1.0, "stop": 5000.0, "step": 0.001}}, "at most 1000"),
    ({"velocities": list(range(1, 1200))}, "at most 1000"),
    ({"level": "fe"}, "level"),
    ({"effects": ["crater", "static", "inertial", "friction"], "friction": 0.1}, "not used at level analytic"),
    ({"level": "trajectory", "effects": ["inertial"]}, "needs ['static']"),
    ({"level": "trajectory", "effects": ["crater", "static", "inertial"], "friction": 0.1}, "friction is set"),
    ({"level": "trajectory", "effects": ["crater", "static", "inertial", "friction"]}, "friction > 0"),
    ({"lock": "literal"}, "only at levels cavity and fe"),
    ({"velocities": "fast"}, "a list of a number"),
])
def test_scene_errors(tmp_path, changes, needle):
    with pytest.raises((SceneError, ConfigError)) as err:
        read_scene(scene_file(tmp_path, **changes), SCENE_SCHEMA, ("analytic", "trajectory"))
    assert needle in str(err.value) and "allowed" in str(err.value) + needle


def test_scene_level_given_twice(tmp_path):
    text = (ROOT / "workflow/scenes/table3.yaml").read_text() + "level: trajectory\n"
    with pytest.raises(ConfigError, match="'level' is given twice"):
        read_scene(scene_file(tmp_path, text=text), SCENE_SCHEMA)


def test_cavity_scene_in_a_plain_rule(tmp_path):
    with pytest.raises(SceneError, match="not run by this rule"):
        read_scene(ROOT / "workflow/scenes/cavity/table3.yaml", SCENE_SCHEMA, ("analytic", "trajectory"))


# ------------------------------------------------------------------ config
def test_nested_override_strings_become_numbers():
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["figures"] = {"dpi": "130", "points_per_segment": "200"}
    check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")
    assert cfg["figures"] == {"dpi": 130, "points_per_segment": 200}


def test_missing_reference_file_is_noticed_at_load(monkeypatch):
    monkeypatch.chdir(ROOT)
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["reference"] = "workflow/reference/nope.csv"
    with pytest.raises(ConfigError, match="reference: file 'workflow/reference/nope.csv' does not exist"):
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")


def test_snakemake_accepts_a_nested_override():
    out = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-c1", "figures/table1.csv", "--config",
                          "figures={dpi: 131, points_per_segment: 200}"], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr


def test_unknown_reference_id_is_noticed_at_load(monkeypatch):
    monkeypatch.chdir(ROOT)
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["calibration"]["do1"]["depth"] = "table2.dopp"
    with pytest.raises(ConfigError, match="calibration.do1.depth: 'table2.dopp' is not an id"):
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")


@pytest.mark.parametrize("field,value", [("diameter_m", "1e-160"), ("mass_kg", "1e-300")])
def test_predict_refuses_sizes_that_make_eq9_infinite(tmp_path, field, value):
    import csv
    import io
    head = header().split(",")
    # the source column holds a quoted reference with commas: rebuild the row with the csv module
    parsed = next(csv.reader(io.StringIO(good_row())))
    parsed[head.index(field)] = value
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(parsed)
    path = shots_file(tmp_path, f"{header()}\n{buf.getvalue()}")
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 2 and field in out.stderr and "allowed" in out.stderr
    assert not (tmp_path / "out.csv").exists()


def test_predict_out_is_a_directory(tmp_path):
    path = shots_file(tmp_path, f"{header()}\n{good_row()}\n")
    out = cli("predict", str(path), "--out", str(tmp_path))
    assert out.returncode == 2 and "is a directory" in out.stderr


def test_yaml_merge_keys_still_load_and_unhashable_keys_are_config_errors(tmp_path):
    from penetration.pipeline.config import load_with
    (tmp_path / "m.yaml").write_text("base: &x {a: 1}\nd: {<<: *x, c: 2}\n")
    assert load_with(tmp_path / "m.yaml", {})["d"] == {"a": 1, "c": 2}
    (tmp_path / "u.yaml").write_text("? [a, b]\n: 1\n")
    with pytest.raises(ConfigError):
        load_with(tmp_path / "u.yaml", {})


@pytest.mark.parametrize("value", ["nan", "inf", "+-5"])
def test_override_strings_that_are_not_finite_numbers_are_refused(value):
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["trajectory"] = {"rtol": value}
    with pytest.raises(ConfigError, match="trajectory.rtol"):
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")


@pytest.mark.parametrize("spec,where", [("cavity_gain,", "default"),
                                         ({"default": "cavity", "columns": {"gain_m": "cavity_gain,"}}, "gain_m")])
def test_unknown_precision_class_is_noticed_at_load(tmp_path, spec, where):
    """A precision class that is not defined (here a YAML block value with a stray comma) stops the run at
    load, naming the file, the output and the column, instead of failing the reproduction check at the end."""
    check = yaml.safe_load((ROOT / "workflow/check.yaml").read_text())
    check["outputs"]["figures/nose_contrasts.csv"] = spec
    (tmp_path / "check.yaml").write_text(yaml.safe_dump(check))
    with pytest.raises(ConfigError, match=f"check.yaml: outputs.figures/nose_contrasts.csv.{where}: precision class "
                                          f"'cavity_gain,' is not defined"):
        load_check(tmp_path / "check.yaml", ROOT / "workflow/schemas/check.schema.json")


FE_BASE = scene_data(ROOT / "workflow/scenes/fe/table3.yaml")  # the fe scene of Table 3, the case merged in


@pytest.mark.parametrize("changes,needle", [
    ({"target": {"rho": 2440.0, "fc": 48e6, "strength": {"law": "li_chen"}}}, "target.strength is not used at level fe"),
    ({"effects": ["strain_rate", "damage"]}, "effect erosion and fe.erosion_strain go together"),
    ({"fe": {"target": "semi_infinite"}}, "effect erosion and fe.erosion_strain go together"),
    ({"effects": ["erosion", "crater"]}, "not used at level fe"),
    ({"fe": {"target": "infinite", "erosion_strain": "calibrated"}}, "semi_infinite"),
    ({"fe": {"target": "block", "erosion_strain": -0.3}}, "erosion_strain"),
    ({"level": "cavity", "effects": ["cavity"], "target": {"rho": 2440.0, "fc": 48e6, "strength": {"law": "li_chen"}}},
     "fe settings are given at level cavity"),
])
def test_fe_scene_errors(tmp_path, changes, needle):
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump({**FE_BASE, **changes}))
    with pytest.raises((SceneError, ConfigError)) as err:
        read_scene(path, SCENE_SCHEMA, ("fe", "cavity"))
    assert needle in str(err.value) and "allowed" in str(err.value)


def test_fe_scenes_of_the_pipeline_are_valid():
    from penetration.pipeline.dispatch import fe_scene_shots
    shots = fe_scene_shots(ROOT / "workflow/scenes/fe", SCENE_SCHEMA)
    assert set(shots) == {"do1", "do1_block", "table3", "fig15", "do1_depth54", "do1_depth54_free_bottom",
                          "do1_block_absorbing_sides", "table3_erosion_free", "table3_erosion_free_hole50",
                          "table3_erosion_free_hole125", "table3_erosion_free_calibrated", "table3_mu005", "table3_mu010",
                          "table3_mu020", "table3_fs038", "table3_erosion_free_mu005", "table3_erosion_free_mu010",
                          "table3_erosion_free_mu020", "table3_erosion_free_eject050", "table3_erosion_free_eject200"}
    assert ("double_ogive", "835") in shots["do1"] and len(shots["table3"]) == 12 and len(shots["fig15"]) == 24
    assert all(len(shots[s]) == 6 for s in shots if s.startswith("table3_erosion_free"))


@pytest.mark.parametrize("profiles,needle", [({"full": 10}, "fe_convergence.profiles"),
                                             ({"fine": 0.5}, "fe_convergence.profiles.fine"),
                                             ({"Fine": 10}, "fe_convergence.profiles"), ({}, "fe_convergence.profiles")])
def test_convergence_profiles_are_checked(profiles, needle):
    """A convergence mesh profile needs a new lower-case name and 1 to 40 elements across the shank radius."""
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["fe_convergence"]["profiles"] = profiles
    with pytest.raises(ConfigError, match=needle):
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")


@pytest.mark.parametrize("band,needle", [({"bands": {"full": {}}, "confidence": 0.95}, "fe_band.bands.full"),
                                         ({"bands": {"full": {"fine": 8.5}}, "confidence": 0.95}, "fe_band.bands.full"),
                                         ({"bands": {"ci": {"band3": 3.5}}, "confidence": 0.95}, "fe_band.bands"),
                                         ({"bands": {"full": {"band1": 8.5, "band2": 0.5}}, "confidence": 0.95},
                                          "fe_band.bands.full.band2"),
                                         ({"bands": {"full": {"band1": 8.5}}, "confidence": 1.0}, "fe_band.confidence")])
def test_band_profiles_are_checked(band, needle):
    """A mesh band is centred on full or a convergence profile and holds profiles named band and digits, each 1 to 40
    elements across the shank radius; its interval's confidence lies in (0, 1)."""
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["fe_band"] = band
    with pytest.raises(ConfigError, match=needle):
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")


@pytest.mark.parametrize("option,value", [("--strength-scale", "1e300"), ("--strength-scale", "0"),
                                          ("--failure-strain", "1e300"), ("--failure-strain", "-1")])
def test_a_calibration_override_out_of_range_is_refused_before_any_run(option, value):
    """A huge strength scale or failure strain ran until killed; each override has a stated range."""
    from conftest import run_cli
    out = run_cli("dop", "ogive", "crh=3", "diameter_m=0.0269", "mass_kg=0.9", "length_m=0.2424", "velocity_ms=500",
                  "fc_MPa=40", "--model", "fe" if option == "--failure-strain" else "cavity", option, value)
    assert out.returncode == 2 and option in out.stderr and "<=" in out.stderr and out.stdout == ""


def test_a_root_whose_config_the_pipeline_would_refuse_is_refused_by_the_command_line(tmp_path):
    """--root's config is checked against the config schema before any shot (a value of the wrong type, which the
    pipeline refuses, reached a cavity answer unchecked)."""
    import shutil

    from conftest import run_cli
    (tmp_path / "workflow").mkdir()
    text = (ROOT / "workflow/config.yaml").read_text()
    assert "\n  zones: " in text
    lines = [("  zones: five" if line.startswith("  zones: ") else line) for line in text.splitlines()]
    (tmp_path / "workflow/config.yaml").write_text("\n".join(lines) + "\n")
    shutil.copytree(ROOT / "workflow/schemas", tmp_path / "workflow/schemas")
    out = run_cli("dop", "ogive", "crh=3", "diameter_m=0.0269", "mass_kg=0.9", "velocity_ms=500", "fc_MPa=40",
                  "--model", "cavity", "--root", str(tmp_path))
    assert out.returncode == 2 and "cavity.zones" in out.stderr and "allowed" in out.stderr and out.stdout == ""
