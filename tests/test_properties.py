"""Property-based tests over random valid ogives and double ogives."""
import math

import numpy as np
from hypothesis import assume, given, settings, strategies as st

from penetration.errors import ParameterError
from penetration.nose.geometry import DoubleOgive, MinimumNstar, Ogive
from penetration.nose.nstar import cumulative_nstar, nstar

psi = st.floats(0.5, 200.0)
scale = st.floats(1e-3, 1e3)


@st.composite
def double_ogives(draw, radius=1.0):
    a2 = draw(st.floats(0.05, 0.98)) * radius
    a1 = draw(st.floats(0.05, 1.0)) * a2
    S2 = (radius - a2) * draw(st.floats(1.05, 50.0))
    try:
        alpha = DoubleOgive(radius, S1=1e9, S2=S2, a1=a1, a2=a2).cone_angle
    except ParameterError:
        assume(False)
    S1 = a1 / math.cos(alpha) * draw(st.floats(1.0 + 1e-9, 100.0))
    try:
        return DoubleOgive(radius, S1=S1, S2=S2, a1=a1, a2=a2)
    except ParameterError:
        assume(False)


@settings(max_examples=150, deadline=None)
@given(psi, st.floats(0.0, 0.95))
def test_ogive_bounds_and_monotone(p, tip):
    nose = Ogive(p, 1.0, tip)
    n = nstar(nose)
    assert 0 < n <= 1
    _, _, cum = cumulative_nstar(nose, 40)
    assert np.all(np.diff(cum) >= -1e-15)


@settings(max_examples=150, deadline=None)
@given(double_ogives())
def test_double_ogive_bounds_monotone_and_optimality(nose):
    n = nstar(nose)
    assert 0 < n <= 1
    _, _, cum = cumulative_nstar(nose, 40)
    assert np.all(np.diff(cum) >= -1e-15)
    # Newton's body is the least N* of all noses of that length and radius
    assert nstar(MinimumNstar(nose.radius, nose.length)) <= n * (1 + 1e-12)


@settings(max_examples=80, deadline=None)
@given(psi, scale)
def test_ogive_scale_independent(p, s):
    assert math.isclose(nstar(Ogive(p, s)), nstar(Ogive(p, 1.0)), rel_tol=1e-12)


@settings(max_examples=60, deadline=None)
@given(double_ogives(), scale)
def test_double_ogive_scale_independent(nose, s):
    scaled = DoubleOgive(nose.radius * s, S1=nose.S1 * s, S2=nose.S2 * s, a1=nose.a1 * s, a2=nose.a2 * s)
    assert math.isclose(nstar(scaled), nstar(nose), rel_tol=1e-11)
    assert math.isclose(scaled.volume(), nose.volume() * s**3, rel_tol=1e-11)
