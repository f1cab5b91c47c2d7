"""HJC single-element tests against closed forms (design note 2.8)."""
import math

import numpy as np
import pytest

from penetration.concrete.hjc import HJC, PointState, drive, fracture_strain, loading_pressure, strength
from penetration.errors import ParameterError

MAT = HJC()
Q = MAT.as_array()


def hydro(mu_target, n=400, state=None, material=MAT):
    """Hydrostatic path from the state's volumetric strain to mu_target."""
    st = state or PointState.new()
    ev0 = st.strain[:3].sum()
    ev1 = -math.log(1 + mu_target)
    de = (ev1 - ev0) / n / 3
    return drive(material, np.tile([de, de, de, 0, 0, 0], (n, 1)), state=st)


def p_virgin(mu, m=MAT):
    """Independent transcription of Eqs 12, 13, 15 with the offset lock."""
    if mu <= m.muc:
        return m.pc / m.muc * mu
    if mu <= m.mul:
        return m.pc + (m.pl - m.pc) * (mu - m.muc) / (m.mul - m.muc)
    mb = (mu - m.mu_lock) / (1 + m.mu_lock)
    return m.k1 * mb + m.k2 * mb**2 + m.k3 * mb**3


def test_derived_elastic_constants_decode_table1():
    assert MAT.Ke == pytest.approx(16e9)
    assert MAT.E == pytest.approx(34.04e9, rel=1e-3)
    assert MAT.nu == pytest.approx(0.145, abs=5e-4)


def test_hydrostatic_loading_follows_the_three_stages():
    out, _ = hydro(0.2)
    expected = np.array([p_virgin(m) for m in out["mu"]])
    assert np.allclose(out["p"], expected, rtol=1e-12, atol=1.0)


def test_offset_lock_is_continuous_literal_is_not():
    assert p_virgin(MAT.mul + 1e-12) == pytest.approx(MAT.pl, rel=1e-6)
    lit = HJC(lock="literal")
    ql = lit.as_array()
    assert loading_pressure(lit.mul + 1e-9, ql) == pytest.approx(0.0, abs=1e3)  # the literal drop to zero
    mus = np.linspace(0, 0.25, 5001)
    jumps = np.abs(np.diff([loading_pressure(m, Q) for m in mus]))
    assert jumps.max() < 0.02 * MAT.pl  # no jump larger than the grid step times the stiffest slope


@pytest.mark.parametrize("mu_max", [0.02, 0.05, 0.09])
def test_unloading_from_crush_stage_has_eq14_slope(mu_max):
    _, st = hydro(mu_max)
    out, _ = hydro(mu_max - 0.004, n=40, state=st)
    F = (mu_max - MAT.muc) / (MAT.mul - MAT.muc)
    K = (1 - F) * MAT.Ke + F * MAT.k1
    slope = (out["p"][-1] - out["p"][0]) / (out["mu"][-1] - out["mu"][0])
    assert slope == pytest.approx(K, rel=1e-9)


def test_reload_returns_to_the_virgin_curve():
    _, st = hydro(0.06)
    _, st = hydro(0.03, state=st)
    out, _ = hydro(0.08, state=st)
    assert out["p"][-1] == pytest.approx(p_virgin(0.08), rel=1e-9)


def test_uniaxial_strain_leaves_permanent_crush_strain():
    st = PointState.new()
    n = 500
    de = -math.log(1.12) / n
    load, st = drive(MAT, np.tile([de, 0, 0, 0, 0, 0], (n, 1)), state=st)
    assert load["p"].max() > 1e9
    mu_p = st.mu_p
    unload, st = drive(MAT, np.tile([-de, 0, 0, 0, 0, 0], (n, 1)), state=st)
    assert 0.05 < mu_p < 0.1
    # on the way back the pressure reaches zero at mu = mu_p (dense: at mu_lock), not at mu = 0
    zero = unload["mu"][np.argmin(np.abs(unload["p"]))]
    assert zero == pytest.approx(MAT.mu_lock, abs=2e-3)


