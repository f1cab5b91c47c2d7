"""The limit at zero element size (penetration.studies.mesh_convergence) against exact lines and its own coverage."""
import numpy as np
import pandas as pd
import pytest

from penetration.studies import mesh_convergence as mc
from penetration.studies.fe_results import extrapolation_rows
from penetration.studies.mesh_convergence import size_regression


def test_an_exact_line_is_extrapolated_exactly_with_no_interval():
    h = np.linspace(5.5e-3, 9.7e-3, 21)
    fit = size_regression(h, 1.05 + 12.0 * h)
    assert fit.f0 == pytest.approx(1.05, abs=1e-12) and fit.slope == pytest.approx(12.0, rel=1e-10)
    assert fit.f0_high - fit.f0_low < 1e-8 and fit.scatter < 1e-10
    assert fit.reach == pytest.approx(5.5 / 4.2)


def test_the_interval_covers_the_true_limit_at_its_confidence():
    """Monte Carlo over noisy lines like the band meshes (21 sizes, 3 points of scatter): the 95 % interval holds
    the true value at h = 0 in 95 +- 2 % of 2000 draws, and the plain mean over the meshes is biased by the slope."""
    rng = np.random.default_rng(7)
    h = np.linspace(5.5e-3, 9.7e-3, 21)
    hits, means = 0, []
    for _ in range(2000):
        fit = size_regression(h, 1.0 + 15.0 * h + rng.normal(0, 0.03, h.size))
        hits += fit.inside(1.0)
        means.append(fit.mean)
    assert 0.93 <= hits / 2000 <= 0.97
    assert np.mean(means) == pytest.approx(1.0 + 15.0 * h.mean(), abs=2e-3)  # the mean is not the limit


@pytest.mark.parametrize("h, f, field", [([1e-3, 2e-3], [1, 1], ">= 3 meshes"), ([1e-3] * 3, [1, 2, 3], ">= 2 sizes"),
                                         ([0, 1e-3, 2e-3], [1, 1, 1], "h > 0"), ([1e-3, 2e-3, np.nan], [1, 1, 1], "finite")])
def test_bad_samples_are_refused(h, f, field):
    with pytest.raises(ValueError, match=field):
        size_regression(h, f)


def test_rows_flag_a_single_mesh_series_that_is_not_monotone():
    h = np.linspace(5e-3, 9e-3, 9)
    meshes = pd.DataFrame({"contrast": "A/B", "velocity_ms": 500, "element_size_m": h, "fe_ratio": 1 + 10 * h,
                           "paper_sim_ratio": 1.04})
    singles = pd.DataFrame({"contrast": "A/B", "velocity_ms": 500, "elements_across_radius": [3, 8, 10, 12],
                            "fe_ratio": [0.96, 1.16, 1.02, 1.03]})
    row = extrapolation_rows(meshes, singles, 0.95).iloc[0]
    assert row.ratio_at_zero_size == pytest.approx(1.0) and not row.single_meshes_monotone
    assert row.zero_size_minus_paper_points == pytest.approx(-4.0) and not row.paper_inside_interval
    singles["fe_ratio"] = [0.96, 1.0, 1.02, 1.03]
    assert extrapolation_rows(meshes, singles, 0.95).iloc[0].single_meshes_monotone


# ------------------------------------------------------------------ grid refinement (Roache's GCI)
from penetration.studies.mesh_convergence import CONVERGED, MONOTONE, NOT_ASYMPTOTIC, OSCILLATORY, grid_refinement


@pytest.mark.parametrize("p, r", [(1.0, 1.25), (2.0, 1.25), (1.5, 2.0)])
def test_grid_refinement_recovers_the_order_and_the_limit_of_an_exact_power_law(p, r):
    """f(h) = f0 + c h^p on four meshes refined by r: the observed order is p, the Richardson extrapolation is f0, the
    two triples agree (asymptotic ratio 1) and the fine GCI is Fs |f1 - f0| (the error it bounds, times 1.25)."""
    h = 0.01 / r ** np.arange(4)
    f0, c = 3.2, 40.0
    f = f0 + c * h ** p
    g = grid_refinement(f, r)
    assert g.order == pytest.approx(p, rel=1e-9) and g.order_coarse == pytest.approx(p, rel=1e-9)
    assert g.extrapolated == pytest.approx(f0, rel=1e-12)
    assert g.asymptotic_ratio == pytest.approx(1.0, rel=1e-9) and g.status == MONOTONE
    assert g.gci_fine == pytest.approx(1.25 * abs(f[-1] - f0), rel=1e-9)
    assert g.gci_fine_relative == pytest.approx(g.gci_fine / f[-1])


