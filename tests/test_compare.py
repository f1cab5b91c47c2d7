"""The nose comparison (shots.compare, `compare`): contrasts against independently computed Eq 9 depths, the
uncertainty parts against their definitions, the refusals, and the files it writes."""
import csv
import math

import pytest

from penetration.errors import ParameterError
from penetration.shots import compare as C

SHOT = ("mass_kg=0.5", "diameter_m=0.025", "length_m=0.2", "fc_MPa=40")


def cli(*args):
    from conftest import run_cli
    return run_cli(*args)


def _dop(nstar, velocity, law="li_chen"):
    """Eq 9 by hand for SHOT (0.5 kg, 25 mm, 40 MPa, the default concrete density 2440 kg/m^3): S = 72 fc^-0.5
    (Li & Chen) or 82.6 fc^-0.544 (Frew et al.), fc in MPa; Forrestal's V1^2 with its a^3 terms."""
    from conftest import eq9_by_hand
    fc = 40.0
    R = (72 * fc**-0.5 if law == "li_chen" else 82.6 * fc**-0.544) * fc * 1e6
    return eq9_by_hand(0.5, 0.0125, nstar, 2440.0, R, velocity)


CRH3, CONE = (8 * 3 - 1) / (24 * 3**2), 0.0125**2 / (0.0125**2 + 0.06**2)   # N* of an ogive, of a cone (sin^2)


def test_analytic_contrasts_and_calibration_part_from_dop(tmp_path):
    res = cli("compare", "--nose", "crh3=ogive crh=3", "--nose", "cone=cone length=0.06", "--velocities", "400:800:400",
              *SHOT, "--out", str(tmp_path))
    assert res.returncode == 0, res.stderr
    rows = list(csv.DictReader(open(tmp_path / "compare.csv")))
    assert len(rows) == 4 and {r["reference"] for r in rows} == {"crh3"}
    for v in (400, 800):
        ref = next(r for r in rows if r["nose"] == "crh3" and float(r["velocity_ms"]) == v)
        cone = next(r for r in rows if r["nose"] == "cone" and float(r["velocity_ms"]) == v)
        assert float(ref["contrast"]) == 1.0 and ref["u_combined"] == ""
        want = _dop(CONE, v) / _dop(CRH3, v)
        assert float(cone["contrast"]) == pytest.approx(want, rel=1e-9)
        other = _dop(CONE, v, law="forrestal") / _dop(CRH3, v, law="forrestal")
        assert float(cone["u_calibration"]) == pytest.approx(abs(other / want - 1), rel=1e-6)
        assert "validated" in cone["parts"] and "calibration (S law forrestal" in cone["parts"]
        parts = [float(cone[k]) for k in ("u_validated", "u_calibration")]
        assert float(cone["u_combined"]) == pytest.approx(math.hypot(*parts), rel=1e-9)
    for name in ("compare.png", "noses.png"):
        assert (tmp_path / name).stat().st_size > 10_000
    noses = list(csv.DictReader(open(tmp_path / "noses.csv")))
    assert [r["nose"] for r in noses] == ["crh3", "cone"] and float(noses[1]["nose_length_m"]) == 0.06


def _done(contrasts_by_member, velocity=1000.0):
    """A finished fe run set: the reference at depth 1, nose x at the given contrasts per member."""
    out = []
    for k, c in enumerate(contrasts_by_member):
        variant = "base" if k == 0 else f"member {k}"
        out += [(C.Job("fe", variant, "ref", velocity, k), 1.0, 1.0, None),
                (C.Job("fe", variant, "x", velocity, k), c, 1.0, None)]
    out += [(C.Job("fe", "calibration", "ref", velocity), 2.0, 1.0, None),
            (C.Job("fe", "calibration", "x", velocity), 2.0 * 1.3, 1.0, None)]
    return out


