"""Finite-element level: verification against closed forms, published solutions, the cavity level, and audits."""
import math

import numpy as np
import pytest

from penetration.concrete.hjc import HJC
from penetration.fe import (Controls, Grid, MeshSpec, Model, Projectile, Unstable, body_outline, build, run,
                            state as fe_state)
from penetration.fe.nodes import node_pass
from penetration.fe.verification import setups
from penetration.nose.geometry import Flat, Ogive

# one element pass over every row, and the nodal force sums by the solver's own gather (the verification's helpers;
# the verification problems themselves, the patch test, rigid translation and penetration audit among them, run in
# tests/test_verification.py)
_pass, _residual = setups.element_pass, setups.nodal_forces

def _penetration(nose, v, h=0.02, fs=1.0, end=1.5e-3, **kw):
    a = 0.07
    zeta, rho = body_outline(nose, 1.13)
    g = build(MeshSpec(h, 3 * a, 2.0, 1.0, 2.5, 1.15))
    c = dict(erosion="plastic_strain", erosion_value=fs, end_time=end, output_interval=1e-4,
             lateral="non_reflecting", bottom="non_reflecting")
    c.update(kw)
    m = Model(g, HJC(), Controls(**c))
    p = Projectile(zeta, rho, 81.1, 0.0, v)
    return m, p, run(m, p)


def test_a_shot_is_bit_identical_on_one_and_two_threads():
    """Rows are independent tasks and no kernel reassociates a sum: the thread count cannot change a result (the
    discrete erosion is chaotic, so anything less than bit-identity would show as a different depth)."""
    import numba

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("one core: there is no second thread to compare with")
    n0 = numba.get_num_threads()
    out = []
    try:
        for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(threads)
            m, p, res = _penetration(Ogive(3.0, 0.07), 835.0, end=1e-3)
            out.append((p.Zt, p.V, m.E.copy(), m.vz.copy(), m.alive.copy()))
    finally:
        numba.set_num_threads(n0)
    (z1, v1, E1, w1, a1), (z2, v2, E2, w2, a2) = out
    assert z1 == z2 and v1 == v2 and np.array_equal(a1, a2)
    assert np.array_equal(E1, E2) and np.array_equal(w1, w2)
    assert (a1 == 0).sum() > 0  # elements eroded: the chaotic path was exercised


@pytest.mark.parametrize("nose,v", [(Flat(0.07), 300.0), (Ogive(0.5, 0.07), 1500.0), (Ogive(3.0, 0.07), 1500.0)])
def test_hard_shots_stay_finite(nose, v):
    """A flat and a hemispherical nose, 300 and 1500 m/s: finite results and a closed audit (guards on)."""
    m, p, res = _penetration(nose, v, end=1e-3)
    assert np.isfinite(p.Zt) and 0 < p.V <= v
    assert np.all(np.isfinite(m.vz)) and abs(res.audit[-1]["energy_error"]) < 0.02


def test_inverted_element_without_guard_stops_with_a_diagnostic():
    with pytest.raises(Unstable, match=r"inverted element .* at r = .* m, z = .* m"):
        _penetration(Ogive(3.0, 0.07), 835.0, erosion="none", guard=False, end=2e-3)


def test_time_step_collapse_is_refused_or_eroded():
    """A floor above the initial step: without the guard the run stops naming the element, with it the element erodes."""
    with pytest.raises(Unstable, match="time step below the floor"):
        _penetration(Ogive(3.0, 0.07), 835.0, guard=False, dt_floor=0.9, end=5e-4)
    m, p, res = _penetration(Ogive(3.0, 0.07), 835.0, guard=True, dt_floor=0.9, end=3e-4)
    assert m.ledger.eroded_mass > 0 and np.isfinite(p.Zt)


def test_controls_refuse_bad_values():
    from penetration.errors import ParameterError
    with pytest.raises(ParameterError, match="hourglass"):
        Controls(hourglass=0.3)
    with pytest.raises(ParameterError, match="erosion"):
        Controls(erosion="strain")
    with pytest.raises(ParameterError, match="element_size"):
        MeshSpec(0.5, 0.2, 1.0, 2.0, 3.0)