def test_grid_refinement_says_when_it_is_not_in_the_asymptotic_range():
    r = 1.25
    h = 0.01 / r ** np.arange(4)
    # two error terms of opposite sign: the triples' orders differ
    f = 3.0 + 50 * h - 1000 * h ** 2
    g = grid_refinement(f, r)

    def triple(a, b, c):    # Roache by hand: observed order and fine GCI (Fs 1.25) of coarse a, medium b, fine c
        p = np.log((a - b) / (b - c)) / np.log(r)
        return p, 1.25 * abs(c - b) / (r**p - 1)
    (p_fine, gci_fine), (p_coarse, gci_coarse) = triple(*f[1:]), triple(*f[:3])
    assert g.order == pytest.approx(p_fine, rel=1e-12) and g.order_coarse == pytest.approx(p_coarse, rel=1e-12)
    assert g.asymptotic_ratio == pytest.approx(gci_coarse / (r**p_fine * gci_fine), rel=1e-12)
    assert abs(g.asymptotic_ratio - 1) > 0.2 and g.status == NOT_ASYMPTOTIC
    assert grid_refinement(3.0 + 50 * h + 2000 * h ** 2, r).status == MONOTONE   # the same, its terms of one sign
    assert grid_refinement([3.0, 3.1, 3.05, 3.08], r).status == OSCILLATORY
    assert grid_refinement([3.0, 3.1, 3.2, 3.2], r).status == CONVERGED
    assert grid_refinement([3.0, 3.01, 3.03, 3.06], r).status == NOT_ASYMPTOTIC   # diverging (order < 0)
    with pytest.raises(ValueError, match="ratio"):
        grid_refinement([1.0, 2.0, 3.0], 1.0)
    with pytest.raises(ValueError, match=">= 3"):
        grid_refinement([1.0, 2.0], 1.25)


@pytest.mark.parametrize("p, n", [(1.0, (8.192, 10.24, 12.8, 16.0)), (2.0, (8.192, 10.24, 12.8, 16.0)),
                                  (1.6, (4.0, 6.0, 9.0, 13.5, 20.25)), (0.8, (3.0, 5.0, 6.0, 11.0))])
def test_least_squares_recovers_an_exact_power_law_and_reduces_to_the_gci(p, n):
    """On an exact law f = 3 - c h^p (any ratios) the free fit finds p and f0, its standard deviation vanishes
    and U is 1.25 times the finest mesh's error (the GCI of a well-behaved set, as the procedure says)."""
    h = 0.07 / np.asarray(n)
    c = 0.1 / (0.07 / 8) ** p   # a 10 % error at 8 across
    r = mc.least_squares_uncertainty(h, 3.0 - c * h ** p)
    assert r.fit == mc.FREE
    assert r.order == pytest.approx(p, rel=1e-6) and r.exact == pytest.approx(3.0, rel=1e-9)
    assert r.std < 1e-6 * r.error and r.safety == 1.25
    assert r.error == pytest.approx(c * h.min() ** p, rel=1e-6)
    assert r.uncertainty == pytest.approx(1.25 * c * h.min() ** p, rel=1e-6) and r.inside(3.0)


def test_least_squares_takes_fixed_orders_below_half_and_its_uncertainty_holds_the_limit():
    h = 0.07 / np.array([8.192, 10.24, 12.8, 16.0])
    r = mc.least_squares_uncertainty(h, 2.0 + 0.4 * (h / h.max()) ** 0.3)
    assert r.order == pytest.approx(0.3, rel=1e-6) and r.fit in (mc.FIRST, mc.SECOND, mc.FIRST_SECOND)
    assert r.safety == 3.0 and r.inside(2.0) and not mc.least_squares_uncertainty(h, 2.0 + 0.1 * h / h.max()).inside(2.2)


