"""Noses by constraint (nose.solve): the solved parameter against closed forms, the recovery of a known nose's key,
and the refusals; the outline command's CSV read back as a table nose."""
import math

import pytest

from penetration.errors import ParameterError
from penetration.nose.geometry import Cone, DoubleOgive, MinimumNstar, TabulatedNose, make_nose
from penetration.nose.nstar import nstar
from penetration.nose.solve import solve_nose

A = 0.0125


def cli(*args):
    from conftest import run_cli
    return run_cli(*args)


@pytest.mark.parametrize("psi", [0.5, 1.0, 3.0, 6.0, 40.0])
def test_ogive_by_length_closed_form(psi):
    # tangent ogive: L = a sqrt(4 psi - 1)
    nose, sol = solve_nose("ogive", {"radius": A, "nose_length": A * math.sqrt(4 * psi - 1)})
    assert sol.key == "psi" and nose.psi == pytest.approx(psi, rel=1e-9) and not sol.other_values


@pytest.mark.parametrize("psi", [0.5, 2.0, 4.5, 12.0])
def test_ogive_by_nstar_closed_form(psi):
    # tangent ogive: N* = (8 psi - 1) / (24 psi^2), decreasing on psi >= 0.5
    nose, sol = solve_nose("ogive", {"radius": A, "nstar": (8 * psi - 1) / (24 * psi**2)})
    assert nose.psi == pytest.approx(psi, rel=1e-8)


@pytest.mark.parametrize("n", [0.05, 0.2, 0.8])
def test_cone_by_nstar_closed_form(n):
    # sharp cone: N* = a^2 / (a^2 + L^2)
    nose, sol = solve_nose("cone", {"radius": A, "nstar": n})
    assert sol.key == "length" and nose.length == pytest.approx(A * math.sqrt(1 / n - 1), rel=1e-8)


def test_cone_by_length_is_its_length():
    nose, sol = solve_nose("cone", {"radius": A, "nose_length": "0.06"})
    assert isinstance(nose, Cone) and nose.length == 0.06


@pytest.mark.parametrize("key", ["S1", "S2", "a1", "a2"])
def test_double_ogive_recovers_a_known_key(key):
    known = DoubleOgive(radius=0.07, S1=0.3, S2=0.42, a1=0.0397, a2=0.0638)
    given = {k: getattr(known, k) for k in ("radius", "S1", "S2", "a1", "a2") if k != key}
    nose, sol = solve_nose("double_ogive", {**given, "nose_length": known.length})
    values = [sol.value, *sol.other_values]
    assert nose.length == pytest.approx(known.length, rel=1e-10)
    assert any(v == pytest.approx(getattr(known, key), rel=1e-7) for v in values)


def test_double_ogive_by_nstar_and_solve_key():
    known = DoubleOgive(radius=0.07, S1=0.3, S2=0.42, a1=0.0397, a2=0.0638, tip_length=0.05)
    given = dict(radius=0.07, S1=0.3, S2=0.42, a1=0.0397, a2=0.0638)
    nose, sol = solve_nose("double_ogive", {**given, "nstar": nstar(known), "solve": "tip_length"})
    assert nstar(nose) == pytest.approx(nstar(known), rel=1e-10)
    assert any(v == pytest.approx(0.05, rel=1e-6) for v in (sol.value, *sol.other_values))


def test_minimum_nstar_by_nstar():
    nose, sol = solve_nose("minimum_nstar", {"radius": A, "nstar": 0.05})
    assert isinstance(nose, MinimumNstar) and nstar(nose) == pytest.approx(0.05, rel=1e-9)


def test_keys_as_text_as_the_command_line_gives_them():
    nose, _ = solve_nose("ogive", {"radius": "0.0125", "nose_length": repr(A * math.sqrt(23))})
    assert nose.psi == pytest.approx(6.0) and nose == make_nose("ogive", radius="0.0125", psi=str(nose.psi))


