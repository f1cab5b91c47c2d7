"""The empirical formulas with a size term (analytic.empirical), written in their authors' units, against the SI forms
of the reviews (Kennedy 1976; Li et al. 2005), the size exponents they state and the joins of their branches."""
import numpy as np
import pytest

from penetration.analytic import empirical as emp
from penetration.errors import ParameterError

M, D, FC, V = np.array([0.9, 12.9, 81.1, 450.0]), np.array([0.0269, 0.0762, 0.14, 0.25]), 40e6, 450.0


def test_ndrc_matches_the_reviews_si_form():
    """G = 3.8e-5 N M / (d sqrt(fc)) (V/d)^1.8 in SI (fc in Pa)."""
    si = 3.8e-5 * 1.14 * M / (D * np.sqrt(FC)) * (V / D) ** 1.8
    np.testing.assert_allclose(emp.ndrc_g(M, D, FC, V, 1.14), si, rtol=2e-3)


def test_ace_and_brl_match_the_reviews_si_forms():
    ace = D * (3.5e-4 / np.sqrt(FC) * M / D ** 3 * D ** 0.215 * V ** 1.5 + 0.5)
    brl = D * (1.33e-3 / np.sqrt(FC) * M / D ** 3 * D ** 0.2 * V ** 1.33)
    np.testing.assert_allclose(emp.ace_depth(M, D, FC, V), ace, rtol=1e-3)
    np.testing.assert_allclose(emp.brl_depth(M, D, FC, V), brl, rtol=3e-3)


def test_geometric_similarity_gives_the_stated_size_exponents():
    """Mass as d^3 at one velocity: BRL's x/d as d^0.2, ACE's x/d - 0.5 as d^0.215, NDRC's G as d^0.2."""
    d = np.geomspace(0.01, 0.3, 7)
    m = 8000.0 * d ** 3
    slope = lambda y: np.diff(np.log(y)) / np.diff(np.log(d))
    np.testing.assert_allclose(slope(emp.brl_depth(m, d, FC, V) / d), 0.2, atol=1e-12)
    np.testing.assert_allclose(slope(emp.ace_depth(m, d, FC, V) / d - 0.5), 0.215, atol=1e-12)
    np.testing.assert_allclose(slope(emp.ndrc_g(m, d, FC, V, 1.0)), 0.2, atol=1e-12)


def test_ndrc_branches_meet_at_g_one():
    g = lambda v: float(emp.ndrc_g(12.9, 0.0762, FC, v, 1.0))
    from scipy.optimize import brentq
    v1 = brentq(lambda v: g(v) - 1.0, 10.0, 2000.0, xtol=1e-12)
    lo, hi = emp.ndrc_depth(12.9, 0.0762, FC, [v1 * (1 - 1e-9), v1 * (1 + 1e-9)], 1.0)
    assert hi == pytest.approx(lo, rel=1e-6)


def test_young_factor_is_near_one_at_its_limit_and_matches_the_metric_form():
    """0.4 W^0.15 reaches 0.98 at 400 lb; the metric form quoted as 0.46 m^0.15 (m in kg) to 2.5 %."""
    assert emp.young_mass_factor(400 * emp.LB * (1 - 1e-9)) == pytest.approx(1.0, abs=0.02)
    assert emp.young_mass_factor(400 * emp.LB) == 1.0
    m = np.array([0.9, 12.9, 81.1])
    np.testing.assert_allclose(emp.young_mass_factor(m), 0.46 * m ** 0.15, rtol=0.025)


@pytest.mark.parametrize("call, field", [(lambda: emp.brl_depth(-1.0, 0.1, FC, V), "mass"),
                                         (lambda: emp.ace_depth(1.0, 0.1, 0.0, V), "fc"),
                                         (lambda: emp.ndrc_depth(1.0, 0.1, FC, V, 0.0), "nose_factor"),
                                         (lambda: emp.young_mass_factor(float("nan")), "mass")])
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ParameterError, match=field):
        call()
