"""The element pass: every active element row's kinematics, stress, energy, stable step, erosion and forces.

Rows j0 <= j < j1 (the active window), in chunks of ROWS_PER_CHUNK rows per parallel task. Each row in three
phases, which call the same helpers (``element``, ``constitutive``, ``timestep``, ``erosion``), so each formula
exists once:

1. kinematics (vectorised, branch-free): strain rates, spin and volume ratio from the half-step geometry, the
   rotated deviator, and, for HJC, the shortcut update (``hjc.quick_update``: no crush and no plastic flow, or
   fully damaged outside compression) with its energy, viscosity and stable step, stored where valid; the
   element is DONE when it also passes the scalar phase's checks (finite, not eroding, step above the floor);
2. scalar, for the others: the full material update (``constitutive.update``), the erosion criterion and the
   guards;
3. forces (vectorised): internal and hourglass forces at the new geometry (``element.row_forces``).

Element states (``state``): LIVE, ERODED, INACTIVE (below the window), RETIRED (behind it); an element that erodes
in this pass is set to ERODING. Per row j (``Rows``): the smallest stable step with its element and criterion,
the hourglass work, the internal energy of the elements eroded, and the first failure (element and code).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..concrete.hjc import I_RATELAW, power_chords, quick_update
from .constitutive import HJC_KIND, longitudinal_modulus, update, wave_speed
from .element import corners, energy_increment, equivalent_rate, length, moment, rates, rotate, row_forces, sound_shape
from .erosion import erodes
from .state import (BAD_SHAPE, C_DT, C_DTMIN, C_EROSION, C_EROSION_VALUE, C_GUARD, C_Q1, C_Q2, C_QH, CHECK, DMG, DONE,
                    DT_COLLAPSE, EPSEFF, EPSP, ERODING, FAST, IE, INVERTED, LIVE, MUMAX, N_SCRATCH, NON_FINITE, QV,
                    RF_DT, RF_ERO, RF_HG, RI_ARG, RI_CODE, RI_CRIT, RI_FAIL, ROWS_PER_CHUNK, S_C, S_DRR, S_DRZ, S_DT,
                    S_DTT, S_DZZ, S_LC, S_MU, S_R0, S_R1, S_R3, S_RATE, S_STATE, S_TV, S_VH, SCALAR, SKIP, SRR, SRZ,
                    STT, SZZ, TWO_PI, V0, VR, VZ, P)
from .timestep import NO_STEP, criterion, row_step, stable_step, viscosity

N_HJC = I_RATELAW + 1  # length of an HJC parameter array
_ONE = np.uint64(1)


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def _kinematics(j, nr, X, V, E, alive, kind, q, chords, ctl, S):
    """Phase 1 of row j, branch-free (vectorised); unsigned indices: numba then emits no negative-index
    wrap-around and the loop vectorises. q is an HJC parameter array for every kind (a stand-in for the others:
    their shortcut results are discarded)."""
    dt, q1, q2 = ctl[C_DT], ctl[C_Q1], ctl[C_Q2]
    erosion, ev, dtmin = int(ctl[C_EROSION]), ctl[C_EROSION_VALUE], ctl[C_DTMIN]
    h = 0.5 * dt
    un = np.uint64(nr)
    b = np.uint64(j) * (un + _ONE)
    e0 = np.uint64(j) * un
    hjc = kind == HJC_KIND
    for i in range(un):
        e = e0 + i
        n1 = b + i
        n4 = n1 + un + _ONE
        u = corners(V, VR, n1, n4)
        w = corners(V, VZ, n1, n4)
        x = corners(X, 0, n1, n4)
        y = corners(X, 1, n1, n4)
        xh = (x[0] - h * u[0], x[1] - h * u[1], x[2] - h * u[2], x[3] - h * u[3])   # half-step geometry
        yh = (y[0] - h * w[0], y[1] - h * w[1], y[2] - h * w[2], y[3] - h * w[3])
        drr, dzz, dtt, drz, spin, Wh = rates(xh, yh, u, w)
        ok = sound_shape(x, y, xh, yh)
        tv = drr + dzz + dtt
        Vh = TWO_PI * Wh
        mu_ratio = E[V0, e] / (TWO_PI * moment(x[0], x[1], x[2], x[3], y[0], y[1], y[2], y[3])[0])
        old = (E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], E[P, e])
        t0, t1, t3 = rotate(old[0], old[1], old[3], spin, dt)
        rate = equivalent_rate(drr, dzz, dtt, drz, tv)
        lc = length(x, y)
        de = (drr * dt, dzz * dt, dtt * dt, drz * dt)
        valid, n0, n1_, n2, n3, pn, mm, dep, modulus = quick_update(t0, t1, old[2], t3, mu_ratio - 1.0, E[MUMAX, e],
                                                                    E[DMG, e], E[EPSP, e], de[0], de[1], de[2], de[3],
                                                                    rate, q, chords)
        live = alive[e] == LIVE
        fast = live & ok & hjc & valid
        rho = q[0] * mu_ratio
        c = wave_speed(modulus, rho)
        qv = viscosity(rho, lc, c, tv, q1, q2)
        ie_new = E[IE, e] + energy_increment(Vh, old, (n0, n1_, n2, n3, pn), de, E[QV, e], qv, tv, dt)
        dte = stable_step(lc, c, tv, q1, q2)
        ep_new = E[EPSP, e] + dep
        ee_new = E[EPSEFF, e] + rate * dt
        gone = erodes(erosion, ev, ep_new, ee_new, E[DMG, e], math.inf)
        clean = (fast & math.isfinite(dte) & math.isfinite(ie_new) & math.isfinite(pn) & math.isfinite(n0) & (not gone)
                 & (dte >= dtmin))
        E[SRR, e] = n0 if fast else old[0]
        E[SZZ, e] = n1_ if fast else old[1]
        E[STT, e] = n2 if fast else old[2]
        E[SRZ, e] = n3 if fast else old[3]
        E[P, e] = pn if fast else old[4]
        E[MUMAX, e] = mm if fast else E[MUMAX, e]
        E[QV, e] = qv if fast else E[QV, e]
        E[IE, e] = ie_new if fast else E[IE, e]
        E[EPSEFF, e] = ee_new if fast else E[EPSEFF, e]
        E[EPSP, e] = ep_new if fast else E[EPSP, e]
        S[S_DRR, i] = drr
        S[S_DZZ, i] = dzz
        S[S_DTT, i] = dtt
        S[S_DRZ, i] = drz
        S[S_RATE, i] = rate
        S[S_MU, i] = mu_ratio
        S[S_TV, i] = tv
        S[S_VH, i] = Vh
        S[S_STATE, i] = (DONE if clean else CHECK) if fast else (SKIP if not live else (SCALAR if ok else BAD_SHAPE))
        S[S_R0, i] = t0
        S[S_R1, i] = t1
        S[S_R3, i] = t3
        S[S_LC, i] = lc
        S[S_C, i] = c if fast else 0.0
        S[S_DT, i] = dte


@njit(cache=True, inline="always", error_model="numpy")
def _scalar_update(e, i, E, kind, q, ctl, S):
    """Phase 2's material update of element e (scratch column i): stress, state, energy and viscosity into E,
    wave speed into S; returns its stable step."""
    dt, q1, q2 = ctl[C_DT], ctl[C_Q1], ctl[C_Q2]
    drr, dzz, dtt, drz, tv = S[S_DRR, i], S[S_DZZ, i], S[S_DTT, i], S[S_DRZ, i], S[S_TV, i]
    rate, lc, mu_ratio = S[S_RATE, i], S[S_LC, i], S[S_MU, i]
    old = (E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], E[P, e])
    E[SRR, e], E[SZZ, e], E[SRZ, e] = S[S_R0, i], S[S_R1, i], S[S_R3, i]
    de = (drr * dt, dzz * dt, dtt * dt, drz * dt)
    dep = update(kind, q, E, e, de, mu_ratio, rate)
    E[EPSP, e] += dep
    E[EPSEFF, e] += rate * dt
    rho = q[0] * mu_ratio
    c = wave_speed(longitudinal_modulus(kind, q, mu_ratio - 1.0, E[MUMAX, e]), rho)
    S[S_C, i] = c
    qv = viscosity(rho, lc, c, tv, q1, q2)
    E[IE, e] += energy_increment(S[S_VH, i], old, (E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], E[P, e]), de, E[QV, e],
                                 qv, tv, dt)
    E[QV, e] = qv
    return stable_step(lc, c, tv, q1, q2)


@njit(cache=True, inline="always", error_model="numpy")
def _scalar(j, nr, E, alive, kind, q, ctl, rf, ri, S):
    """Phase 2 of row j: the elements phase 1 left (SCALAR, CHECK, BAD_SHAPE); the row's step, its element and
    criterion, eroded energy and first failure into rf, ri (Rows.f, Rows.i)."""
    erosion, ev, guard, dtmin = int(ctl[C_EROSION]), ctl[C_EROSION_VALUE], ctl[C_GUARD] > 0.5, ctl[C_DTMIN]
    dt_row, arg, crit, ero_row, fail, code = NO_STEP, -1, 0, 0.0, -1, 0
    for i in range(nr):
        state = S[S_STATE, i]
        if state == SKIP or state == DONE:
            continue
        e = j * nr + i
        if state == BAD_SHAPE:
            if guard:
                alive[e] = ERODING
                ero_row += E[IE, e]
            elif fail < 0:
                fail, code = e, INVERTED
            continue
        dte = _scalar_update(e, i, E, kind, q, ctl, S) if state == SCALAR else S[S_DT, i]
        if not (math.isfinite(dte) and math.isfinite(E[IE, e]) and math.isfinite(E[P, e]) and math.isfinite(E[SRR, e])):
            if fail < 0:
                fail, code = e, NON_FINITE
            continue
        gone = erodes(erosion, ev, E[EPSP, e], E[EPSEFF, e], E[DMG, e], 1.0 / S[S_MU, i] - 1.0)
        if dte < dtmin:
            if guard:
                gone = True
            elif fail < 0:
                fail, code = e, DT_COLLAPSE
        if gone:
            alive[e] = ERODING
            ero_row += E[IE, e]
            continue
        if dte < dt_row:
            dt_row, arg, crit = dte, e, criterion(S[S_TV, i])
    rf[RF_DT, j], ri[RI_ARG, j], ri[RI_CRIT, j] = row_step(S, nr, j * nr, dt_row, arg, crit)
    rf[RF_ERO, j] = ero_row
    ri[RI_FAIL, j] = fail
    ri[RI_CODE, j] = code


@njit(parallel=True, cache=True, error_model="numpy", fastmath=FAST)
def element_pass(span, X, V, kind, q, ctl, E, F, alive, rf, ri):
    """Strain rates, stress update, internal energy, forces, hourglass, stable time step and erosion of the rows
    span.j0 <= j < span.j1 (see the module's docstring): the element fields E, forces F and states alive, and each
    row's reductions rf, ri (Rows.f, Rows.i), from the node positions X (rows r, z) and velocities V, for the
    material of kind ``kind`` with parameters q."""
    nr, j0, j1 = span.nr, span.j0, span.j1
    # phase 1 evaluates the HJC shortcut for every element (selects, not branches): other materials get a
    # stand-in HJC parameter array so that it reads in bounds (its results are discarded for them)
    qf = q if kind == HJC_KIND else np.ones(N_HJC)
    chords = power_chords(qf)
    nchunk = (j1 - j0 + ROWS_PER_CHUNK - 1) // ROWS_PER_CHUNK
    for ch in prange(nchunk):
        S = np.empty((N_SCRATCH, nr))
        for j in range(j0 + ch * ROWS_PER_CHUNK, min(j1, j0 + (ch + 1) * ROWS_PER_CHUNK)):
            _kinematics(j, nr, X, V, E, alive, kind, qf, chords, ctl, S)
            _scalar(j, nr, E, alive, kind, q, ctl, rf, ri, S)
            rf[RF_HG, j] = row_forces(j, nr, X, V, E, F, alive, ctl[C_QH], ctl[C_DT], S)