@pytest.mark.parametrize("kind,params,needle", [
    ("ogive", {"radius": A, "nstar": 0.9}, "nstar between"),             # above the hemisphere's 0.5
    ("ogive", {"radius": A, "nstar": 0.1, "nose_length": 0.05}, "one constraint at a time"),
    ("ogive", {"radius": A, "psi": 3, "nstar": 0.1}, "one key left out"),
    ("flat", {"radius": A, "nstar": 0.1}, "no free parameter"),
    ("double_ogive", {"radius": 0.07, "S1": 0.3, "a1": 0.04, "nose_length": 0.2}, "give all of"),
    ("double_ogive", {"radius": 0.07, "S1": 0.3, "S2": 0.42, "a1": 0.0397, "a2": 0.0638, "nose_length": 0.2,
                      "solve": "S1"}, "not also given"),
    ("ogive", {"radius": A, "nstar": "-1"}, "nstar > 0"),
    ("ogive", {"radius": A, "nstar": "abc"}, "a number"),
    ("ogive", {"radius": A, "solve": "psi"}, "only with a constraint"),
    ("cone", {"radius": A, "nstar": 0.2, "bogus": 1}, "a key among"),
])
def test_refusals_name_the_field(kind, params, needle):
    with pytest.raises(ParameterError, match="not allowed") as err:
        solve_nose(kind, params)
    assert needle in str(err.value)


def test_outline_writes_a_table_nose(tmp_path):
    out = tmp_path / "do.csv"
    res = cli("outline", "double_ogive", "radius=0.0125", "S1=0.05", "a1=0.005", "a2=0.01", "nose_length=0.06",
              "--out", str(out), "--points", "400")
    assert res.returncode == 0, res.stderr
    assert "solved  S2" in res.stdout and (tmp_path / "do.png").stat().st_size > 10_000
    table = TabulatedNose.from_csv(out)
    exact, _ = solve_nose("double_ogive", {"radius": 0.0125, "S1": 0.05, "a1": 0.005, "a2": 0.01, "nose_length": 0.06})
    assert table.length == pytest.approx(0.06, rel=1e-12) and table.radius == pytest.approx(0.0125, rel=1e-12)
    assert nstar(table) == pytest.approx(nstar(exact), rel=1e-5)   # the polyline's chords


def test_outline_refuses_before_writing(tmp_path):
    res = cli("outline", "ogive", "radius=0.0125", "nstar=0.9", "--out", str(tmp_path / "o.csv"))
    assert res.returncode == 2 and "nstar between" in res.stderr and not list(tmp_path.iterdir())
    res = cli("outline", "ogive", "radius=0.0125", "psi=3", "--out", str(tmp_path / "o.png"))
    assert res.returncode == 2 and "--out" in res.stderr


def test_dop_by_nose_length_equals_the_explicit_nose():
    keys = ("mass_kg=0.5", "diameter_m=0.025", "fc_MPa=40", "velocity_ms=800", "--json")
    import json
    by_length = json.loads(cli("dop", "ogive", f"nose_length={A * math.sqrt(23)!r}", *keys).stdout)
    explicit = json.loads(cli("dop", "ogive", "psi=6", *keys).stdout)
    assert by_length["depth_m"] == pytest.approx(explicit["depth_m"], rel=1e-9)


