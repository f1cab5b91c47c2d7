"""The statistics of the studies, each written once: Student-t quantiles and intervals, Welch's interval of a
difference of means, least-squares slopes with their intervals, Richardson's extrapolation of three meshes (the
core of Roache's GCI, ``mesh_convergence.grid_refinement``, and of the FE verification's convergence rows) and the
exponent of a power law. Pure: numbers or arrays in, numbers out."""
from __future__ import annotations

import math
import statistics

import numpy as np


def t_quantile(confidence, dof):
    """The two-sided Student-t quantile at ``confidence`` on ``dof`` degrees of freedom."""
    from scipy import stats
    return stats.t.ppf(0.5 + confidence / 2, dof)


def t_interval(x, confidence):
    """Student-t interval of the mean of the sample x at a two-sided confidence level (the interval does not depend
    on the test's popmean; scipy's round-off does, and 1 is the one the committed intervals were made with)."""
    from scipy import stats
    lo, hi = stats.ttest_1samp(x, 1.0).confidence_interval(confidence)
    return float(lo), float(hi)


def welch(x, y, confidence):
    """mean(y) - mean(x) and its Welch interval at the two-sided confidence."""
    from scipy import stats
    x, y = np.asarray(x, float), np.asarray(y, float)
    lo, hi = stats.ttest_ind(y, x, equal_var=False).confidence_interval(confidence)
    return float(y.mean() - x.mean()), float(lo), float(hi)


def slope(x, y, confidence=0.90):
    """Least-squares slope of y on x with its two-sided Student-t interval: (slope, low, high, n)."""
    from scipy import stats
    x, y = np.asarray(x, float), np.asarray(y, float)
    n = x.size
    if n < 3 or np.ptp(x) == 0:
        return math.nan, math.nan, math.nan, n
    r = stats.linregress(x, y)
    t = t_quantile(confidence, n - 2)
    return float(r.slope), float(r.slope - t * r.stderr), float(r.slope + t * r.stderr), n


def within_slope(x, y, groups, confidence=0.90):
    """The slope of y on x inside groups (a separate intercept per group: x and y demeaned within each group), with
    its two-sided Student-t interval on n - groups - 1 degrees of freedom: (slope, low, high, n)."""
    x, y, groups = np.asarray(x, float), np.asarray(y, float), np.asarray(groups)
    xd, yd = x.copy(), y.copy()
    names = np.unique(groups)
    for g in names:
        m = groups == g
        xd[m] -= x[m].mean()
        yd[m] -= y[m].mean()
    sxx = float(xd @ xd)
    dof = x.size - names.size - 1
    if dof < 1 or sxx == 0:
        return math.nan, math.nan, math.nan, int(x.size)
    b = float(xd @ yd) / sxx
    resid = yd - b * xd
    se = math.sqrt(float(resid @ resid) / dof / sxx)
    t = t_quantile(confidence, dof)
    return b, b - t * se, b + t * se, int(x.size)


def richardson(f3, f2, f1, r):
    """Richardson's extrapolation of coarse f3, medium f2 and fine f1 on meshes refined by the ratio r: (the observed
    order p, the extrapolated value f1 + (f1 - f2) / (r^p - 1), the fine mesh's absolute GCI with safety factor 1,
    |f1 - f2| / (r^p - 1), whether the two differences have one sign). Where two results agree exactly: (nan, f1, 0,
    the signs' agreement)."""
    e32, e21 = f3 - f2, f2 - f1
    if e21 == 0.0 or e32 == 0.0:
        return float("nan"), f1, 0.0, e32 * e21 >= 0
    q = e32 / e21
    p = float(np.log(abs(q)) / np.log(r))
    gain = r ** p - 1.0
    return p, f1 + (f1 - f2) / gain if gain != 0 else float("nan"), abs(f1 - f2) / gain if gain > 0 else float("inf"), q > 0


def power_law_exponent(x, y):
    """The exponent p of y = c x^p fitted by least squares on log-log axes (x, y > 0, >= 2 distinct x)."""
    return statistics.linear_regression([math.log(a) for a in x], [math.log(b) for b in y]).slope
