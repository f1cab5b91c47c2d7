"""N* against closed forms (analytic oracles), to 1e-10 relative."""
import math

import numpy as np
import pytest

from penetration.nose.geometry import NOSES, Cone, DoubleOgive, Flat, MinimumNstar, Ogive
from penetration.nose.nstar import cumulative_nstar, nstar, nstar_parts, shape_rate

RTOL = 1e-10


def ogive_closed(psi):
    return (8 * psi - 1) / (24 * psi**2)


def blunt_ogive_closed(psi, a, rf):
    """Eq 5 integrated by hand over the arc y = S sin(phi) - (S - a), plus the flat."""
    S = 2 * psi * a
    s0 = (rf + S - a) / S
    c0 = math.sqrt(1 - s0**2)
    arc = S * c0**4 / 4 - (S - a) * ((1 - s0) - (1 - s0**3) / 3)
    return (rf / a) ** 2 + 2 * S / a**2 * arc


@pytest.mark.parametrize("psi", [0.5, 0.5000001, 0.75, 1, 2, 3, 4.5, 5, 10, 37.3, 100, 1e4])
def test_ogive(psi):
    assert nstar(Ogive(psi, 0.07)) == pytest.approx(ogive_closed(psi), rel=RTOL)


def test_hemisphere_is_half():
    assert nstar(Ogive(0.5, 1.3)) == pytest.approx(0.5, rel=RTOL)


@pytest.mark.parametrize("psi,frac", [(0.5, 0.3), (3, 1e-9), (3, 0.2), (4.5, 0.5), (10, 0.999), (2, 1e-3)])
def test_blunted_ogive(psi, frac):
    a = 0.05
    assert nstar(Ogive(psi, a, frac * a)) == pytest.approx(blunt_ogive_closed(psi, a, frac * a), rel=RTOL)


def test_blunt_closed_form_reduces_to_sharp():
    """The hand-derived oracle agrees with the textbook one (checks the oracle)."""
    for psi in (0.5, 1, 3, 7):
        assert blunt_ogive_closed(psi, 1.0, 0.0) == pytest.approx(ogive_closed(psi), rel=1e-12)


@pytest.mark.parametrize("ratio", [1e-3, 0.1, 1, 4.123, 30, 1e3])
def test_cone(ratio):
    a = 0.07
    assert nstar(Cone(a, ratio * a)) == pytest.approx(1 / (1 + ratio**2), rel=RTOL)


@pytest.mark.parametrize("rf", [1e-6, 0.2, 0.9])
def test_truncated_cone(rf):
    a, b = 1.0, 3.0
    sin2 = (a - rf) ** 2 / ((a - rf) ** 2 + b**2)
    expected = rf**2 + sin2 * (1 - rf**2)
    assert nstar(Cone(a, b, rf)) == pytest.approx(expected, rel=RTOL)


def test_flat_is_one():
    assert nstar(Flat(0.2)) == pytest.approx(1.0, rel=RTOL)


def test_parts_sum_and_cumulative_end():
    nose = Ogive(3, 0.07, 0.01)
    _, _, cum = cumulative_nstar(nose, 50)
    assert sum(nstar_parts(nose)) == pytest.approx(nstar(nose), rel=1e-14)
    assert cum[-1] == pytest.approx(nstar(nose), rel=1e-12)


def test_shape_rate_integrates_to_nstar():
    """k = dN*/dx integrated by an independent rule (Simpson on a fine grid)."""
    from scipy.integrate import simpson
    nose = Ogive(3, 0.07)
    x = np.linspace(0, nose.length, 20001)
    assert simpson(shape_rate(nose, x), x=x) == pytest.approx(nstar(nose), rel=1e-8)


def test_shape_rate_peak_of_crh3():
    """The paper's Fig 3b: k of CRH 3 peaks at x/b = 0.208."""
    nose = Ogive(3, 1.0)
    x = np.linspace(0, nose.length, 100001)
    assert x[np.argmax(shape_rate(nose, x))] / nose.length == pytest.approx(0.208, abs=5e-4)


EXAMPLES = {
    "ogive": lambda tmp: Ogive(3, 0.07, 0.005),
    "cone": lambda tmp: Cone(0.07, 0.3, 0.01),
    "flat": lambda tmp: Flat(0.07),
    "double_ogive": lambda tmp: DoubleOgive(0.07, S1=0.5, S2=0.42, a1=0.03, a2=0.045),
    "minimum_nstar": lambda tmp: MinimumNstar(0.07, 0.3),
    "table": lambda tmp: _table(tmp),
}


def _table(tmp):
    path = tmp / "nose.csv"
    path.write_text("x,y\n0,0.01\n0.1,0.04\n0.3,0.07\n")
    return NOSES["table"].from_keywords(path=str(path))


def test_examples_cover_the_registry():
    assert set(EXAMPLES) == set(NOSES)


@pytest.mark.parametrize("kind", sorted(NOSES))
def test_registered_kind_basic_properties(kind, tmp_path):
    """Every registered nose: 0 < N* <= 1, parts add up, cumulative N* rises to N*, closes on the shank."""
    nose = EXAMPLES[kind](tmp_path)
    n = nstar(nose)
    assert 0 < n <= 1
    _, y, cum = cumulative_nstar(nose, 30)
    assert np.all(np.diff(cum) >= -1e-15) and cum[-1] == pytest.approx(n, rel=1e-12)
    assert y[-1] == pytest.approx(nose.radius, rel=1e-12)


@pytest.mark.parametrize("nose", [DoubleOgive(0.07, S1=0.8576, S2=0.42, a1=0.0397, a2=0.0638, alpha=0.245),
                                  MinimumNstar(0.07, 0.2886)])
def test_eq5_in_x_by_adaptive_quadrature(nose):
    """Independent oracle: Eq 5 as written (integral over x of y y'^3/(1+y'^2)), by scipy quad
    with y' from finite differences of y(x), plus the flat tip's (r0/a)^2."""
    from scipy.integrate import quad
    h = 1e-7 * nose.length

    def integrand(x):
        xs = np.array([x - h, x + h]).clip(0, nose.length)
        yp = np.diff(nose.y(xs))[0] / (xs[1] - xs[0])
        return float(nose.y(np.array([x]))[0]) * yp**3 / (1 + yp**2)

    joints = [s.point(s.t0)[0] for s in nose.segments[1:]]
    val = quad(integrand, 0, nose.length, points=joints, limit=400, epsabs=1e-13, epsrel=1e-11)[0]
    flat = nose.segments[0].y1 ** 2 if nose.kind == "minimum_nstar" else 0.0
    expected = 2 / nose.radius**2 * val + flat / nose.radius**2
    assert nstar(nose) == pytest.approx(expected, rel=2e-6)