@pytest.mark.parametrize("pstar", [0.0, 1.0, 5.0, 10.0, 20.0])
def test_strength_surface(pstar):
    p = pstar * MAT.fc
    expected = min(MAT.smax, MAT.A + MAT.B * pstar**MAT.N) * MAT.fc
    assert strength(p, 0.0, 1.0, Q) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("mu0", [0.0, 0.005, 0.05])
def test_first_yield_in_shear_at_the_surface(mu0):
    """Confine, then shear at constant volume: first yield at sigma_y(p, D) of that state."""
    st = PointState.new()
    if mu0 > 0:
        _, st = hydro(mu0, state=st)
    p0, d0 = st.p, st.D
    g = 5e-6
    out, st = drive(MAT, np.tile([0, 0, 0, g, 0, 0], (3000, 1)), state=st)
    first = np.argmax(out["eps_p"] > 0)
    assert first > 0
    assert out["seq"][first] == pytest.approx(strength(p0, d0, 1.0, Q), rel=1e-9)


def test_pure_shear_at_zero_pressure_fails_at_efmin():
    out, _ = drive(MAT, np.tile([0, 0, 0, 5e-5, 0, 0], (2000, 1)))
    assert np.allclose(out["p"], 0.0)
    assert fracture_strain(0.0, Q) == pytest.approx(MAT.efmin)
    full = np.argmax(out["D"] >= 1.0)
    assert out["D"][-1] == 1.0
    assert out["eps_p"][full] == pytest.approx(MAT.efmin, rel=2e-2)
    assert out["seq"][-1] == pytest.approx(0.0, abs=1.0)


def test_tension_cutoff_and_damage():
    out, st = hydro(-0.01)
    assert out["p"].min() == pytest.approx(-MAT.T, rel=1e-12)
    drive(MAT, np.tile([0, 0, 0, 5e-5, 0, 0], (2000, 1)), state=st)  # damage it fully
    out, _ = hydro(-0.02, state=st, n=50)
    assert out["p"].min() == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("tension", ["openradioss", "sphinxsys"])
def test_tension_branches_reach_zero_where_documented(tension):
    q = HJC(tension=tension).as_array()
    assert strength(-MAT.T, 0.0, 1.0, q) == pytest.approx(0.0, abs=1e-9)
    D = 0.5
    zero_at = -MAT.T if tension == "openradioss" else -MAT.T * (1 - D)
    assert strength(zero_at, D, 1.0, q) == pytest.approx(0.0, abs=1e-6)
    assert strength(0.5 * zero_at, D, 1.0, q) > 0


def test_rate_effect_and_floor():
    s1 = strength(MAT.fc, 0.0, 1.0, Q)
    assert strength(MAT.fc, 0.0, 1e4, Q) / s1 == pytest.approx(1 + MAT.C * math.log(1e4), rel=1e-12)
    assert strength(MAT.fc, 0.0, 1e-3, Q) == pytest.approx(s1)
    q = HJC(rate_floor=False).as_array()
    assert strength(MAT.fc, 0.0, 1e-3, q) < s1


def test_rigid_rotation_keeps_invariants():
    st = PointState.new()
    _, st = hydro(0.004, state=st)
    drive(MAT, [[2e-5, -1e-5, -1e-5, 1e-5, 0, 0]], state=st)
    j2 = lambda s: 0.5 * s[:3] @ s[:3] + s[3:] @ s[3:]
    before, s0 = j2(st.s), st.s.copy()
    w = np.array([[0, -1.0, 0], [1.0, 0, 0], [0, 0, 0]])
    out, st2 = drive(MAT, np.zeros((200, 6)), state=st, spin=w, dt=math.pi / 2 / 200)
    assert j2(st2.s) == pytest.approx(before, rel=1e-12)
    assert not np.allclose(st2.s, s0)  # it did rotate


