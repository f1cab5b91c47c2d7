"""Inputs and outputs that cannot be handled for sure are refused, naming what and why.

Writes never replace what is not a regular file; dop, simulate and predict
speak the shots CSV's vocabulary; numbers are read in one form everywhere;
no level extrapolates past its sigma_n table.
"""
import json
import os
import stat
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from penetration.nose.geometry import Cone, MinimumNstar, Ogive
from penetration.pipeline.io import TargetError, write_csv
from penetration.shots import ladder as L

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "workflow/data/experiments-dev.csv"


def cli(*args, cwd=ROOT):
    """The command line, run in this process (conftest.run_cli)."""
    from conftest import run_cli
    return run_cli(*args, cwd=cwd)


def shots_file(tmp_path, text, name="shots.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


SHOT = ("ogive", "psi=3", "diameter_m=0.14", "mass_kg=81.1", "velocity_ms=835", "fc_MPa=48")


def header():
    return SHOTS.read_text().splitlines()[0]


def good_row():
    return SHOTS.read_text().splitlines()[1]


# ------------------------------------------------------- writes never replace a non-regular file
@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "pipe"
    os.mkfifo(path)
    return path


def test_write_csv_refuses_a_fifo(fifo):
    with pytest.raises(TargetError, match="FIFO.*allowed: a regular file or a new path"):
        write_csv(pd.DataFrame({"x": [1.0]}), fifo)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert sorted(p.name for p in fifo.parent.iterdir()) == ["pipe"]  # no temporary left


def test_write_csv_judges_a_symlink_by_its_target(tmp_path, fifo):
    link = tmp_path / "link.csv"
    link.symlink_to(fifo)
    with pytest.raises(TargetError, match="FIFO"):
        write_csv(pd.DataFrame({"x": [1.0]}), link)
    assert link.is_symlink() and stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_predict_refuses_a_fifo_as_out(tmp_path, fifo):
    path = shots_file(tmp_path, f"{header()}\n{good_row()}\n")
    out = cli("predict", str(path), "--out", str(fifo))
    assert out.returncode == 2, out.stderr
    assert out.stderr.startswith("error: ") and "--out" in out.stderr and "FIFO" in out.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_simulate_refuses_a_fifo_as_out(fifo):
    out = cli("simulate", *SHOT,
              "--model", "trajectory", "--out", str(fifo))
    assert out.returncode == 2, out.stderr
    assert out.stderr.startswith("error: ") and "--out" in out.stderr and "FIFO" in out.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


# ------------------------------------------------------- one vocabulary of shot inputs
PROJECTILE = ("diameter_m=0.14", "mass_kg=81.1", "velocity_ms=835", "fc_MPa=48")


@pytest.mark.parametrize("model", ["analytic", "trajectory"])
@pytest.mark.parametrize("kind,nose", [("cone", Cone(0.07, 0.21)), ("minimum_nstar", MinimumNstar(0.07, 0.21))])
def test_a_cone_and_a_minimum_nstar_nose_run_through_dop(kind, nose, model):
    """The nose's own length key is the nose's; the projectile's is length_m (formerly the one key `length`)."""
    out = cli("dop", kind, "length=0.21", *PROJECTILE, "length_m=1.13", "--model", model, "--json")
    assert out.returncode == 0, out.stderr
    want = L.run(L.UserShot(nose, 81.1, 835.0, 48e6, 2440.0, 1.13), model, L.Context())
    assert json.loads(out.stdout)["depth_m"] == pytest.approx(want.depth_m, rel=1e-9)


def _one_row_csv(tmp_path, **changes):
    import csv
    import io
    head = header().split(",")
    row = next(csv.reader(io.StringIO(good_row())))
    for k, v in changes.items():
        row[head.index(k)] = v
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows([head, row])
    return shots_file(tmp_path, buf.getvalue()), dict(zip(head, row))


@pytest.mark.parametrize("model", ["analytic", "trajectory"])
def test_dop_of_a_row_equals_predict_of_it(tmp_path, model):
    path, row = _one_row_csv(tmp_path)
    assert row["nose_shape"] == "ogive"
    keys = [f"{k}={row[k]}" for k in ("crh", "diameter_m", "length_m", "mass_kg", "velocity_ms", "fc_MPa",
                                      "target_density_kgm3")]
    one = cli("dop", "ogive", *keys, "--model", model, "--json")
    assert one.returncode == 0, one.stderr
    many = cli("predict", str(path), "--model", model, "--out", str(tmp_path / "out.csv"))
    assert many.returncode == 0, many.stderr
    predicted = pd.read_csv(tmp_path / "out.csv").dop_pred_m.iloc[0]
    assert float(f"{json.loads(one.stdout)['depth_m']:.6g}") == predicted


@pytest.mark.parametrize("old,new,unit", [("mass=81.1", "mass_kg", "kg"), ("velocity=835", "velocity_ms", "m/s"),
                                          ("fc=48e6", "fc_MPa", "MPa"), ("radius=0.07", "diameter_m", "m"),
                                          ("density=2440", "target_density_kgm3", "kg/m^3"), ("length=1.13", "length_m", "m")])
@pytest.mark.parametrize("command", ["dop", "simulate"])
def test_former_keys_are_refused_with_the_new_key(tmp_path, command, old, new, unit):
    key = old.split("=")[0]
    keep = [k for k in (*SHOT[1:], "length_m=1.13") if not k.startswith(new + "=")]
    out = cli(command, "ogive", *keep, old, "--model", "trajectory",
              *(("--out", str(tmp_path / "h.csv")) if command == "simulate" else ()))
    assert out.returncode == 2 and out.stdout == ""
    assert f"{key} is not a shot key: give {new} ({unit})" in out.stderr
    assert not (tmp_path / "h.csv").exists()


def test_psi_and_crh_together_are_refused():
    out = cli("dop", *SHOT, "crh=3")
    assert out.returncode == 2 and "psi or crh, not both" in out.stderr


def test_help_lists_the_one_table_of_shot_fields():
    from penetration.shots.fields import SHOT_FIELDS
    for command in ("dop", "simulate", "predict"):
        out = cli(command, "--help")
        assert out.returncode == 0
        for name, f in SHOT_FIELDS.items():
            assert name in out.stdout and f.allowed in " ".join(out.stdout.split()), (command, name)
    predict = " ".join(cli("predict", "--help").stdout.split())
    assert "nose_shape" in predict and "crh" in predict


def test_user_shot_ranges_are_the_csv_ranges():
    from penetration.shots.fields import SHOT_FIELDS
    for attr, (lo, hi) in L.SHOT_RANGES.items():
        f = next(f for f in SHOT_FIELDS.values() if f.attribute == attr)
        assert (lo, hi) == (f.lo * f.si, f.hi * f.si)


# ------------------------------------------------------- numbers in one form, CSVs read for sure
@pytest.mark.parametrize("text", ["3_0", "1_000", "inf", "-inf", "nan", "Infinity", " 3", "3 ", "1e999", "٣"])
def test_a_number_float_would_take_is_refused_on_the_command_line(text):
    for args in (("nstar", "ogive", f"psi={text}", "radius=0.07"), ("dop", "ogive", f"psi={text}", *PROJECTILE),
                 ("dop", *SHOT, f"target_density_kgm3={text}")):
        out = cli(*args)
        assert out.returncode == 2 and "a plain decimal number" in out.stderr and out.stdout == "", (args, out.stderr)


@pytest.mark.parametrize("text", ["3_0", "1_000", "inf", "nan", " 48", "48 "])
def test_a_number_float_would_take_is_refused_in_a_shots_row(tmp_path, text):
    path, _ = _one_row_csv(tmp_path, fc_MPa=text)
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 2 and "row 2: fc_MPa" in out.stderr and "a plain decimal number" in out.stderr
    assert not (tmp_path / "out.csv").exists()


def test_an_option_number_with_an_underscore_is_refused():
    out = cli("dop", *SHOT, "--model", "cavity", "--strength-scale", "0_6")
    assert out.returncode == 2 and "--strength-scale" in out.stderr and "a plain decimal number" in out.stderr


def test_a_column_given_twice_in_a_shots_file_is_refused(tmp_path):
    head = header()
    path = shots_file(tmp_path, f"{head},fc_MPa\n{good_row()},480\n")
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 2 and "column 'fc_MPa' is given twice" in out.stderr
    assert not (tmp_path / "out.csv").exists()


def nose_table(tmp_path, text, encoding="utf-8"):
    path = tmp_path / "nose.csv"
    path.write_text(text, encoding=encoding)
    return path


@pytest.mark.parametrize("text,needle", [
    ("x,y\n0,0\n0.1,0.07,0.5\n", "row 3 = ['0.1', '0.07', '0.5'] is not allowed: 2 fields"),
    ("x,y\n0,0\n0.1\n", "row 3 = ['0.1'] is not allowed: 2 fields"),
    ("x,y\n", "at least 2 rows"),
    ("x,y\n0,0\n", "at least 2 rows"),
    ("x,y,x\n0,0,0\n0.1,0.07,0.1\n", "'x' is given twice"),
    ("x,y\n0,0\n0.1,3_0\n", "y in row 3 = '3_0'"),
    ("x,y\n0,0\n0.1,nan\n", "y in row 3 = 'nan'"),
])
def test_nose_table_refusals_name_the_row_or_what_is_needed(tmp_path, text, needle):
    out = cli("nstar", "table", f"path={nose_table(tmp_path, text)}")
    assert out.returncode == 2 and needle in out.stderr and out.stdout == "", out.stderr


def test_nose_table_monotonicity_names_the_row_that_decreases(tmp_path):
    """Rows counted as predict counts them (the header is row 1): the fourth row's y falls below the third's."""
    path = nose_table(tmp_path, "x,y\n0,0\n0.1,0.05\n0.2,0.04\n0.3,0.07\n")
    out = cli("nstar", "table", f"path={path}")
    assert out.returncode == 2 and "y in row 4 = 0.04 is not allowed" in out.stderr and "row 3 has y = 0.05" in out.stderr


def test_a_byte_order_mark_is_read_by_nstar_table_and_predict(tmp_path):
    text = "x,y\n0,0\n0.1,0.07\n"
    plain = cli("nstar", "table", f"path={nose_table(tmp_path, text)}", "--json")
    marked = cli("nstar", "table", f"path={nose_table(tmp_path, chr(0xFEFF) + text)}", "--json")
    assert plain.returncode == marked.returncode == 0, marked.stderr
    assert json.loads(marked.stdout) == json.loads(plain.stdout)
    path = shots_file(tmp_path, f"\ufeff{header()}\n{good_row()}\n")
    out = cli("predict", str(path), "--out", str(tmp_path / "out.csv"))
    assert out.returncode == 0, out.stderr
    assert pd.read_csv(tmp_path / "out.csv").columns[0] == "shot_id"  # the mark is not part of the first name


@pytest.mark.parametrize("value", ["1_0e-8", " 1e-8", "1e-8 "])
def test_a_config_override_number_float_would_take_is_refused(monkeypatch, value):
    import yaml
    monkeypatch.chdir(ROOT)
    from penetration.pipeline.config import ConfigError, check_config
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg["trajectory"] = {"rtol": value}
    with pytest.raises(ConfigError, match="trajectory.rtol"):
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")


# ------------------------------------------------------- the config refuses bad values
def config(**changes):
    """The shipped config with changes at dotted paths."""
    import yaml
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    for dotted, value in changes.items():
        *head, last = dotted.split("/")
        node = cfg
        for key in head:
            node = node[key]
        node[last] = value
    return cfg


def refused_config(cfg):
    from penetration.pipeline.config import ConfigError, check_config
    with pytest.raises(ConfigError) as err:
        check_config(cfg, ROOT / "workflow/schemas/config.schema.json", "config")
    return str(err.value)


@pytest.mark.parametrize("dotted,value,needle", [
    ("fe/cutoff_hz", float("nan"), "fe.cutoff_hz: nan is not allowed: a finite number"),
    ("fe/target_radius", float("inf"), "fe.target_radius: inf is not allowed: a finite number"),
    ("fig01/strengths", [20e6, float("nan")], "fig01.strengths.1: nan is not allowed"),
])
def test_non_finite_numbers_anywhere_in_the_config_are_refused(monkeypatch, dotted, value, needle):
    monkeypatch.chdir(ROOT)
    assert needle in refused_config(config(**{dotted: value}))


def test_a_non_finite_number_in_the_check_file_is_refused(tmp_path):
    import yaml

    from penetration.pipeline.config import ConfigError, load_check
    check = yaml.safe_load((ROOT / "workflow/check.yaml").read_text())
    check["precision"]["round_off"]["atol"] = float("inf")
    (tmp_path / "check.yaml").write_text(yaml.safe_dump(check))
    with pytest.raises(ConfigError, match="precision.round_off.atol: inf is not allowed"):
        load_check(tmp_path / "check.yaml", ROOT / "workflow/schemas/check.schema.json")


def test_the_shipped_config_is_finite_and_its_unfiltered_row_rule_still_picks_the_unfiltered_rows():
    """fig14_cutoff.csv's unfiltered rows (cutoff_hz written inf) take the fe_spike class: `where` names them by
    the text "inf" now, which the check reads as the number the committed column holds."""
    import numpy as np

    from penetration.pipeline.config import non_finite, read_yaml
    from penetration.tasks.reference import cell_tolerances
    cfg = read_yaml(ROOT / "workflow/config.yaml")
    check = read_yaml(ROOT / cfg["check"])
    assert non_finite(cfg) == [] and non_finite(check) == []
    spec = check["outputs"]["figures/fe/{profile}/fig14_cutoff.csv"]
    committed = pd.read_csv(ROOT / "figures/fe/ci/fig14_cutoff.csv")
    tol = cell_tolerances(spec, check["precision"], check["factor"], committed)
    spike = check["factor"] * check["precision"]["fe_spike"].get("rtol", 0.0)
    unfiltered = np.isinf(committed.cutoff_hz.to_numpy())
    assert unfiltered.sum() > 0
    assert np.all(tol["peak_g"][0][unfiltered] == spike)
    assert np.all(tol["peak_g"][0][~unfiltered] != spike)


@pytest.mark.parametrize("dotted,value,needle", [
    ("cavity/velocities", [100.0, 100.0, 200.0], "cavity.velocities: [100.0, 100.0, 200.0] is not allowed: strictly increasing"),
    ("cavity/velocities", [200.0, 100.0, 300.0], "cavity.velocities: [200.0, 100.0, 300.0] is not allowed: strictly increasing"),
    ("fe/cutoffs_hz", [1000.0, 1000.0], "fe.cutoffs_hz"),
    ("cavity/quasi_static_from", [100.0, 50.0], "cavity.quasi_static_from"),
    ("fig10/unload_from", [0.05, 0.02], "fig10.unload_from"),
    ("fe/profiles/ci/mesh_study", [0.035, 0.035, 0.0233333333333], "fe.profiles.ci.mesh_study"),
    ("sweep/sizes", {"analytic": [6, 6]}, "sweep.sizes.analytic"),
    ("sweep/velocities", [800.0, 400.0, 800.0], "sweep.velocities"),
    ("fe/fs_bracket", [3.0, 0.3], "fe.fs_bracket: [3.0, 0.3] is not allowed: [low, high] with low < high"),
])
def test_lists_whose_order_matters_are_checked(monkeypatch, dotted, value, needle):
    monkeypatch.chdir(ROOT)
    assert needle in refused_config(config(**{dotted: value}))


def test_sizes_beyond_the_machine_are_refused_with_their_bound(monkeypatch):
    monkeypatch.chdir(ROOT)
    text = refused_config(config(**{"sweep/sizes": {"fe": [100000]}}))
    assert "sweep.sizes.fe: [100000] is not allowed: at most the 78 shots of the sweep's grid" in text
    text = refused_config(config(**{"cavity/zones": 5000}))
    assert "cavity.zones: 5000 is not allowed" in text and "zones^2" in text and "at most 1906 zones" in text
    text = refused_config(config(**{"fe/profiles/full/elements_across": 1000}))
    assert "fe.profiles.full.elements_across: 1000 elements across the shank radius" in text and "is not allowed" in text
    assert "bytes per element" in text and "os.sysconf" in text and "allowed: at most" in text and "elements across" in text


def test_fe_mesh_estimate_counts_the_meshes_the_level_builds():
    """The config's element count is that of fe.mesh.build for the same mesh (within the columns the kernels'
    vector width adds)."""
    from penetration.fe.mesh import build
    from penetration.fe.shot import Settings, TargetSpec, mesh_spec
    from penetration.nose.geometry import Ogive
    from penetration.pipeline.config import fe_mesh_elements, read_yaml
    fe = read_yaml(ROOT / "workflow/config.yaml")["fe"]
    for h in (0.0233333333333, 0.00875, 0.003):
        spec = mesh_spec(Ogive(3.0, 0.07), Settings.from_config(fe, None, h), TargetSpec(radius=fe["target_radius"]), 5.1)
        built = build(spec).elements
        assert 0.9 * built <= fe_mesh_elements(h, fe, 0.07, 5.1) <= built


def test_a_key_given_twice_in_a_configfile_stops_snakemake(tmp_path):
    path = tmp_path / "extra.yaml"
    path.write_text("trajectory:\n  rtol: 1.0e-8\ntrajectory:\n  rtol: 1.0e-6\n")
    out = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-c1", "figures/table1.csv", "--configfile",
                          str(path)], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode != 0
    assert f"{path}: line 3: key 'trajectory' is given twice" in out.stdout + out.stderr