def test_chaos_and_calibration_parts_of_the_fe_level():
    from penetration.nose.geometry import Ogive
    study = C.Study(noses={"ref": ("ogive", {"psi": "3"}), "x": ("ogive", {"psi": "6"})}, reference="ref",
                    shot={"mass_kg": "0.5", "diameter_m": "0.025", "length_m": "0.2", "fc_MPa": "40"},
                    velocities=(1000.0,), levels=("fe",), members=3)
    noses = {"ref": (Ogive(3.0, 0.0125), None), "x": (Ogive(6.0, 0.0125), None)}
    ctxs = C.Contexts({}, {("fe", "calibration"): "calibration do1 for laboratory"})
    table = C.tabulate(study, noses, _done([1.2, 1.1, 1.3]), {("fe", "laboratory"): (0.1, "scope")}, "laboratory",
                       "li_chen", ctxs)
    x = table[table.nose == "x"].iloc[0]
    assert x.contrast == pytest.approx(1.2)
    assert x.u_chaos == pytest.approx(0.1 / 1.2)               # s.d. of 1.2, 1.1, 1.3 over their mean
    assert x.u_calibration == pytest.approx(1.3 / 1.2 - 1)
    assert x.u_validated == 0.1 and math.isnan(x.u_mesh) and "mesh not included" in x.parts
    assert x.u_combined == pytest.approx(math.sqrt(0.1**2 + (0.1 / 1.2)**2 + (1.3 / 1.2 - 1)**2))


def test_plan_runs_extra_fe_only_at_the_top_velocity():
    study = C.Study(noses={"a": ("ogive", {"psi": "3"}), "b": ("ogive", {"psi": "6"})}, reference="a",
                    shot={"mass_kg": "0.5", "diameter_m": "0.025", "length_m": "0.2", "fc_MPa": "40"},
                    velocities=(400.0, 600.0, 800.0), levels=("analytic", "fe"), members=3, mesh_check=True)
    jobs = C.plan(study)
    fe_extra = [j for j in jobs if j.level == "fe" and j.variant != "base"]
    assert {j.velocity for j in fe_extra} == {800.0}
    assert len(fe_extra) == 2 * (1 + 2 + 1)                    # calibration, 2 more members, the other mesh
    assert len([j for j in jobs if j.level == "analytic"]) == 2 * 3 * 2


@pytest.mark.parametrize("kw,needle", [
    ({"reference": "z"}, "one of the noses' labels"),
    ({"members": 1}, "2 <= members"),
    ({"levels": ("fe",), "shot": {"mass_kg": "0.5", "diameter_m": "0.025", "fc_MPa": "40"}}, "length_m"),
    ({"velocities": (400.0, 400.0)}, "each velocity once"),
    ({"velocities": (-5.0,)}, "velocity_ms"),
    ({"shot": {"mass_kg": "0.5", "fc_MPa": "40"}}, "diameter_m"),
    ({"shot": {"mass_kg": "abc", "diameter_m": "0.025", "fc_MPa": "40"}}, "mass_kg"),
    ({"levels": ("magic",)}, "levels among"),
    ({"shot": {"mass_kg": "0.5", "diameter_m": "0.025", "fc_MPa": "40", "speed": "3"}}, "a shot key"),
])
def test_study_refusals_name_the_field(kw, needle):
    base = dict(noses={"a": ("ogive", {"psi": "3"}), "b": ("ogive", {"psi": "6"})}, reference="a",
                shot={"mass_kg": "0.5", "diameter_m": "0.025", "length_m": "0.2", "fc_MPa": "40"},
                velocities=(400.0,), levels=("analytic",))
    with pytest.raises(ParameterError) as err:
        C.Study(**{**base, **kw})
    assert needle in str(err.value)


def test_cli_refusals_write_nothing(tmp_path):
    (tmp_path / "afile").write_text("x")
    res = cli("compare", "--nose", "a=ogive crh=3", "--nose", "b=ogive crh=6", "--velocities", "400", *SHOT,
              "--out", str(tmp_path / "afile"))
    assert res.returncode == 2 and "is a file" in res.stderr
    res = cli("compare", "--nose", "a=ogive crh=3", "--nose", "b=ogive nstar=0.9", "--velocities", "400", *SHOT,
              "--out", str(tmp_path / "o"))
    assert res.returncode == 2 and "nstar between" in res.stderr and not (tmp_path / "o").exists()
    res = cli("compare", "--nose", "a=ogive crh=3", "--nose", "b=ogive crh=6", "--velocities", "400:300:10", *SHOT,
              "--out", str(tmp_path / "o"))
    assert res.returncode == 2 and "--velocities" in res.stderr