def test_mesh_columns_in_multiples_of_the_vector_width():
    """The radial grading is eased so that a row has a multiple of 4 elements (no scalar remainder in the
    kernels): the core keeps its size, the graded cells still grow, by at most the spec's ratio, and the last
    node lies on the outer radius. Left as they are: a radius the core fills, and a graded span too short for
    the extra cells even at the core's size."""
    from penetration.fe.mesh import graded
    for h, core, radius, ratio in ((0.00875, 0.21, 1.8, 1.1), (0.021, 0.21, 1.8, 1.1), (0.0035, 0.21, 1.8, 1.1),
                                   (0.00875, 0.21, 2.5, 1.05), (0.01, 0.2, 0.33, 1.5)):
        x = graded(0.0, core, radius, h, ratio, 4)
        d = np.diff(x)
        n_core = int(math.ceil(core / h - 1e-9))
        assert d.size % 4 == 0 and 0 <= d.size - (graded(0.0, core, radius, h, ratio).size - 1) <= 3, d.size
        assert np.allclose(d[:n_core], h, rtol=1e-12)
        growth = d[n_core:] / d[n_core - 1:-1]
        assert np.all(growth > 1.0) and np.all(growth <= ratio * (1 + 1e-9)), (growth.min(), growth.max())
        assert abs(x[-1] - radius) < 1e-12 * radius
    assert np.array_equal(graded(0.0, 0.5, 0.5, 0.05, 1.1, 4), graded(0.0, 0.5, 0.5, 0.05, 1.1))  # 10 core cells
    # 4 core cells and 5 graded ones (ratio 1.2) over 0.4 m: 8 graded cells would need more than 8 x 0.05 m
    assert np.array_equal(graded(0.0, 0.2, 0.6, 0.05, 1.2, 4), graded(0.0, 0.2, 0.6, 0.05, 1.2))
    assert build(MeshSpec(0.00875, 0.21, 2.5, 1.2, 2.5, 1.1)).nr % 4 == 0


def test_hourglass_control_stays_active_in_fully_damaged_material():
    """An hourglass velocity mode in fully damaged HJC (no shear strength left) is resisted: the force opposes the
    mode and its work is positive; a linear field in the same elements gets no hourglass force."""
    g = Grid.tensor(np.linspace(0.5, 0.6, 3), np.linspace(0.0, 0.1, 3))
    m = Model(g, HJC(), Controls(hourglass=0.1))
    m.E[fe_state.DMG] = 1.0
    h = np.array([1.0, -1.0, 1.0, -1.0])
    m.vz[:] = 0.0
    for e, nodes in enumerate(g.connectivity()):
        m.vz[nodes] += 0.25 * h  # superposed hourglass patterns (a checkerboard on the nodes)
    _pass(m, 1e-7)
    fr, fz = _residual(m)
    assert m.rows.hg.sum() > 0
    assert np.dot(fz, m.vz) > 0  # internal force in the direction of the mode: the node update opposes it
    m2 = Model(g, HJC(), Controls(hourglass=0.1))
    m2.E[fe_state.DMG] = 1.0
    m2.vz[:] = 0.1 * m2.z
    _pass(m2, 1e-7)
    assert m2.rows.hg.sum() < 1e-12 * m.rows.hg.sum()


def test_failure_strain_calibration_finds_the_root_of_a_noisy_decreasing_depth(monkeypatch):
    """The bracketing secant in log fs stops within tol of the target despite a 0.3 % noise (a stand-in for the FE
    run: depth = 5.1 (1.02/fs)^0.8 (1 + noise)); a bracket that misses the target is refused."""
    from penetration.fe import level as fe_level
    from penetration.fe.shot import RunSpec
    rng = np.random.default_rng(1)

    class Run:
        def __init__(self, fs):
            self.depth = 5.1 * (1.02 / fs) ** 0.8 * (1 + 0.003 * rng.standard_normal())
            self.wall_time, self.status, self.peak_deceleration, self.elements, self.steps = 1.0, "rest", 1.0, 1, 1

        def summary(self):
            return {"energy_error_max": 0.0}

    monkeypatch.setattr(fe_level, "run_shot", lambda spec, **k: Run(spec.settings.controls.erosion_value))
    spec = RunSpec(None, 81.1, 835.0, None)
    fit = fe_level.calibrate_failure_strain(spec, 5.1, tol_m=0.02)
    assert fit["converged"] and abs(fit["residual_m"]) <= 0.02
    assert fit["fs"] == pytest.approx(1.02, rel=0.02)
    assert len(fit["runs"]) <= 10
    with pytest.raises(ValueError, match="no fs in"):
        fe_level.calibrate_failure_strain(spec, 5.1, bracket=(1.5, 3.0))


