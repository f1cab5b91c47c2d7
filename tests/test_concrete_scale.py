"""The published rate and size relations of concrete (concrete.scale) against the properties their codes state:
branches that meet at their knees, the two codes' agreement where their exponents coincide, the limits of Bazant's
law, the tables of strength class C40/50."""
import numpy as np
import pytest

from penetration.concrete import scale
from penetration.errors import ParameterError
from penetration.units import MPA

FCM = np.array([20.0, 35.0, 48.0, 70.0, 110.0]) * MPA


def test_ceb1990_compression_branches_meet_exactly():
    """1.026 and 6.156 are chosen so that the two branches meet at 30 1/s, for every strength."""
    for fcm in FCM:
        below = scale.dif_compression_ceb1990(30.0, fcm)
        above = scale.dif_compression_ceb1990(30.0 * (1 + 1e-12), fcm)
        assert above == pytest.approx(below, rel=1e-9)


def test_ceb1990_tension_and_mc2010_branches_meet_within_their_rounding():
    for fcm in FCM:
        lo, hi = scale.dif_tension_ceb1990([30.0, 30.0 * (1 + 1e-12)], fcm)
        assert hi == pytest.approx(lo, rel=0.01)
    lo, hi = scale.dif_compression_mc2010([30.0, 30.0 * (1 + 1e-12)])
    assert hi == pytest.approx(lo, rel=0.015)
    lo, hi = scale.dif_tension_mc2010([10.0, 10.0 * (1 + 1e-12)])
    assert hi == pytest.approx(lo, rel=0.002)


def test_the_two_codes_agree_where_their_compression_exponents_coincide():
    """MC2010 fixed the exponent 0.014 of MC90's 1.026 alpha_s: at the strength where they are equal
    (alpha_s = 0.014 / 1.026) the two codes give the same factor on both branches."""
    alpha = 0.014 / 1.026
    fcm = (1.0 / alpha - 5.0) / 9.0 * scale.FCM0
    rates = np.geomspace(1e-3, 300.0, 40)
    np.testing.assert_allclose(scale.dif_compression_ceb1990(rates, fcm), scale.dif_compression_mc2010(rates),
                               rtol=0.015)


def test_beyond_the_codes_range_cap_holds_and_extrapolate_grows_as_the_cube_root():
    rates = np.array([100.0, 300.0, 1e3, 1e4, 1e5])
    cap = scale.dif_compression_mc2010(rates, beyond="cap")
    ext = scale.dif_compression_mc2010(rates, beyond="extrapolate")
    np.testing.assert_allclose(cap[:2], ext[:2])
    assert np.all(cap[2:] == cap[1])
    np.testing.assert_allclose(scale.size_exponent(ext[1:], rates[1:]), 1.0 / 3.0)
    assert np.all(np.diff(scale.dif_tension_mc2010(rates, beyond="extrapolate")) > 0)


def test_tensile_strength_branches_meet_at_c50():
    """MC2010's two relations for f_ctm meet at fck = 50 MPa to within 0.3 %."""
    lo = scale.tensile_strength_mc2010(58.0 * MPA)
    hi = scale.tensile_strength_mc2010(58.0 * MPA * (1 + 1e-9))
    assert hi == pytest.approx(lo, rel=0.003)
    assert lo == pytest.approx(0.3 * 50.0 ** (2 / 3) * MPA, rel=1e-6)


def test_class_c40_matches_the_codes_tables():
    """C40/50 (fcm 48 MPa) in the codes' tables: f_ctm 3.5 MPa (EC2 Table 3.1, MC2010), E_ci 36.3 GPa (MC2010)."""
    assert scale.tensile_strength_mc2010(48.0 * MPA) / MPA == pytest.approx(3.5, abs=0.02)
    assert scale.elastic_modulus_mc2010(48.0 * MPA) / 1e9 == pytest.approx(36.3, abs=0.05)


def test_higher_strength_concrete_is_more_brittle():
    """Hillerborg's length l_ch = E G_F / f_t^2 falls as the strength rises (f_t grows faster than E G_F)."""
    fcm = np.array([30.0, 40.0, 48.0, 58.0, 80.0]) * MPA
    lch = scale.characteristic_length(scale.elastic_modulus_mc2010(fcm), scale.fracture_energy_mc2010(fcm),
                                      scale.tensile_strength_mc2010(fcm))
    assert np.all(np.diff(lch) < 0)


def test_size_effect_law_limits():
    """Strength criterion for small sizes, LEFM's D^(-1/2) for large ones, 1/sqrt(2) at D = D0."""
    D = np.geomspace(1e-6, 1e6, 13)
    f = scale.size_effect_factor(D, 1.0)
    assert f[0] == pytest.approx(1.0, abs=1e-6)
    assert scale.size_exponent(f[-2:], D[-2:])[0] == pytest.approx(-0.5, abs=1e-5)
    assert scale.size_effect_factor(2.0, 2.0) == pytest.approx(2 ** -0.5)
    assert np.all(np.diff(f) < 0)


@pytest.mark.parametrize("call, field", [
    (lambda: scale.dif_compression_mc2010(1e3, beyond="clip"), "beyond"),
    (lambda: scale.dif_tension_mc2010(-1.0), "rate"),
    (lambda: scale.dif_compression_ceb1990(1.0, -5.0), "fcm"),
    (lambda: scale.tensile_strength_mc2010(5e6), "fcm"),
    (lambda: scale.elastic_modulus_mc2010(4e7, aggregate="granite"), "aggregate"),
    (lambda: scale.size_effect_factor(0.1, 0.0), "transitional_size")])
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ParameterError, match=field):
        call()
