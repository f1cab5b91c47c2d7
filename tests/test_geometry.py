"""Profiles: sizes against closed forms, continuity, and parameter errors."""
import math

import numpy as np
import pytest

from penetration.errors import ParameterError
from penetration.nose.geometry import Cone, DoubleOgive, Flat, MinimumNstar, Ogive, TabulatedNose, make_nose
from penetration.nose.nstar import nstar


def test_ogive_length_and_volume():
    a, psi = 0.07, 4.5
    nose = Ogive(psi, a)
    assert nose.length == pytest.approx(a * math.sqrt(4 * psi - 1), rel=1e-14)
    # volume of the tangent ogive (solid of revolution), closed form in terms of S
    S = 2 * psi * a
    b = nose.length
    c = S - a
    vol = math.pi * (b * (S**2 + c**2) - b**3 / 3 - c * (b * math.sqrt(S**2 - b**2) + S**2 * math.asin(b / S)))
    assert nose.volume() == pytest.approx(vol, rel=1e-12)


def test_hemisphere_and_cone_volumes():
    assert Ogive(0.5, 2.0).volume() == pytest.approx(2 / 3 * math.pi * 8, rel=1e-13)
    assert Cone(0.3, 1.1).volume() == pytest.approx(math.pi * 0.09 * 1.1 / 3, rel=1e-13)
    assert Flat(1.0).volume() == 0.0


@pytest.mark.parametrize("nose", [Ogive(3, 0.07), Ogive(0.5, 1.0), Ogive(3, 0.07, 0.01), Cone(1, 2, 0.1),
                                  MinimumNstar(0.07, 0.29),
                                  DoubleOgive(0.07, S1=0.5, S2=0.42, a1=0.03, a2=0.045)])
def test_profile_closes_on_shank(nose):
    assert nose.y(np.array([nose.length]))[0] == pytest.approx(nose.radius, rel=1e-12)
    x = np.linspace(0, nose.length, 2001)
    y = nose.y(x)
    assert np.all(np.diff(y) >= -1e-15)
    assert np.all((nose.angle(x) >= -1e-15) & (nose.angle(x) <= math.pi / 2 + 1e-15))


def test_double_ogive_tangent_joints():
    nose = DoubleOgive(0.07, S1=0.5, S2=0.42, a1=0.03, a2=0.045)
    tip, cone, base = nose.segments
    assert tip.angle(tip.t1) == pytest.approx(cone.angle(0.0), abs=1e-13)
    assert cone.angle(1.0) == pytest.approx(base.angle(base.t0), abs=1e-13)
    for s1, s2 in ((tip, cone), (cone, base)):
        assert np.allclose(s1.point(s1.t1), s2.point(s2.t0), atol=1e-14)
    assert base.angle(base.t1) == pytest.approx(0.0, abs=1e-15)


def test_double_ogive_corner_and_chord_tip():
    nose = DoubleOgive(0.07, S1=0.6, S2=0.42, a1=0.03, a2=0.05, alpha=0.2, tip_length=0.1)
    tip, cone, base = nose.segments
    assert np.allclose(tip.point(tip.t0), (0, 0), atol=1e-14)
    assert np.allclose(tip.point(tip.t1), (0.1, 0.03), atol=1e-14)
    assert cone.angle(0.0) == pytest.approx(0.2)
    assert 0 < nstar(nose) < 1


def test_double_ogive_without_cone_is_two_arcs():
    nose = DoubleOgive(0.07, S1=0.5, S2=0.42, a1=0.05, a2=0.05)
    assert len(nose.segments) == 2


def test_minimum_nstar_beats_ogive_and_cone_of_same_length():
    a = 0.07
    L = Ogive(4.5, a).length
    best = nstar(MinimumNstar(a, L))
    assert best < nstar(Cone(a, L)) < nstar(Ogive(4.5, a))
    assert MinimumNstar(a, L).length == pytest.approx(L, rel=1e-12)


def test_table_polygon_exact_and_smooth_convergence():
    a, b = 0.07, 0.3
    assert nstar(TabulatedNose((0, b), (0, a))) == pytest.approx(nstar(Cone(a, b)), rel=1e-14)
    ogive = Ogive(3, a)
    errs = []
    for n in (41, 81, 161):
        x = np.linspace(0, ogive.length, n)
        errs.append(abs(nstar(TabulatedNose(tuple(x), tuple(ogive.y(x)))) - nstar(ogive)))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(orders > 1.8)


def test_table_with_flat_tip_and_shift():
    nose = TabulatedNose((1.0, 1.0, 2.0), (0.2, 0.2, 1.0))
    assert nose.length == pytest.approx(1.0)
    assert nstar(nose) == pytest.approx(nstar(Cone(1.0, 1.0, 0.2)), rel=1e-13)


@pytest.mark.parametrize("kind,params,field", [
    ("ogive", dict(psi=0.49, radius=0.07), "psi"),
    ("ogive", dict(psi=3, radius=-1), "radius"),
    ("ogive", dict(psi=3, radius=0.07, tip_radius=0.07), "tip_radius"),
    ("cone", dict(radius=0.07, length=0), "length"),
    ("double_ogive", dict(radius=0.07, S1=0.5, S2=0.42, a1=0.05, a2=0.04), "a1"),
    ("double_ogive", dict(radius=0.07, S1=0.5, S2=0.01, a1=0.03, a2=0.04), "S2"),
    ("double_ogive", dict(radius=0.07, S1=0.01, S2=0.42, a1=0.03, a2=0.04), "S1"),
    ("double_ogive", dict(radius=0.07, S1=0.5, S2=0.42, a1=0.03, a2=0.07), "a2"),
    ("minimum_nstar", dict(radius=0.07, length=-0.1), "length"),
    ("ogive", dict(psi="x", radius=0.07), "psi"),
    ("ogive", dict(psi=float("nan"), radius=0.07), "psi"),
])
def test_bad_parameters_name_the_field(kind, params, field):
    with pytest.raises(ParameterError) as err:
        make_nose(kind, **params)
    assert err.value.name == field
    assert field in str(err.value) and "allowed" in str(err.value)


def test_non_monotone_table_names_the_row(tmp_path):
    path = tmp_path / "nose.csv"
    path.write_text("x,y\n0,0\n0.1,0.05\n0.2,0.04\n")
    with pytest.raises(ParameterError, match="y in row 4 = 0.04 "):  # the header is row 1
        make_nose("table", path=str(path))


def test_a_table_nose_answers_radius_and_shape_rate_like_the_nose_it_samples():
    """A table nose's ``y`` is its column of points, so the radius along the nose is radius_at for every nose (the
    FE level's nose pressure and the shape rate called ``y`` and failed on a table nose)."""
    import numpy as np

    from penetration.nose.geometry import Ogive, TabulatedNose
    from penetration.nose.nstar import shape_rate
    ogive = Ogive(3.0, 0.07)
    xs = np.linspace(0.0, ogive.length, 2001)
    table = TabulatedNose(tuple(xs), tuple(ogive.radius_at(xs)))
    x = np.linspace(0.05, 0.8, 7) * ogive.length   # away from the shank, where the slope and its chord error vanish
    np.testing.assert_allclose(table.radius_at(x), ogive.radius_at(x), rtol=1e-6)
    np.testing.assert_allclose(shape_rate(table, x), shape_rate(ogive, x), rtol=1e-2)   # chord slopes: O(h kappa / beta)