def test_step_halving_converges_on_a_mixed_path():
    """Compression with a shear direction turning through 180 deg: first-order convergence."""
    def path(n):
        th = np.linspace(0, math.pi, n, endpoint=False) + math.pi / (2 * n)
        amp = 2e-2 / n
        inc = np.zeros((n, 6))
        inc[:, :3] = -1e-2 / n / 3
        inc[:, 3], inc[:, 5] = amp * np.cos(th), amp * np.sin(th)
        return inc
    final = [drive(MAT, path(n))[0]["sigma"][-1] for n in (100, 200, 400, 1600)]
    errs = [np.linalg.norm(final[i] - final[-1]) for i in range(3)]
    assert errs[0] > errs[1] > errs[2] > 0
    assert errs[1] / errs[2] == pytest.approx(2.0, rel=0.35)


def test_bad_parameters():
    with pytest.raises(ParameterError, match="lock"):
        HJC(lock="glued")
    with pytest.raises(ParameterError, match="pc"):
        HJC(pc=-1.0)


def test_erosion_strain_removes_deviatoric_stress_and_keeps_pressure():
    """Confined shear: identical to the uneroded point until eps_p reaches erosion_strain, then seq = 0."""
    import dataclasses
    eroding = dataclasses.replace(MAT, erosion_strain=0.02)
    paths = []
    for m in (MAT, eroding):
        _, st = hydro(0.05, material=m)
        paths.append(drive(m, np.tile([0, 0, 0, 2e-5, 0, 0], (3000, 1)), state=st)[0])
    plain, ero = paths
    before = ero["eps_p"] < 0.02
    assert before.sum() > 10 and (~before).sum() > 10
    np.testing.assert_allclose(ero["seq"][before], plain["seq"][before], rtol=1e-12)
    after = np.flatnonzero(~before)[1:]  # the step that crosses the limit still yields at the surface
    assert np.all(ero["seq"][after] <= 1e-6 * plain["seq"][after])
    np.testing.assert_allclose(ero["p"], plain["p"], rtol=1e-12)  # pressure depends on mu only


def test_erosion_strain_validated():
    with pytest.raises(ParameterError, match="erosion_strain"):
        HJC(erosion_strain=0.0)


def test_extended_crushing_lock_keeps_mul_as_offset_and_meets_the_dense_curve_at_pl():
    """Extended convention (SPHinXsys HJCSolid): the dense curve k1 x + k2 x^2 + k3 x^3 with x = (mu - mul)/(1 + mul)
    is zero at mul; the crushing line runs from (muc, pc) to where that curve reaches pl (about 0.1106)."""
    ext = HJC(lock="extended")
    q = ext.as_array()
    x = (ext.mu_crush_end - ext.mul) / (1 + ext.mul)
    assert ext.k1 * x + ext.k2 * x**2 + ext.k3 * x**3 == pytest.approx(ext.pl, rel=1e-12)
    assert ext.mu_crush_end == pytest.approx(0.1106, abs=1e-4)
    assert ext.mu_lock == ext.mul
    assert loading_pressure(ext.mu_crush_end, q) == pytest.approx(ext.pl, rel=1e-12)
    assert loading_pressure(ext.mu_crush_end + 1e-9, q) == pytest.approx(ext.pl, rel=1e-6)  # continuous
    mid = 0.5 * (ext.muc + ext.mu_crush_end)
    assert loading_pressure(mid, q) == pytest.approx(0.5 * (ext.pc + ext.pl), rel=1e-12)  # a straight crushing line
    mus = np.linspace(0, 0.25, 5001)
    assert np.all(np.diff([loading_pressure(m, q) for m in mus]) > 0)  # monotone, no drop at mul
    # unloading from the dense region returns along the dense curve to zero at mul
    _, st = hydro(0.15, material=ext)
    out, _ = hydro(0.105, n=200, state=st, material=ext)
    xb = (0.105 - ext.mul) / (1 + ext.mul)
    assert out["p"][-1] == pytest.approx(ext.k1 * xb + ext.k2 * xb**2 + ext.k3 * xb**3, rel=1e-6)