def test_study_file_and_options(tmp_path):
    study = tmp_path / "s.yaml"
    study.write_text("noses:\n  a: {kind: ogive, crh: 3}\n  b: {kind: ogive, nose_length: 0.06}\nreference: b\n"
                     "shot: {mass_kg: 0.5, diameter_m: 0.025, fc_MPa: 40}\nvelocities: [500, 700]\ntitle: my study\n")
    res = cli("compare", "--study", str(study), "--out", str(tmp_path / "o"))
    assert res.returncode == 0, res.stderr
    rows = list(csv.DictReader(open(tmp_path / "o/compare.csv")))
    assert {r["reference"] for r in rows} == {"b"} and {float(r["velocity_ms"]) for r in rows} == {500.0, 700.0}
    study.write_text("noses: {}\nbogus: 1\n")
    res = cli("compare", "--study", str(study), "--out", str(tmp_path / "p"))
    assert res.returncode == 2 and "bogus" in res.stderr


def test_a_failed_calibration_run_leaves_its_part_out_and_says_why():
    from penetration.nose.geometry import Ogive
    study = C.Study(noses={"ref": ("ogive", {"psi": "3"}), "x": ("ogive", {"psi": "6"})}, reference="ref",
                    shot={"mass_kg": "0.5", "diameter_m": "0.025", "length_m": "0.2", "fc_MPa": "40"},
                    velocities=(1000.0,), levels=("fe",), members=2)
    noses = {"ref": (Ogive(3.0, 0.0125), None), "x": (Ogive(6.0, 0.0125), None)}
    done = [d for d in _done([1.2, 1.1]) if d[0].variant != "calibration"]
    done += [(C.Job("fe", "calibration", "ref", 1000.0), float("nan"), 0.0, "no DO1 record"),
             (C.Job("fe", "calibration", "x", 1000.0), float("nan"), 0.0, "no DO1 record")]
    x = C.tabulate(study, noses, done, {}, "laboratory", "li_chen", C.Contexts({}, {})).set_index("nose").loc["x"]
    assert math.isnan(x.u_calibration) and "not available: no DO1 record" in x.parts
    assert x.u_combined == pytest.approx(x.u_chaos) and C.base_failures(done) == []


@pytest.mark.parametrize("args,needle", [
    (("--velocities", "abc"), "--velocities"),
    (("--velocities", "400,,600"), "--velocities"),
    (("--velocities", "400:1000:1e-320"), "at most"),
    (("--velocities=-5",), "velocity_ms"),
    (("--velocities", "400", "--workers", "-1"), "--workers"),
    (("--velocities", "400", "--max-minutes", "0"), "--max-minutes"),
    (("--velocities", "400", "--nose", "c=ogive crh=3 psi=3"), "not both"),
])
def test_cli_bad_options_are_refused_naming_them(tmp_path, args, needle):
    res = cli("compare", "--nose", "a=ogive crh=3", "--nose", "b=ogive crh=6", *args, *SHOT, "--out", str(tmp_path / "o"))
    assert res.returncode == 2 and needle in res.stderr and "Traceback" not in res.stderr, res.stderr


@pytest.mark.parametrize("doc,needle", [
    ("noses: [a, b]\n", "noses"), ("shot: [1]\n", "shot"), ("velocities: 500\n", "velocities"),
    ("members: 2.9\n", "members"), ("mesh_check: 'false'\n", "mesh_check"),
])
def test_study_file_types_are_checked(tmp_path, doc, needle):
    study = tmp_path / "s.yaml"
    study.write_text(doc)
    res = cli("compare", "--study", str(study), "--out", str(tmp_path / "o"))
    assert res.returncode == 2 and needle in res.stderr and "Traceback" not in res.stderr, res.stderr


def test_velocity_ranges():
    from penetration.cli import _velocities
    assert _velocities("400:1000:100") == tuple(float(v) for v in range(400, 1001, 100))
    assert _velocities("400:1000:400") == (400.0, 800.0) and _velocities("500, 700") == (500.0, 700.0)


def test_a_zero_reference_depth_is_no_contrast():
    from penetration.nose.geometry import Ogive
    study = C.Study(noses={"ref": ("ogive", {"psi": "3"}), "x": ("ogive", {"psi": "6"})}, reference="ref",
                    shot={"mass_kg": "0.5", "diameter_m": "0.025", "fc_MPa": "40"}, velocities=(500.0,))
    noses = {"ref": (Ogive(3.0, 0.0125), None), "x": (Ogive(6.0, 0.0125), None)}
    done = [(C.Job("analytic", "base", "ref", 500.0), 0.0, 0.0, None), (C.Job("analytic", "base", "x", 500.0), 0.2, 0.0, None)]
    x = C.tabulate(study, noses, done, {}, "laboratory", "li_chen", C.Contexts({}, {})).set_index("nose").loc["x"]
    assert math.isnan(x.contrast)
