"""Command line and config validation: errors name the field and the range."""
import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from penetration.pipeline.config import ConfigError, load, validate

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow/schemas/config.schema.json"


def cli(*args):
    return subprocess.run([sys.executable, "-m", "penetration", *args], capture_output=True, text=True,
                          cwd=ROOT, env={"PYTHONPATH": str(ROOT / "src"), "PATH": "/usr/bin:/bin"})


def test_nstar_json():
    out = cli("nstar", "ogive", "psi=3", "radius=0.07", "--json")
    assert out.returncode == 0
    data = json.loads(out.stdout)
    assert set(data) == {"nstar", "length", "volume"}
    assert data["nstar"] == pytest.approx(23 / 216, rel=1e-10)


@pytest.mark.parametrize("args,needle", [
    (("nstar", "ogive", "psi=0.2", "radius=0.07"), "psi"),
    (("nstar", "ogive", "psi=3", "radius=0.07", "colour=red"), "colour"),
    (("nstar", "spike", "radius=1"), "kind"),
    (("nstar", "cone", "radius=0.07"), "length"),
    (("nstar", "table", "path=/nonexistent.csv"), "path"),
])
def test_cli_errors(args, needle):
    out = cli(*args)
    assert out.returncode == 2
    assert needle in out.stderr and "allowed" in out.stderr
    assert out.stdout == ""


def test_shipped_config_is_valid():
    load(ROOT / "workflow/config.yaml", SCHEMA)


@pytest.mark.parametrize("path,value,needle", [
    (("projectile", "density"), -1, "projectile.density"),
    (("fig4_design", "convention"), "dN/dz", "fig4_design.convention"),
    (("figures", "dpi"), "high", "figures.dpi"),
    (("projectile", "colour"), 1, "projectile"),
])
def test_config_errors_name_field(path, value, needle):
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    cfg[path[0]][path[1]] = value
    with pytest.raises(ConfigError) as err:
        validate(cfg, json.loads(SCHEMA.read_text()), "config.yaml")
    assert needle in str(err.value) and "allowed" in str(err.value)


def test_predict_reports_bad_rows_and_writes_good_ones(tmp_path):
    shots = tmp_path / "shots.csv"
    shots.write_text("shot_id,mass_kg,diameter_m,nose_shape,crh,target_density_kgm3,fc_MPa,velocity_ms,dop_m,extra\n"
                     "A,0.9,0.0269,ogive,2,2370,32.4,800,0.958,keep\n"
                     "B,-1,0.0269,ogive,2,2370,32.4,800,0.9,x\n"
                     "C,0.9,0.0269,wedge,2,2370,32.4,800,0.9,x\n"
                     "D,0.9,0.0269,hemispherical,,2370,32.4,800,0.9,x\n")
    out = tmp_path / "out.csv"
    res = cli("predict", str(shots), "--model", "analytic", "--out", str(out))
    assert res.returncode == 0
    assert "row 3: mass_kg" in res.stderr and "row 4: nose_shape" in res.stderr
    import csv
    rows = list(csv.DictReader(open(out)))
    assert [r["shot_id"] for r in rows] == ["A", "D"] and rows[0]["extra"] == "keep"
    # independent check of row A: Eq 9 by hand with S = 72 fc^-0.5 and N* = (8*2-1)/(24*4)
    from conftest import eq9_by_hand
    p = eq9_by_hand(0.9, 0.01345, 15 / 96, 2370.0, 72 * 32.4**-0.5 * 32.4e6, 800.0)
    assert float(rows[0]["dop_pred_m"]) == pytest.approx(p, rel=1e-5)