@pytest.mark.parametrize("tension, rate_law", [("openradioss", "hjc"), ("sphinxsys", "hjc"),
                                               ("openradioss", "mc2010_extrapolate"), ("openradioss", "mc2010_cap")])
def test_quick_update_equals_the_full_point_update(tension, rate_law):
    """hjc.quick_update (the FE level's vectorised shortcut) against update_point on random states across the
    three EOS regions, loading and unloading, compression and tension, damaged, intact and fully damaged, slow and
    fast, with HJC's rate factor or MC2010's: wherever the shortcut claims validity it must give update_point's
    stress, pressure, mu_max and plastic strain increment, with the damage and mu_p unchanged."""
    from penetration.concrete.hjc import permanent_strain, power_chords, quick_update, update_point

    mat = HJC(tension=tension, rate_law=rate_law)
    q = mat.as_array()
    chords = power_chords(q)
    rng = np.random.default_rng(7)
    n_valid = n_flow = 0
    regions = set()
    n = 8000
    for _ in range(n):
        mu_max = float(rng.choice([0.0, rng.uniform(0, mat.muc), rng.uniform(mat.muc, mat.mul), rng.uniform(mat.mul, 0.3)]))
        mu = float(mu_max + rng.uniform(-0.004, 0.002))
        D = float(rng.choice([0.0, rng.uniform(0, 1), 1.0]))
        s = rng.normal(0, float(rng.choice([1e5, 3e6, 3e7])), 4)
        s[2] = -s[0] - s[1]
        de = rng.normal(0, 1e-5, 4)
        rate = float(rng.choice([0.0, 0.5, 30.0, 3e4]))
        mu_p = 0.0 if mu_max <= mat.muc else float(permanent_strain(mu_max, q))
        valid, s0, s1, s2, s3, p, mm, dep, _ = quick_update(*s, mu, mu_max, D, 0.0, *de, rate, q, chords)
        if not valid:
            continue
        n_valid += 1
        n_flow += dep > 0
        regions.add((mm <= mat.muc, mm <= mat.mul, p >= 0, D >= 1))
        s6 = np.array([*s, 0.0, 0.0])
        d6 = np.array([*de, 0.0, 0.0])
        p_ref, mm_ref, mu_p_ref, D_ref, dep_ref = update_point(s6, mu, mu_max, mu_p, D, 0.0, d6, rate, q)
        assert D_ref == D and mu_p_ref == mu_p and mm == mm_ref
        assert dep == pytest.approx(dep_ref, rel=1e-12, abs=1e-300)
        assert p == pytest.approx(p_ref, rel=1e-12, abs=1e-6)
        assert np.allclose([s0, s1, s2, s3], s6[:4], rtol=1e-12, atol=1e-6)
    # the shortcut must cover the common cases, not only trivial ones
    assert n_valid > 0.3 * n and n_flow > 0.02 * n and len(regions) >= 6


def test_power_chords_bound_the_power_from_below():
    """min over power_chords' lines <= x^N on [0, 32], exact at the breakpoints, within 2 % between them."""
    from penetration.concrete.hjc import I_N, power_chords

    q = HJC().as_array()
    c = power_chords(q)
    x = np.concatenate([np.linspace(0, 32, 20001), 2.0 ** np.arange(-8, 6)])
    lb = np.min(c[0][:, None] * x + c[1][:, None], axis=0)
    exact = x ** q[I_N]
    assert np.all(lb <= exact * (1 + 1e-14) + 1e-300)
    assert np.allclose(lb[-14:], exact[-14:], rtol=1e-13)
    assert np.all(lb[x >= 2.0 ** -8] >= 0.9 * exact[x >= 2.0 ** -8])


