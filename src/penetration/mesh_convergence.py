"""The limit of a mesh-dependent result as the element size h goes to zero.

Two estimators, both pure (arrays in, a frozen record out):

- `size_regression`: a straight line f(h) = f0 + b h fitted by least squares to results on many meshes,
  f0 with its Student-t interval. It assumes the error is first order in h over the sampled range (the
  order of a one-point quadrilateral with erosion, whose error is dominated by where the front meets the
  element rows) and takes the scatter about the line as noise; the interval then holds the fit's
  uncertainty, not a model error. Extrapolating from meshes of size h_min..h_max to 0 is a reach of
  h_min / (h_max - h_min) times the sampled range: the interval widens with it.
- `grid_refinement`: Roache's grid convergence index (Roache 1998; the procedure of Celik et al., J. Fluids Eng.
  130, 2008) from results on meshes refined by a constant ratio: the observed order from the three finest, the
  Richardson extrapolation, the GCI of the finest mesh, and, with a fourth mesh, the same from the coarser three
  and the asymptotic-range check GCI_coarse / (r^p GCI_fine) ~ 1. It assumes a smooth, monotone error
  expansion in h (the erosion-free target's), which the checks test.

The mean of results over meshes of nearly one size measures their scatter, not the discretisation error.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SizeRegression:
    """f(h) = f0 + slope h fitted to n meshes of sizes h_min..h_max (m)."""
    n: int
    h_min: float
    h_max: float
    f0: float                # the fit at h = 0
    f0_low: float            # its Student-t interval at `confidence`
    f0_high: float
    f0_stderr: float
    slope: float             # df/dh (per m)
    slope_stderr: float
    slope_p: float           # two-sided p-value of slope = 0
    scatter: float           # standard deviation of the residuals (n - 2 degrees of freedom)
    mean: float              # the plain mean over the meshes (a scatter measure, for comparison)
    confidence: float

    @property
    def reach(self):
        """How far the extrapolation reaches beyond the sampled sizes, in units of their range."""
        return self.h_min / (self.h_max - self.h_min)

    def inside(self, value):
        return bool(self.f0_low <= value <= self.f0_high)


def size_regression(h, f, confidence=0.95):
    """Least-squares line through (h, f) and its value at h = 0 with the Student-t interval at `confidence`.

    Needs at least 3 meshes of at least 2 distinct sizes; h > 0 (m).
    """
    from scipy import stats

    h, f = np.asarray(h, float), np.asarray(f, float)
    if h.shape != f.shape or h.ndim != 1:
        raise ValueError(f"size_regression: h {h.shape} and f {f.shape}; allowed: two 1-D arrays of one length")
    if h.size < 3 or np.unique(h).size < 2:
        raise ValueError(f"size_regression: {h.size} meshes of {np.unique(h).size} sizes; allowed: >= 3 meshes, >= 2 sizes")
    if not (np.all(np.isfinite(h)) and np.all(np.isfinite(f)) and h.min() > 0):
        raise ValueError("size_regression: h and f must be finite and h > 0 (element sizes in m)")
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"size_regression: confidence {confidence}; allowed: 0 < confidence < 1")
    fit = stats.linregress(h, f)
    dof = h.size - 2
    resid = f - (fit.intercept + fit.slope * h)
    scatter = float(np.sqrt(resid @ resid / dof)) if dof > 0 else float("nan")
    t = stats.t.ppf(0.5 + confidence / 2, dof)
    se0 = float(fit.intercept_stderr)
    return SizeRegression(n=int(h.size), h_min=float(h.min()), h_max=float(h.max()), f0=float(fit.intercept),
                          f0_low=float(fit.intercept - t * se0), f0_high=float(fit.intercept + t * se0), f0_stderr=se0,
                          slope=float(fit.slope), slope_stderr=float(fit.stderr), slope_p=float(fit.pvalue),
                          scatter=scatter, mean=float(f.mean()), confidence=float(confidence))


# grid_refinement's verdicts, for people
MONOTONE, OSCILLATORY, NOT_ASYMPTOTIC, CONVERGED = "asymptotic", "oscillatory", "not asymptotic", "converged"
ORDER_RANGE = (0.5, 4.0)      # an observed order outside it is not taken as asymptotic
ASYMPTOTIC_TOLERANCE = 0.15   # |GCI_coarse / (r^p GCI_fine) - 1| within it: in the asymptotic range


@dataclass(frozen=True)
class GridRefinement:
    """Roache's grid refinement of results f on meshes refined by ``ratio`` (coarse first)."""
    values: tuple            # f on each mesh, coarse first
    ratio: float
    order: float             # observed order p from the three finest meshes (nan when it cannot be had)
    extrapolated: float      # Richardson: f_fine + (f_fine - f_medium) / (r^p - 1)
    gci_fine: float          # Fs |f_fine - f_medium| / (r^p - 1), absolute (the unit of f)
    gci_fine_relative: float  # the same over |f_fine|
    order_coarse: float      # p from the coarsest three (four or more meshes; else nan)
    asymptotic_ratio: float  # GCI_coarse / (r^p GCI_fine) of the two triples (~1 in the asymptotic range)
    status: str              # CONVERGED, MONOTONE, OSCILLATORY or NOT_ASYMPTOTIC
    safety: float