@pytest.mark.parametrize("name,suggested", [("my-shots", "my_shots"), ("shots.v2", "shots_v2"), ("tré", "tr_")])
def test_a_scene_name_outside_the_scene_wildcard_is_refused(tmp_path, name, suggested):
    """An FE scene folder is listed when the Snakefile is read: a file the wildcard [A-Za-z0-9_]+ cannot name is
    refused there with a name that would do, not met by Snakemake's 'no rule to produce'."""
    from penetration.pipeline.dispatch import fe_scene_shots
    from penetration.pipeline.scenes import SceneError, read_scene, scene_names
    folder = tmp_path / "fe"
    folder.mkdir()
    (folder / f"{name}.yaml").write_text((ROOT / "workflow/scenes/fe/do1.yaml").read_text())
    schema = ROOT / "workflow/schemas/scene.schema.json"
    for call in (lambda: fe_scene_shots(folder, schema), lambda: read_scene(folder / f"{name}.yaml", schema),
                 lambda: scene_names(folder)):
        with pytest.raises(SceneError) as err:
            call()
        text = str(err.value)
        assert f"{name}.yaml" in text and "[A-Za-z0-9_]+" in text and f"e.g. {suggested}.yaml" in text


def test_the_shipped_scene_folders_have_wildcard_names():
    from penetration.pipeline.scenes import scene_names
    for folder in ("workflow/scenes", "workflow/scenes/cavity", "workflow/scenes/fe"):
        assert scene_names(ROOT / folder)