def _branching_update(s, mu, mu_max, mu_p, D, eps_p, de, rate, q):
    """update_point written with a branch per region of the piecewise laws (Eqs 12-18), in plain Python: the
    oracle of the compiled update, which evaluates every region and selects (see test below)."""
    from penetration.concrete import hjc as H

    q, de = [float(v) for v in q], [float(v) for v in de]

    def crush(m):
        return q[H.I_PC] + (q[H.I_PL] - q[H.I_PC]) * (m - q[H.I_MUC]) / (q[H.I_MUCRUSH] - q[H.I_MUC])

    def dense(m):
        mb = (m - q[H.I_MULOCK]) / (1.0 + q[H.I_MULOCK])
        if mb <= 0.0:
            return q[H.I_K1] * mb
        return q[H.I_K1] * mb + q[H.I_K2] * mb * mb + q[H.I_K3] * mb * mb * mb

    def load(m):
        if m <= q[H.I_MUC]:
            return q[H.I_KE] * m
        return crush(m) if m <= q[H.I_MUCRUSH] else dense(m)

    def k_unload(m):
        F = min(max((m - q[H.I_MUC]) / (q[H.I_MUCRUSH] - q[H.I_MUC]), 0.0), 1.0)
        return (1.0 - F) * q[H.I_KE] + F * q[H.I_K1]

    G = q[H.I_G]
    s = [float(v) for v in s]
    tr = (de[0] + de[1] + de[2]) / 3.0
    for i in range(3):
        s[i] += 2.0 * G * (de[i] - tr)
    for i in range(3, 6):
        s[i] += 2.0 * G * de[i]
    if mu >= mu_max:
        mu_max = mu
        p = load(mu)
    elif mu_max <= q[H.I_MUC]:
        p = q[H.I_KE] * mu
    elif mu_max <= q[H.I_MUCRUSH]:
        p = crush(mu_max) - k_unload(mu_max) * (mu_max - mu)
    else:
        p = dense(mu)
    if mu_max <= q[H.I_MUC]:
        mu_p_new = 0.0
    else:
        m = min(mu_max, q[H.I_MUCRUSH])
        mu_p_new = m - load(m) / k_unload(m)
    p = max(p, -q[H.I_T] * (1.0 - D))
    seq = math.sqrt(3.0 * (0.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) + s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))
    dep = 0.0
    if eps_p >= q[H.I_EROSION]:
        sy = 0.0
    else:
        fc = q[H.I_FC]
        r = rate / q[H.I_EPS0]
        if q[H.I_RATEFLOOR] > 0.5:
            r = max(r, 1.0)
        factor = 1.0 + q[H.I_C] * math.log(r) if (r > 0.0 and r != 1.0) else 1.0
        ps = p / fc
        if ps >= 0.0:
            sv = q[H.I_A] * (1.0 - D) + q[H.I_B] * ps ** q[H.I_N]
        elif q[H.I_TENSION] < 0.5:
            sv = q[H.I_A] * (1.0 + p / q[H.I_T]) * (1.0 - D)
        else:
            sv = q[H.I_A] * max(0.0, 1.0 - D + p / q[H.I_T])
        sy = q[H.I_SCALE] * fc * min(max(sv, 0.0) * factor, q[H.I_SMAX])
    if seq > sy:
        scale = sy / seq if seq > 0.0 else 0.0
        s = [v * scale for v in s]
        dep = (seq - sy) / (3.0 * G)
    dmu_p = max(mu_p_new - mu_p, 0.0)
    if q[H.I_DAMAGE] > 0.5 and dep + dmu_p > 0.0:
        x = (p + q[H.I_T]) / q[H.I_FC]
        ef = q[H.I_EFMIN] if x <= 0.0 else max(q[H.I_EFMIN], q[H.I_D1] * x ** q[H.I_D2])
        D = min(1.0, D + (dep + dmu_p) / ef)
    p = max(p, -q[H.I_T] * (1.0 - D))
    return s, (p, mu_max, mu_p_new, D, dep)


