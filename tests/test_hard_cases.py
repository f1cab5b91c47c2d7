"""Degenerate and extreme noses stay finite and continuous, or fail clearly."""
import math

import numpy as np
import pytest

from penetration.errors import ParameterError
from penetration.nose.geometry import Cone, DoubleOgive, MinimumNstar, Ogive
from penetration.nose.nstar import cumulative_nstar, nstar


def finite(nose):
    n = nstar(nose)
    x, y, cum = cumulative_nstar(nose, 30)
    return math.isfinite(n) and np.all(np.isfinite(x)) and np.all(np.isfinite(cum)) and 0 < n <= 1


def test_psi_exactly_half_and_just_above_are_continuous():
    assert finite(Ogive(0.5, 1.0))
    assert nstar(Ogive(0.5 + 1e-12, 1.0)) == pytest.approx(nstar(Ogive(0.5, 1.0)), abs=1e-10)


def test_psi_huge():
    nose = Ogive(1e6, 1.0)
    assert finite(nose)
    assert nstar(nose) == pytest.approx((8e6 - 1) / (24e12), rel=1e-9)


@pytest.mark.parametrize("frac", [1e-14, 1e-8, 1 - 1e-9])
def test_tiny_and_huge_flat_tips(frac):
    nose = Ogive(3, 0.07, frac * 0.07)
    assert finite(nose)
    if frac < 1e-6:
        assert nstar(nose) == pytest.approx(nstar(Ogive(3, 0.07)), rel=1e-9)
    else:
        assert nstar(nose) == pytest.approx(1.0, rel=1e-6)


def test_nearly_flat_cone_tip():
    assert nstar(Cone(1.0, 1.0, 1 - 1e-12)) == pytest.approx(1.0, rel=1e-9)


def test_near_degenerate_double_ogives():
    # cone of vanishing length
    a = DoubleOgive(1.0, S1=5.0, S2=6.0, a1=0.5, a2=0.5 + 1e-12)
    b = DoubleOgive(1.0, S1=5.0, S2=6.0, a1=0.5, a2=0.5)
    assert finite(a) and nstar(a) == pytest.approx(nstar(b), rel=1e-9)
    # tip ogive radius at its lower bound (normal at the tip along the axis)
    lo = 0.5 / math.cos(DoubleOgive(1.0, S1=1e9, S2=6.0, a1=0.5, a2=0.6).cone_angle)
    c = DoubleOgive(1.0, S1=lo, S2=6.0, a1=0.5, a2=0.6)
    assert finite(c)
    # base ogive just able to reach the shank (S2 = a - a2): its tangent at D is
    # normal to the axis, so only a cone with its own angle can meet it
    d = DoubleOgive(1.0, S1=5.0, S2=0.4, a1=0.5, a2=0.6, alpha=0.3)
    assert finite(d)
    with pytest.raises(ParameterError, match="S1"):
        DoubleOgive(1.0, S1=5.0, S2=0.4, a1=0.5, a2=0.6)
    with pytest.raises(ParameterError, match="S1"):
        DoubleOgive(1.0, S1=lo * (1 - 1e-9), S2=6.0, a1=0.5, a2=0.6)


@pytest.mark.parametrize("fineness", [1e-3, 0.05, 1.0, 4.123, 50.0, 1e3])
def test_minimum_nstar_extreme_fineness(fineness):
    nose = MinimumNstar(1.0, fineness)
    assert finite(nose)
    assert nose.length == pytest.approx(fineness, rel=1e-10)
    assert nstar(nose) <= nstar(Cone(1.0, fineness)) * (1 + 1e-12)