# ------------------------------------------------------------------ predict takes every nose
def test_predict_takes_every_nose(tmp_path):
    """One CSV with every nose kind (the ogive also by its nose length, a table from the outline command): each
    row's Eq 9 depth equals dop's for the same nose and shot."""
    import csv
    import json
    assert cli("outline", "cone", "radius=0.0125", "length=0.05", "--out", str(tmp_path / "cone.csv")).returncode == 0
    shot = {"mass_kg": "0.5", "diameter_m": "0.025", "fc_MPa": "40", "velocity_ms": "800", "target_density_kgm3": "2300"}
    rows = [
        ({"nose_shape": "ogive", "crh": "3"}, ("ogive", "psi=3")),
        ({"nose_shape": "ogive", "nose_length": str(A * math.sqrt(23))}, ("ogive", "psi=6")),
        ({"nose_shape": "hemispherical"}, ("ogive", "psi=0.5")),
        ({"nose_shape": "flat", "S1": "0.3"}, ("flat",)),        # another kind's column passes through
        ({"nose_shape": "cone", "length": "0.05"}, ("cone", "length=0.05")),
        ({"nose_shape": "double_ogive", "S1": "0.05", "a1": "0.005", "a2": "0.01", "nose_length": "0.06"},
         ("double_ogive", "S1=0.05", "a1=0.005", "a2=0.01", "nose_length=0.06")),
        ({"nose_shape": "minimum_nstar", "length": "0.05"}, ("minimum_nstar", "length=0.05")),
        ({"nose_shape": "table", "path": "cone.csv", "diameter_m": ""}, ("cone", "length=0.05")),
    ]
    names = ["shot_id", *shot, "nose_shape", "crh", "length", "S1", "a1", "a2", "nose_length", "path"]
    with open(tmp_path / "shots.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, names, restval="")
        w.writeheader()
        for i, (nose, _) in enumerate(rows):
            w.writerow({"shot_id": f"s{i}", **shot, **nose})
    res = cli("predict", str(tmp_path / "shots.csv"), "--out", str(tmp_path / "out.csv"))
    assert res.returncode == 0, res.stderr
    got = list(csv.DictReader(open(tmp_path / "out.csv")))
    assert len(got) == len(rows)
    for row, (_, dop_args) in zip(got, rows):
        keys = [f"{k}={v}" for k, v in shot.items()]
        want = json.loads(cli("dop", *dop_args, *keys, "--json").stdout)["depth_m"]
        assert float(row["dop_pred_m"]) == pytest.approx(want, rel=2e-5), row   # the CSV's 6 digits; a table's chords


@pytest.mark.parametrize("nose,needle", [
    ({"nose_shape": "ogive", "crh": "3", "nstar": "0.1"}, "crh"),
    ({"nose_shape": "cone"}, "length"),
    ({"nose_shape": "double_ogive", "S1": "0.05", "a1": "0.005"}, "give all of"),
    ({"nose_shape": "table", "path": "missing.csv"}, "path"),
    ({"nose_shape": "wedge"}, "nose_shape"),
])
def test_predict_skips_a_bad_nose_row_naming_it(tmp_path, nose, needle):
    import csv
    row = {"shot_id": "x", "mass_kg": "0.5", "diameter_m": "0.025", "fc_MPa": "40", "velocity_ms": "800",
           "target_density_kgm3": "2300", **nose}
    ok = {"shot_id": "ok", "mass_kg": "0.5", "diameter_m": "0.025", "fc_MPa": "40", "velocity_ms": "800", "target_density_kgm3": "2300",
          "nose_shape": "ogive", "crh": "3"}
    names = list(dict.fromkeys([*ok, *row]))
    with open(tmp_path / "shots.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, names, restval="")
        w.writeheader()
        w.writerows([row, ok])
    res = cli("predict", str(tmp_path / "shots.csv"), "--out", str(tmp_path / "out.csv"))
    assert res.returncode == 0 and "skipped row 2" in res.stderr and needle in res.stderr.split("skipped row 2")[1]


@pytest.mark.parametrize("params,needle", [
    ({"radius": "none", "nose_length": 0.06}, "radius"),
    ({"radius": -0.01, "nose_length": 0.06}, "radius"),
    ({"radius": A, "psi": "abc", "tip_radius": 0.001, "nstar": 0.1, "solve": "tip_radius"}, "ogive.psi"),
    ({"radius": A, "nose_length": 0.06, "tip_radius": True}, "ogive.tip_radius"),
])
def test_bad_keys_are_named_before_solving(params, needle):
    with pytest.raises(ParameterError) as err:
        solve_nose("ogive", params)
    assert needle in str(err.value)
