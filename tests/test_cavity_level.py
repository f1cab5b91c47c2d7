"""The cavity level with a known sigma_n law reproduces the closed form."""
import numpy as np
import pytest

from conftest import recorded_work
from penetration.analytic.dop import penetration_depth
from penetration.analytic.resistance import Target
from penetration.cavity.level import SigmaTable, cavity_trajectory
from penetration.nose.geometry import DoubleOgive, Ogive
from penetration.nose.nstar import nstar

TG = Target(2440.0, 48e6, 6.69)


@pytest.mark.parametrize("nose", [Ogive(3, 0.07), DoubleOgive(0.07, S1=0.8576, S2=0.42, a1=0.0397, a2=0.0638,
                                                                alpha=0.245)], ids=lambda n: n.kind)
@pytest.mark.parametrize("vs", [150.0, 835.0, 1500.0])
def test_forrestal_law_as_a_table_gives_eq9(nose, vs):
    v = np.linspace(0, 2000, 4001)
    table = SigmaTable(v, TG.R + TG.rho * v**2, np.zeros(v.size, bool))
    depth = cavity_trajectory(nose, 81.1, vs, table, rtol=1e-9).depth
    assert depth == pytest.approx(float(penetration_depth(81.1, 0.07, nstar(nose), TG, vs)), rel=1e-5)


def test_table_is_exact_for_forrestal_form_on_coarse_nodes():
    """PCHIP in v^2 reproduces A + B v^2 between and beyond sparse nodes."""
    v = np.array([0.0, 200.0, 700.0, 1000.0, 2000.0])
    table = SigmaTable(v, 3e8 + 1.1 * 2440 * v**2, np.zeros(v.size, bool))
    probe = np.linspace(0.0, 3000.0, 301)
    np.testing.assert_allclose(table(probe), 3e8 + 1.1 * 2440 * probe**2, rtol=1e-12)


def test_table_extends_beyond_its_range_linearly_in_v_squared():
    t = SigmaTable(np.array([0.0, 1.0, 2.0]), np.array([1.0, 2.0, 4.0]), np.zeros(3, bool))
    assert t(3.0) == pytest.approx(4.0 + (2.0 / 3.0) * 5.0)
    assert t(1.0) == pytest.approx(2.0) and t(2.0) == pytest.approx(4.0)


def test_table_is_monotone_between_nodes():
    v = np.array([0.0, 50.0, 100.0, 300.0, 800.0, 2000.0])
    s = np.array([2.7e8, 2.75e8, 3.3e8, 6.6e8, 2.1e9, 1.06e10])  # shape of the calibrated HJC table
    probe = np.linspace(0, 2000, 4001)
    assert np.all(np.diff(SigmaTable(v, s, np.zeros(v.size, bool))(probe)) >= 0)


@pytest.mark.parametrize("v", [np.array([0.0]), np.array([0.0, 2.0, 1.0]), np.array([-1.0, 1.0])])
def test_table_rejects_bad_velocities(v):
    with pytest.raises(ValueError, match="strictly increasing"):
        SigmaTable(v, np.ones(v.size), np.zeros(v.size, bool))


@pytest.fixture(scope="module")
def hjc_table():
    """sigma_n(v) of Table 1 HJC concrete at a strength scale near the calibrated one."""
    from pathlib import Path

    from penetration.cavity.level import sigma_table
    from penetration.concrete.hjc import from_table1
    from penetration.paper.reference import load_reference
    refs = load_reference(Path(__file__).resolve().parents[1] / "workflow/reference/paper_values.csv")
    mat = from_table1(lambda q: refs[f"table1.{q}"].si, strength_scale=0.6)
    v = [50.0, 100.0, 200.0, 400.0, 800.0, 1200.0, 2000.0]
    return sigma_table(mat, v, 0.07)[0]


@pytest.mark.parametrize("effects", [("crater", "cavity"), ("nose_entry", "cavity")])
@pytest.mark.parametrize("nose", [Ogive(3, 0.07), Ogive(0.5, 0.07), DoubleOgive(0.07, S1=0.8576, S2=0.42, a1=0.0397,
                                                                                 a2=0.0638, alpha=0.245)],
                         ids=lambda n: f"{n.kind}")
def test_hjc_level_finite_monotone_and_energy_closed_from_30_to_2500(hjc_table, nose, effects):
    """Hard cases 8 and 9: stops in the crater phase, extrapolation above the table, blunt nose."""
    depths = []
    for vs in (30.0, 100.0, 250.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0):
        tr = cavity_trajectory(nose, 81.1, vs, hjc_table, effects, rtol=1e-8)
        assert np.isfinite(tr.depth) and tr.depth > 0
        assert recorded_work(tr, 81.1) == pytest.approx(0.5 * 81.1 * vs**2, rel=1e-3)
        depths.append(tr.depth)
    assert np.all(np.diff(depths) > 0)


@pytest.mark.parametrize("name, truth", [("strength_scale", 0.7), ("erosion_strain", 0.3)])
def test_calibration_recovers_the_parameter_that_made_the_depth(name, truth):
    """Round trip on a coarse table: the depth of a known parameter value gives that value back."""
    import dataclasses

    from penetration.cavity.expansion import Mesh
    from penetration.cavity.level import calibrate_parameter, sigma_table
    from penetration.concrete.hjc import HJC
    mesh, vel, nose = Mesh(zones=40), [100.0, 400.0, 900.0, 2000.0], Ogive(3, 0.07)
    table, _ = sigma_table(dataclasses.replace(HJC(), **{name: truth}), vel, 0.07, mesh)
    depth = cavity_trajectory(nose, 81.1, 835.0, table).depth
    fit = calibrate_parameter(HJC(), name, nose, 81.1, 835.0, depth, vel, 0.07, mesh=mesh)
    assert fit[name] == pytest.approx(truth, rel=2e-3) and abs(fit["relative_residual"]) < 1e-3


def test_calibration_names_an_unknown_parameter():
    from penetration.cavity.level import calibrate_parameter
    from penetration.concrete.hjc import HJC
    with pytest.raises(ValueError, match="not in"):
        calibrate_parameter(HJC(), "D1", Ogive(3, 0.07), 81.1, 835.0, 5.1, [100.0, 500.0], 0.07)


def test_linear_interpolation_of_the_density_study_is_straight_in_v():
    v = np.array([0.0, 100.0, 400.0])
    t = SigmaTable(v, 1e8 + 2e5 * v, np.zeros(3, bool), interpolation="linear_v")
    np.testing.assert_allclose(t(np.array([50.0, 250.0, 400.0])), 1e8 + 2e5 * np.array([50.0, 250.0, 400.0]))
    with pytest.raises(ValueError, match="interpolation"):
        SigmaTable(v, v, np.zeros(3, bool), interpolation="cubic")