def _triple(f3, f2, f1, r):
    """Observed order, extrapolation and absolute fine GCI (safety 1) of coarse f3, medium f2, fine f1."""
    e32, e21 = f3 - f2, f2 - f1
    if e21 == 0.0 or e32 == 0.0:
        return float("nan"), f1, 0.0, e32 * e21 >= 0
    q = e32 / e21
    p = float(np.log(abs(q)) / np.log(r))
    gain = r ** p - 1.0
    return p, f1 + (f1 - f2) / gain if gain != 0 else float("nan"), abs(f1 - f2) / gain if gain > 0 else float("inf"), q > 0


def grid_refinement(f, ratio, safety=1.25):
    """Observed order, Richardson extrapolation and grid convergence index of results ``f`` on >= 3 meshes refined by
    a constant ``ratio`` > 1 (coarse first). Status: CONVERGED when the two finest agree exactly; OSCILLATORY when
    the differences change sign; MONOTONE when the order is within ORDER_RANGE and, with four or more meshes, the
    two triples agree (|asymptotic ratio - 1| <= ASYMPTOTIC_TOLERANCE); NOT_ASYMPTOTIC otherwise (more meshes are
    needed)."""
    f = np.asarray(f, float)
    if f.ndim != 1 or f.size < 3 or not np.all(np.isfinite(f)):
        raise ValueError(f"grid_refinement: {f.size} results; allowed: >= 3 finite values on meshes refined by a constant ratio")
    if not (np.isfinite(ratio) and ratio > 1.0):
        raise ValueError(f"grid_refinement: ratio {ratio}; allowed: > 1 (the constant refinement ratio)")
    p, ext, gci, monotone = _triple(f[-3], f[-2], f[-1], ratio)
    gci *= safety
    order_c, asym = float("nan"), float("nan")
    if f.size >= 4:
        order_c, _, gci_c, _ = _triple(f[-4], f[-3], f[-2], ratio)
        gci_c *= safety
        if gci > 0 and np.isfinite(p):
            asym = float(gci_c / (ratio ** p * gci))
    if f[-1] == f[-2]:
        status = CONVERGED
    elif not monotone:
        status = OSCILLATORY
    elif ORDER_RANGE[0] <= p <= ORDER_RANGE[1] and (f.size < 4 or abs(asym - 1.0) <= ASYMPTOTIC_TOLERANCE):
        status = MONOTONE
    else:
        status = NOT_ASYMPTOTIC
    rel = gci / abs(f[-1]) if f[-1] != 0 else float("inf")
    return GridRefinement(values=tuple(float(x) for x in f), ratio=float(ratio), order=p, extrapolated=float(ext),
                          gci_fine=float(gci), gci_fine_relative=float(rel), order_coarse=order_c,
                          asymptotic_ratio=asym, status=status, safety=float(safety))