@pytest.mark.parametrize("fields", [{}, {"lock": "extended", "tension": "sphinxsys"},
                                    {"lock": "literal", "D2": 0.7, "rate_floor": False},
                                    {"C": 0.0, "N": 1.3, "damage": False, "erosion_strain": 0.3}])
def test_point_update_equals_a_branching_transcription_bit_for_bit(fields):
    """The compiled update_point (every region evaluated, one selected) against _branching_update on random states
    over the EOS regions, loading and unloading, tension and compression, flow and no flow, damage growth, rates
    below, at and above the reference, and non-finite inputs: the same bits (NaN where the oracle gives NaN)."""
    from penetration.concrete.hjc import update_point

    mat = HJC(**fields)
    q = mat.as_array()
    rng = np.random.default_rng(11)
    n = 3000
    counts = {"flow": 0, "crush": 0, "tension": 0, "unload": 0}
    for k in range(n):
        mu_max = float(rng.choice([0.0, rng.uniform(0, mat.muc), rng.uniform(mat.muc, mat.mul), rng.uniform(mat.mul, 0.3)]))
        mu = float(mu_max + rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-6, -1.5))
        mu_p = float(rng.uniform(0, 0.05))
        D = float(rng.choice([0.0, rng.uniform(0, 1), 1.0]))
        eps_p = float(rng.uniform(0, 0.5))
        rate = float(rng.choice([0.0, 1.0, 10 ** rng.uniform(-3, 5)]))
        s = rng.normal(0, 1, 6) * 10 ** rng.uniform(5, 8.5)
        if k % 3 == 0:
            s[4:] = 0.0
        de = rng.normal(0, 1, 6) * 10 ** rng.uniform(-7, -2.5)
        if k % 101 == 0:
            mu = math.nan
        if k % 103 == 0:
            s[0] = math.inf
        if k % 107 == 0:
            rate = math.nan
        s_ref, ref = _branching_update(s, mu, mu_max, mu_p, D, eps_p, de, rate, q)
        s_new = s.copy()
        got = update_point(s_new, mu, mu_max, mu_p, D, eps_p, de, rate, q)
        want = np.array([*s_ref, *ref])
        have = np.array([*s_new, *got])
        assert np.array_equal(want.view(np.int64), have.view(np.int64)) or np.array_equal(want, have, equal_nan=True), k
        counts["flow"] += ref[4] > 0
        counts["crush"] += ref[2] > mu_p
        counts["tension"] += ref[0] < 0
        counts["unload"] += mu < mu_max
    assert min(counts.values()) > 0.05 * n, counts


@pytest.mark.parametrize("law, beyond", [("mc2010_cap", "cap"), ("mc2010_extrapolate", "extrapolate")])
def test_the_mc2010_rate_law_multiplies_the_rate_free_surface_by_the_codes_factor(law, beyond):
    """strength() with MC2010's law = the rate-free surface times dif_compression_mc2010 (Smax out of reach); the
    rate switch turns either law off."""
    import dataclasses
    from penetration.concrete.hjc import strength
    m = HJC(smax=1e6)
    q_law, q_free = dataclasses.replace(m, rate_law=law).as_array(), dataclasses.replace(m, rate=False).as_array()
    def mc2010(rate):   # fib MC2010 Eq 5.1-49/50 by hand: 0.014 power up to 30 1/s, the cube root above
        rate = min(rate, 300.0) if beyond == "cap" else rate
        return (rate / 30e-6) ** 0.014 if rate <= 30.0 else 0.012 * (rate / 30e-6) ** (1 / 3)
    for p, D in ((50e6, 0.0), (400e6, 0.3), (-1e6, 0.1)):
        for rate in (1e-3, 10.0, 100.0, 1e3, 3e4):
            assert strength(p, D, rate, q_law) == pytest.approx(strength(p, D, rate, q_free) * mc2010(rate), rel=1e-12)
    off = dataclasses.replace(m, rate_law=law, rate=False).as_array()
    assert strength(400e6, 0.0, 3e4, off) == strength(400e6, 0.0, 3e4, q_free)
