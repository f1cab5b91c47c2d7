"""An FE shot a user can look at: its histories (time, depth, velocity, deceleration) and the target's fields as
VTK files that meshio reads back, with PNGs; the writer round-trips a mesh exactly."""
import csv

import numpy as np
import pytest

meshio = pytest.importorskip("meshio")


def cli(*args):
    from conftest import run_cli
    return run_cli(*args)


def test_write_vtu_round_trips_a_mesh(tmp_path):
    from penetration.pipeline.io import write_vtu
    r, z = np.array([0.0, 1.0, 1.0, 0.0, 2.0, 2.0]), np.array([0.0, 0.0, 1.0, 1.0, 0.0, 1.0])
    quads = np.array([[0, 1, 2, 3], [1, 4, 5, 2]])
    write_vtu(tmp_path / "m.vtu", r, z, quads, {"damage": [0.25, 1.0], "state": [1, 0]})
    m = meshio.read(tmp_path / "m.vtu")
    assert np.array_equal(m.points[:, 0], r) and np.array_equal(m.points[:, 1], z)
    assert np.array_equal(m.cells_dict["quad"], quads)
    assert np.array_equal(m.cell_data["damage"][0], [0.25, 1.0])
    assert not list(tmp_path.glob(".*.tmp"))


def test_an_fe_shot_writes_histories_and_fields(tmp_path):
    v0 = 200.0
    res = cli("simulate", "ogive", "crh=3", "mass_kg=0.5", "diameter_m=0.025", "length_m=0.2", "fc_MPa=40",
              f"velocity_ms={v0:g}", "--model", "fe", "--profile", "ci", "--out", str(tmp_path / "h.csv"),
              "--fields", str(tmp_path / "f"), "--field-times-ms", "0.3", "--json")
    assert res.returncode == 0, res.stderr
    import json
    rec = json.loads(res.stdout)
    rows = list(csv.DictReader(open(tmp_path / "h.csv")))
    t, depth, vel, dec = (np.array([float(r[k]) for r in rows]) for k in ("t_s", "depth_m", "velocity_m_s",
                                                                         "deceleration_m_s2"))
    assert depth[-1] == pytest.approx(rec["depth_m"], rel=0.02) and vel[0] == pytest.approx(v0, rel=0.01)
    # the impulse of the contact force is the velocity lost (the binned deceleration conserves it)
    lost = vel[0] - vel[-1]
    assert np.sum(dec * np.gradient(t)) == pytest.approx(lost, rel=0.05)
    vtus = sorted((tmp_path / "f").glob("*.vtu"))
    assert len(vtus) == 2 and vtus[0].name == "fields_end.vtu" and vtus[1].name.startswith("fields_t0.")
    reach = {}
    for p in vtus:
        m = meshio.read(p)
        d, quads = m.cell_data["damage"][0], m.cells_dict["quad"]
        assert len(d) == len(quads)
        assert set(np.unique(m.cell_data["state"][0])) <= {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}
        assert p.with_suffix(".png").stat().st_size > 20_000
        r, z = (m.points[quads, k].mean(axis=1) for k in (0, 1))     # element centres (z into the target)
        reach[p.name] = (r[d > 0.5].max(), z[d > 0.5].max())
    end = meshio.read(tmp_path / "f/fields_end.vtu")
    assert (end.cell_data["damage"][0] > 0.99).any()        # the tunnel's wall is crushed
    # the damaged zone: wider than the shank (radius 12.5 mm), ahead of the nose's final depth, deeper at the end
    # than at 0.3 ms (the damage field, not another of the element rows)
    z_early, (r_end, z_end) = reach[vtus[1].name][1], reach["fields_end.vtu"]
    assert r_end > 0.0125 and z_end > rec["depth_m"] > z_early


def test_fields_refused_before_any_run(tmp_path):
    (tmp_path / "afile").write_text("x")
    keys = ("ogive", "crh=3", "mass_kg=0.5", "diameter_m=0.025", "length_m=0.2", "fc_MPa=40", "velocity_ms=200")
    res = cli("simulate", *keys, "--model", "cavity", "--out", str(tmp_path / "h.csv"), "--fields", str(tmp_path / "f"))
    assert res.returncode == 2 and "only with --model fe" in res.stderr
    res = cli("simulate", *keys, "--model", "fe", "--out", str(tmp_path / "h.csv"), "--fields", str(tmp_path / "afile"))
    assert res.returncode == 2 and "not a file" in res.stderr
    res = cli("simulate", *keys, "--model", "fe", "--out", str(tmp_path / "h.csv"), "--fields", str(tmp_path / "f"),
              "--field-times-ms", "-1")
    assert res.returncode == 2 and "--field-times-ms" in res.stderr and not (tmp_path / "h.csv").exists()