def test_node_pass_without_dashpot_arithmetic_gives_the_same_velocities():
    """Rows flagged dashpot-free take a leaner loop: bit for bit the velocities of the full dashpot arithmetic."""
    m = Model(build(MeshSpec(0.05, 0.2, 1.0, 0.6, 1.2, 1.2)), HJC(), Controls(lateral="non_reflecting", bottom="non_reflecting"))
    g = m.grid
    m.add_dashpots(7 * (g.nr + 1) + np.arange(g.nr + 1))   # a window's bottom row inside the grid
    assert list(np.nonzero(m.rowdash)[0]) == [7, g.nz]  # the bottom face is a grid edge: its flag is never read
    rng = np.random.default_rng(5)
    F = rng.standard_normal(m.F.shape)
    m.fix[:] = rng.integers(0, 4, m.fix.size)         # every fixity and dropped nodes, inside the rows too
    m.nstate[:] = 2 * rng.integers(0, 2, m.nstate.size)
    out = []
    for flags in (m.rowdash, np.ones_like(m.rowdash)):
        V = np.zeros_like(m.V)
        V[fe_state.VR], V[fe_state.VZ] = np.sin(np.arange(m.vr.size)), np.cos(np.arange(m.vz.size))
        V[fe_state.VR, m.on_axis] = 0.0
        rf = np.zeros_like(m.rows.f)
        node_pass(m.span(), F, m.alive, m.mass, m.nstate, m.fix, m.dash, flags, (m.zp, m.zs), 1e-6, V, rf)
        out.append((V[fe_state.VR], V[fe_state.VZ], rf[[fe_state.RF_POWER, fe_state.RF_IMPULSE]]))
    for a, b in zip(out[0], out[1]):
        assert np.array_equal(a, b)
    assert np.all(out[0][2][0, [7, g.nz]] != 0.0)  # the dashpots absorbed power where they are


