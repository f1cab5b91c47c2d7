"""The limit of a mesh-dependent result as the element size h goes to zero.

Two estimators, both pure (arrays in, a frozen record out):

- `size_regression`: a straight line f(h) = f0 + b h fitted by least squares to results on many meshes,
  f0 with its Student-t interval. It assumes the error is first order in h over the sampled range (the
  order of a one-point quadrilateral with erosion, whose error is dominated by where the front meets the
  element rows) and takes the scatter about the line as noise; the interval then holds the fit's
  uncertainty, not a model error. Extrapolating from meshes of size h_min..h_max to 0 is a reach of
  h_min / (h_max - h_min) times the sampled range: the interval widens with it.
- (grid refinement, Roache 1998) to follow with the erosion-free target.

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