def test_the_command_line_reads_the_pipeline_config_strictly(tmp_path):
    """--root's workflow/config.yaml goes through the strict loader as every YAML the package reads."""
    (tmp_path / "workflow").mkdir()
    text = (ROOT / "workflow/config.yaml").read_text()
    (tmp_path / "workflow/config.yaml").write_text(text + "\ntrajectory:\n  rtol: 1.0e-6\n")
    (tmp_path / "workflow/reference").symlink_to(ROOT / "workflow/reference")
    out = cli("dop", *SHOT, "--model", "trajectory", "--root", str(tmp_path))
    assert out.returncode == 2 and "key 'trajectory' is given twice" in out.stderr and out.stdout == ""


# ------------------------------------------------------- no level extrapolates past its table
@pytest.mark.parametrize("velocity", ["3000", "10000"])
def test_the_cavity_level_refuses_a_shot_above_its_table(tmp_path, velocity):
    shot = ("ogive", "psi=3", "diameter_m=0.14", "mass_kg=81.1", f"velocity_ms={velocity}", "fc_MPa=48")
    out = cli("dop", *shot, "--model", "cavity", "--strength-scale", "0.6")
    assert out.returncode == 2 and out.stdout == ""
    assert f"shot.velocity_ms = {float(velocity)!r} is not allowed: at most 2000 m/s" in out.stderr
    assert "cavity.velocities" in out.stderr
    path, _ = _one_row_csv(tmp_path, velocity_ms=velocity)
    out = cli("predict", str(path), "--model", "cavity", "--strength-scale", "0.6", "--out", str(tmp_path / "o.csv"))
    assert out.returncode == 2 and "row 2: shot.velocity_ms" in out.stderr and "at most 2000 m/s" in out.stderr


