"""The stable time step and the bulk viscosity, and what controls the step.

Bulk viscosity (von Neumann-Richtmyer quadratic with a linear term, LS-DYNA's form) in compression:
q = rho l (Q1^2 l e_v^2 - Q2 c e_v), e_v = tr D < 0, l the element length (``element.length``); none in
expansion. The element's stable step is l/c in expansion and l/(Q + sqrt(Q^2 + c^2)), Q = Q2 c + Q1^2 l |e_v|,
in compression (the step the viscosity allows). The step taken is dt_factor times the smallest, grown by at
most 1.2 from one step to the next.

Each element row reports its smallest step with the element and the criterion that set it (``CFL`` or
``VISCOSITY``); ``next_step`` picks the controlling row (or ``GROWTH`` when the growth limit binds), so that a run
can say which element and which criterion control its step.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .state import CFL, DONE, GROWTH, INITIAL, RF_DT, RI_ARG, RI_CRIT, S_DT, S_STATE, S_TV, VISCOSITY

GROWTH_LIMIT = 1.2
NO_STEP = 1e30   # the step of a row or element that does not limit it


@njit(cache=True, inline="always", error_model="numpy")
def viscosity(rho, lc, c, tv, q1, q2):
    """Bulk viscosity q (Pa) at density rho, length lc, wave speed c and volumetric strain rate tv."""
    return rho * lc * (q1 * q1 * lc * tv * tv - q2 * c * tv) if tv < 0.0 else 0.0


@njit(cache=True, inline="always", error_model="numpy")
def stable_step(lc, c, tv, q1, q2):
    """The element's stable step (s): l/c, or with the viscosity's term in compression."""
    Q = q2 * c + q1 * q1 * lc * abs(tv)
    return lc / (Q + math.sqrt(Q * Q + c * c)) if tv < 0.0 else lc / c


@njit(cache=True, inline="always", error_model="numpy")
def criterion(tv):
    """The criterion of an element's stable step: VISCOSITY in compression, CFL otherwise."""
    return VISCOSITY if tv < 0.0 else CFL


@njit(cache=True, inline="always", error_model="numpy")
def _done_minimum(S, nr):
    """The smallest stable step of a row's DONE elements, in four interleaved running minima (a minimum is exact
    in any order; a single chain would wait on each comparison)."""
    m0 = m1 = m2 = m3 = NO_STEP
    i = 0
    while i + 4 <= nr:
        m0 = min(m0, S[S_DT, i] if S[S_STATE, i] == DONE else NO_STEP)
        m1 = min(m1, S[S_DT, i + 1] if S[S_STATE, i + 1] == DONE else NO_STEP)
        m2 = min(m2, S[S_DT, i + 2] if S[S_STATE, i + 2] == DONE else NO_STEP)
        m3 = min(m3, S[S_DT, i + 3] if S[S_STATE, i + 3] == DONE else NO_STEP)
        i += 4
    while i < nr:
        m0 = min(m0, S[S_DT, i] if S[S_STATE, i] == DONE else NO_STEP)
        i += 1
    return min(min(m0, m1), min(m2, m3))


@njit(cache=True, inline="always", error_model="numpy")
def row_step(S, nr, e0, dt_row, arg, crit):
    """The row's smallest step, its element and criterion: those of the scalar phase (dt_row, arg, crit) against the
    DONE elements' (found by a scan only where one of them controls)."""
    m = _done_minimum(S, nr)
    if m < dt_row:
        for i in range(nr):
            if S[S_STATE, i] == DONE and S[S_DT, i] == m:
                return m, e0 + i, criterion(S[S_TV, i])
    return dt_row, arg, crit


@njit(cache=True)
def next_step(rf, ri, nz, dt, t, dt_factor):
    """The next step after a step dt at time t from the rows' steps (Rows.f, Rows.i of nz rows): (dt_new, its
    criterion, the controlling element or -1)."""
    if t <= 0.0:
        return dt, INITIAL, -1
    jm = np.argmin(rf[RF_DT, :nz])
    dt_new = dt_factor * rf[RF_DT, jm]
    if GROWTH_LIMIT * dt < dt_new:
        return GROWTH_LIMIT * dt, GROWTH, -1
    return dt_new, ri[RI_CRIT, jm], ri[RI_ARG, jm]