def test_least_squares_uncertainty_covers_the_limit_of_noisy_results():
    """Results with a second-order error and a noise of 30 and 100 % of the finest mesh's error: U holds the limit in
    at least 93 % of 150 draws each, and grows with the noise (the scatter penalty where s >= D)."""
    h = 0.07 / np.array([8.192, 10.24, 12.8, 16.0])
    rng = np.random.default_rng(7)
    err = 0.05 * (h / h.max()) ** 2
    median = {}
    for noise in (0.3, 1.0):
        hits, us = 0, []
        for _ in range(150):
            r = mc.least_squares_uncertainty(h, 1.0 + err + noise * err.min() * rng.normal(size=h.size))
            hits += r.inside(1.0)
            us.append(r.uncertainty)
        assert hits / 150 >= 0.93, (noise, hits)
        median[noise] = np.median(us)
    assert median[1.0] > 2 * median[0.3]


def test_least_squares_refuses_too_few_or_repeated_meshes_and_gives_zero_on_constant_results():
    with pytest.raises(ValueError, match=">= 4 finite results"):
        mc.least_squares_uncertainty([0.01, 0.008, 0.0064], [1.0, 1.1, 1.2])
    with pytest.raises(ValueError, match=">= 4 finite results"):
        mc.least_squares_uncertainty([0.01, 0.008, 0.0064, 0.005], [1.0, np.nan, 1.2, 1.3])
    with pytest.raises(ValueError, match="distinct sizes"):
        mc.least_squares_uncertainty([0.01, 0.008, 0.008, 0.005], [1.0, 1.1, 1.2, 1.3])
    r = mc.least_squares_uncertainty([0.01, 0.008, 0.0064, 0.005], [2.0] * 4)
    assert r.uncertainty == 0.0 and r.value == 2.0 and r.fit == mc.CONSTANT


def test_least_squares_distrusts_an_order_above_two_and_penalises_scatter_as_large_as_the_trend():
    h = 0.07 / np.array([8.192, 10.24, 12.8, 16.0])
    # an exact third-order law: the free order (3) gives way to the fixed orders 2 and 1 + 2, Fs = 3, U holds the limit
    r = mc.least_squares_uncertainty(h, 1.0 + 0.05 * (h / h.max()) ** 3)
    assert r.order == pytest.approx(3.0, rel=1e-6) and r.fit in (mc.SECOND, mc.FIRST_SECOND)
    assert r.safety == 3.0 and r.inside(1.0)
    # results alternating about 1 (no trend): s >= D, U = 3 s / D (error + s + miss); the fit (a h^2, weighted 1/h)
    # recomputed with numpy's polyfit in x = h^2
    f = np.array([1.0, 1.02, 0.99, 1.01])
    r = mc.least_squares_uncertainty(h, f)
    assert r.fit == mc.SECOND and r.std >= r.data_range == pytest.approx(0.01, rel=1e-12)
    w = (1 / h) / np.sum(1 / h)
    b, a = np.polyfit(h ** 2, f, 1, w=np.sqrt(w))
    fit = a + b * h ** 2
    assert r.weighted and r.exact == pytest.approx(a, rel=1e-10)
    assert r.std == pytest.approx(np.sqrt(4 * np.sum(w * (f - fit) ** 2) / 2), rel=1e-8)
    miss = abs(f[-1] - fit[-1])
    assert r.uncertainty == pytest.approx(3 * r.std / r.data_range * (abs(b) * h[-1] ** 2 + r.std + miss), rel=1e-8)
    c = mc.least_squares_uncertainty(h, [2.0] * 4)
    assert c.fit == mc.CONSTANT and c.uncertainty == 0.0
    # the alternating results have no order: the free fit ends at a bound of its scan, which found_order withholds
    assert r.order == pytest.approx(mc.LS_ORDER_SCAN[1], rel=1e-6) and np.isnan(r.found_order)
    assert mc.least_squares_uncertainty(h, 1.0 + 0.05 * (h / h.max()) ** 3).found_order == pytest.approx(3.0, rel=1e-6)