@pytest.mark.parametrize("case", ["erosion", "floor", "non_finite", "plastic_strain", "damage", "guarded_floor"])
def test_elastic_elements_of_the_vectorised_update_are_still_checked(case):
    """Elements completed by the branch-free HJC update (elastic here) still erode (on the effective strain, the
    plastic strain carried from earlier steps, the damage), hit the step floor (a stop without the guard, an erosion
    with it), or report a non-finite state."""
    controls = {"erosion": Controls(erosion="effective_strain", erosion_value=1e-12),
                "floor": Controls(guard=False, dt_floor=1.0), "non_finite": Controls(),
                "plastic_strain": Controls(erosion="plastic_strain", erosion_value=0.3),
                "damage": Controls(erosion="damage", erosion_value=0.9),
                "guarded_floor": Controls(guard=True, dt_floor=1.0)}[case]
    m = Model(build(MeshSpec(0.05, 0.2, 1.0, 0.6, 1.2, 1.2)), HJC(), controls)
    m.vz[:] = -1e-3 * m.z   # a uniaxial compression far inside the elastic range
    if case in ("floor", "guarded_floor"):
        m.ctl[fe_state.C_DTMIN] = 2.0 * m.dt0
    if case == "non_finite":
        m.E[fe_state.IE, m.nr + 5] = np.inf   # an element that is otherwise fine: only the check can catch it
    marked = m.nr + 5
    if case == "plastic_strain":
        m.E[fe_state.EPSP, marked] = 0.5      # plastic strain from earlier steps, no flow now
    if case == "damage":
        m.E[fe_state.DMG, marked] = 0.95      # damaged earlier, elastic now
    E0 = m.E.copy()
    _pass(m, 1e-7)
    assert np.all(m.E[fe_state.EPSP] == E0[fe_state.EPSP]) and np.all(m.E[fe_state.MUP] == 0.0)  # elastic: hjc.quick_update's case (a)
    assert np.all(m.E[fe_state.DMG] == E0[fe_state.DMG])
    if case in ("plastic_strain", "damage"):
        assert np.flatnonzero(m.alive == fe_state.ERODING).tolist() == [marked]
        assert m.rows.ero.sum() == m.E[fe_state.IE, marked] > 0 and np.all(m.rows.fail == -1)
    elif case == "guarded_floor":
        assert np.all(m.alive == fe_state.ERODING) and np.all(m.rows.fail == -1)
    elif case == "erosion":
        assert np.all(m.alive == fe_state.ERODING)
        assert math.isclose(m.rows.ero.sum(), m.E[fe_state.IE].sum(), rel_tol=1e-12) and m.rows.ero.sum() > 0
        assert np.all(m.E[fe_state.IE] > E0[fe_state.IE])
    elif case == "floor":
        assert m.rows.fail[0] == 0 and m.rows.code[0] == fe_state.DT_COLLAPSE
    else:
        assert [j for j in range(m.nz) if m.rows.fail[j] >= 0] == [1]
        assert m.rows.fail[1] == m.nr + 5 and m.rows.code[1] == fe_state.NON_FINITE


def test_an_elastic_pass_changes_no_row_of_E_outside_the_step_stores():
    """The speed benchmark's floor counts as written only the rows of E in state.STEP_STORES: in the elastic
    state it times (random velocities, half of the elements in tension) no other row changes, and the stored
    ones that carry the state do."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "workflow" / "benchmarks"))
    from fe_speed import _elastic_state  # the benchmark's own state, not a copy of it
    m = Model(build(MeshSpec(0.05, 0.2, 1.0, 0.6, 1.2, 1.2)), HJC(), Controls())
    _elastic_state(m)
    E0 = m.E.copy()
    _pass(m, 0.5 * m.dt)
    others = [f for f in range(fe_state.N_FIELDS) if f not in fe_state.STEP_STORES]
    assert sorted(others) == sorted([fe_state.MUP, fe_state.DMG, fe_state.V0, fe_state.MASS])
    assert np.array_equal(m.E[others], E0[others])
    assert all(np.any(m.E[f] != E0[f]) for f in (fe_state.SRR, fe_state.SZZ, fe_state.STT, fe_state.SRZ, fe_state.P, fe_state.IE, fe_state.EPSEFF))


def test_a_check_row_carries_its_deviation_and_verdict():
    from penetration.checks import below, near
    c = near("p", "q", 2.2, 2.0, 0.05, "m", "s")
    assert not c.holds and c.rel_dev == pytest.approx(0.1, rel=1e-12)
    assert list(c.row()) == ["problem", "quantity", "ours", "reference", "rel_dev", "low", "high", "unit", "source", "holds"]
    b = below("p", "q", 0.5, 1.0, "1", "s")
    assert b.holds and math.isnan(b.rel_dev) and b.row()["holds"] is True


def test_body_outline_does_not_follow_round_off_in_the_nose():
    """numpy's vector maths differ in the last bit between CPUs; the rigid body the erosion sees must not."""
    from types import SimpleNamespace

    from penetration.nose.geometry import MinimumNstar
    nose = MinimumNstar(0.07, Ogive(4.5, 0.07).length)
    x, y = nose.outline(400)
    jittered = SimpleNamespace(length=nose.length, radius=nose.radius,
                               outline=lambda n: (x * (1 + 4e-16), y * (1 - 4e-16)))
    assert not np.array_equal(jittered.outline(400)[0], x)
    for a, b in zip(body_outline(nose, 1.13), body_outline(jittered, 1.13)):
        assert np.array_equal(a, b)