def test_the_cavity_table_span_is_checked_before_a_table_is_built():
    ctx = L.Context(strength_scale=0.6, strength_scale_source="test", cavity_velocities=(100.0, 300.0, 600.0, 1000.0))
    with pytest.raises(L.ParameterError, match="at most 1000 m/s"):
        L.run(L.UserShot(Ogive(3.0, 0.07), 81.1, 1000.5, 48e6), "cavity", ctx)
    assert ctx.table_builds == 0


def test_the_probe_settles_on_the_fastest_of_agreeing_probes():
    """A transient (a probe 150 times slow, as a busy machine once gave) does not set the estimate: probing goes on
    until two agree, and the fastest is taken; a rate beyond BUSY_NS is said to be a busy machine's."""
    from penetration.fe.level import BUSY_NS, MAX_PROBES, CostEstimate, settled_rate
    seq = iter([5000.0, 9221.0, 61.0, 60.0, 1e9])
    assert settled_rate(lambda: next(seq)) == (60.0, 4)
    seq = iter([5000.0, 62.0, 60.0])
    assert settled_rate(lambda: next(seq)) == (60.0, 3)
    calls = []
    busy = lambda: calls.append(1) or 1000.0 + len(calls)   # noqa: E731
    ns, probes = settled_rate(busy)
    assert probes == MAX_PROBES and ns == 1002.0 > BUSY_NS
    est = CostEstimate(100, 100, 1000, 1e-3, ns, 100.0, 1e6, probes)
    assert est.busy and "looks busy" in est.describe() and "best of 5 probes" in est.describe()
    assert not CostEstimate(100, 100, 1000, 1e-3, 60.0, 6.0, 1e6, 3).busy
