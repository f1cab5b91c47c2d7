"""Compiled kernels of the axisymmetric explicit solver (structure-of-arrays, numba).

Formulation (volume-weighted, one-point integration at the element centre):
b_r = dN/dr, b_z = dN/dz of the bilinear quad at its centre; the element
volume is exact, V = 2 pi W with W the integral of r dA over the quad; the hoop
row is (dW/dr_I - W b_rI)/W, so that a field v_r = alpha r gives D_tt = alpha
exactly and a uniform stress with sigma_rr = sigma_tt leaves no residual at
interior nodes of a distorted mesh (with the mean nodal radius in place of W/A
it leaves a few per cent). Internal force f_I = V B_I^T sigma, whose power is
V sigma:D exactly, so the energy audit has no formulation error; the axial
momentum is conserved to round-off (sum_I b_I = 0). Lumped masses m_I = sum of
m_e/4.

One step (central differences): v^{n+1/2} = v^{n-1/2} + dt a^n; kinematic contact
corrects v^{n+1/2}; x^{n+1} = x^n + dt v^{n+1/2}; strain rate and spin from the
half-step geometry; the deviatoric stress is rotated (Jaumann, exact in-plane
rotation by the spin angle) then updated by the material; forces at x^{n+1}.

Hourglass: Flanagan-Belytschko viscous form; the hourglass shape vector is
orthogonal to every linear velocity field (patch test) and the coefficient
QH rho c V/sqrt(A) uses the bulk wave speed, so it stays active where the
material has lost its shear strength. Bulk viscosity q = rho l (Q1^2 l e_v^2 -
Q2 c e_v) in compression, l = sqrt(A).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..hjc import I_HOOP, I_G, I_K1, I_K2, I_K3, I_MUCRUSH, I_MULOCK, power_chords, quick_update, unloading_modulus, update_voigt
from .materials import HJC_KIND

# element fields (rows of E)
SRR, SZZ, STT, SRZ, P, QV, MUMAX, MUP, DMG, EPSP, EPSEFF, IE, V0, MASS = range(14)
N_FIELDS = 14
# the rows phase 1 of the element pass stores for every element, each step (the others are stored only where
# phase 2 updates an element: MUP, DMG; or never: V0, MASS); the speed benchmark counts the bytes a step moves by them
STEP_STORES = (SRR, SZZ, STT, SRZ, P, MUMAX, QV, IE, EPSEFF, EPSP)
# controls (ctl)
C_DT, C_QH, C_Q1, C_Q2, C_EROSION, C_EROSION_VALUE, C_GUARD, C_DTMIN = range(8)
N_CTL = 8
N_HJC = I_HOOP + 1  # length of an HJC parameter array
EROSION_KINDS = {"none": 0, "plastic_strain": 1, "effective_strain": 2, "volumetric_tension": 3, "damage": 4}
BOUNDARIES = {"free": 0, "roller": 1, "non_reflecting": 2}
# failure codes
OK, NON_FINITE, INVERTED, DT_COLLAPSE = 0, 1, 2, 3
FAILURES = {NON_FINITE: "non-finite stress or geometry", INVERTED: "inverted element (a corner Jacobian <= 0)",
            DT_COLLAPSE: "element time step below the floor"}
TWO_PI = 2.0 * math.pi
# No fast-math: with contraction, reassociation or reciprocal approximations LLVM's choices depend on the
# compilation context, and a kernel loaded from numba's cache then gave a different (chaotic) DO1 depth
# (5.18 m) from the same kernel compiled afresh (5.10 m). Without them every operation is IEEE-exact in
# source order, vectorised or not; the loops vectorise all the same (no reductions inside them).
FAST = False
# Constant divisors as multiplications by their reciprocals (each rounded once, here): a division costs the
# vector loops several times a multiplication (12 of the element pass's 30 divisions are by 6 or 3).
# Deterministic like the rest (not IEEE-equal to dividing: the results differ in the last bit).
SIXTH = 1.0 / 6.0
THIRD = 1.0 / 3.0
# Doubles per vector of the row loops as LLVM emits them here (AVX2: 4); a row whose length is not a multiple
# of it leaves its last elements to a scalar remainder loop (fe.mesh.build sizes the rows to avoid that).
VECTOR_WIDTH = 4


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def _moment(r1, r2, r3, r4, z1, z2, z3, z4):
    """W = integral of r dA over the quad (V = 2 pi W) and dW/dr_I (W is quadratic in r, linear in z)."""
    c12 = r1 * z2 - r2 * z1
    c23 = r2 * z3 - r3 * z2
    c34 = r3 * z4 - r4 * z3
    c41 = r4 * z1 - r1 * z4
    W = ((r1 + r2) * c12 + (r2 + r3) * c23 + (r3 + r4) * c34 + (r4 + r1) * c41) * SIXTH
    w1 = (c41 + c12 + (r4 + r1) * (-z4) + (r1 + r2) * z2) * SIXTH
    w2 = (c12 + c23 + (r1 + r2) * (-z1) + (r2 + r3) * z3) * SIXTH
    w3 = (c23 + c34 + (r2 + r3) * (-z2) + (r3 + r4) * z4) * SIXTH
    w4 = (c34 + c41 + (r3 + r4) * (-z3) + (r4 + r1) * z1) * SIXTH
    return W, w1, w2, w3, w4


@njit(cache=True, inline="always", error_model="numpy")
def _wave_speed(kind, q, mu, mumax, rho):
    """Longitudinal (loading or unloading, whichever is stiffer) wave speed."""
    if kind == HJC_KIND:
        K = unloading_modulus(mumax, q)
        if mu > q[I_MUCRUSH]:
            mb = (mu - q[I_MULOCK]) / (1.0 + q[I_MULOCK])
            K = max(K, q[I_K1] + 2.0 * q[I_K2] * mb + 3.0 * q[I_K3] * mb * mb)
        G = q[I_G]
    else:
        K = q[2]
        G = q[1]
    return math.sqrt((K + 4.0 * G / 3.0) / rho)


@njit(cache=True, inline="always", error_model="numpy")
def _simple_update(kind, q, E, e, de0, de1, de2, de3, mu_ratio):
    """Elastic / von Mises update of the deviatoric stress and pressure p = K ln(V0/V); returns d eps_p."""
    G, K = q[1], q[2]
    tr = (de0 + de1 + de2) / 3.0
    E[SRR, e] += 2.0 * G * (de0 - tr)
    E[SZZ, e] += 2.0 * G * (de1 - tr)
    E[STT, e] += 2.0 * G * (de2 - tr)
    E[SRZ, e] += 2.0 * G * de3
    E[P, e] = K * math.log(mu_ratio)
    if kind == 0:
        return 0.0
    s0, s1, s2, s3 = E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e]
    seq = math.sqrt(1.5 * (s0 * s0 + s1 * s1 + s2 * s2) + 3.0 * s3 * s3)
    sy = q[3] + q[4] * E[EPSP, e]
    if seq <= sy:
        return 0.0
    dep = (seq - sy) / (3.0 * G + q[4])
    scale = (sy + q[4] * dep) / seq
    E[SRR, e] = s0 * scale
    E[SZZ, e] = s1 * scale
    E[STT, e] = s2 * scale
    E[SRZ, e] = s3 * scale
    return dep


# scratch rows of one element row (phase 1 -> phase 2 -> phase 3)
(S_DRR, S_DZZ, S_DTT, S_DRZ, S_RATE, S_MU, S_TV, S_VH, S_STATE, S_R0, S_R1, S_R3, S_LC, S_C, S_DT, S_HG,
 N_SCRATCH) = range(17)
# S_STATE: 0 the element is not live, 1 live, done by phase 1 (hjc.quick_update) and through phase 2's checks,
# 2 live, needs the scalar material update, 3 live with an inverted or degenerate geometry, 4 live, done by
# phase 1 but caught by a check (non-finite, eroding, step below the floor): phase 2 deals with it
ROWS_PER_CHUNK = 8
_ONE = np.uint64(1)


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def _row_kinematics(j, nr, r, z, vr, vz, E, alive, kind, q, chords, dt, q1, q2, erosion, ev, dtmin, S):
    """Phase 1 of a row, branch-free (vectorised): strain rates, spin, volume ratio, length; for HJC the
    no-crush update (hjc.quick_update: no plastic flow, or fully damaged outside compression), its energy,
    viscosity and stable step, stored into E where valid, and phase 2's checks of these elements. Unsigned
    indices: numba then emits no negative-index wrap-around and the loop vectorises."""
    h = 0.5 * dt
    un = np.uint64(nr)
    b = np.uint64(j) * (un + _ONE)
    e0 = np.uint64(j) * un
    hjc = kind == HJC_KIND
    for i in range(un):
        e = e0 + i
        n1 = b + i
        n4 = n1 + un + _ONE
        u1, u2, u3, u4 = vr[n1], vr[n1 + _ONE], vr[n4 + _ONE], vr[n4]
        w1, w2, w3, w4 = vz[n1], vz[n1 + _ONE], vz[n4 + _ONE], vz[n4]
        r1, r2, r3, r4 = r[n1], r[n1 + _ONE], r[n4 + _ONE], r[n4]
        z1, z2, z3, z4 = z[n1], z[n1 + _ONE], z[n4 + _ONE], z[n4]
        # ---- half-step geometry: strain rate and spin
        R1, R2, R3, R4 = r1 - h * u1, r2 - h * u2, r3 - h * u3, r4 - h * u4
        Z1, Z2, Z3, Z4 = z1 - h * w1, z2 - h * w2, z3 - h * w3, z4 - h * w4
        A2h = (R3 - R1) * (Z4 - Z2) + (R2 - R4) * (Z3 - Z1)
        # ---- new geometry
        A2 = (r3 - r1) * (z4 - z2) + (r2 - r4) * (z3 - z1)
        c1 = (r2 - r1) * (z4 - z1) - (z2 - z1) * (r4 - r1)
        c2 = (r3 - r2) * (z1 - z2) - (z3 - z2) * (r1 - r2)
        c3 = (r4 - r3) * (z2 - z3) - (z4 - z3) * (r2 - r3)
        c4 = (r1 - r4) * (z3 - z4) - (z1 - z4) * (r3 - r4)
        ok = ((A2h > 0.0) & (A2 > 0.0) & (min(min(c1, c2), min(c3, c4)) > 0.0) & (r1 + r2 + r3 + r4 > 0.0)
              & (R1 + R2 + R3 + R4 > 0.0))
        ih = 1.0 / A2h
        br1, br2 = (Z2 - Z4) * ih, (Z3 - Z1) * ih
        bz1, bz2 = (R4 - R2) * ih, (R1 - R3) * ih
        drr = br1 * (u1 - u3) + br2 * (u2 - u4)
        dzz = bz1 * (w1 - w3) + bz2 * (w2 - w4)
        dvr_dz = bz1 * (u1 - u3) + bz2 * (u2 - u4)
        dvz_dr = br1 * (w1 - w3) + br2 * (w2 - w4)
        # hoop rate consistent with the exact volume: (1/W) sum (dW/dr_I - W b_rI) v_rI (= alpha for v_r = alpha r)
        Wh, h1, h2, h3, h4 = _moment(R1, R2, R3, R4, Z1, Z2, Z3, Z4)
        dtt = (h1 * u1 + h2 * u2 + h3 * u3 + h4 * u4) / Wh - drr
        drz = 0.5 * (dvr_dz + dvz_dr)
        spin = 0.5 * (dvr_dz - dvz_dr)
        tv = drr + dzz + dtt
        Vh = TWO_PI * Wh
        W = _moment(r1, r2, r3, r4, z1, z2, z3, z4)[0]
        mu_ratio = E[V0, e] / (TWO_PI * W)
        # ---- rotate the deviatoric stress by the spin angle (Jaumann)
        so0, so1, so2, so3, po = E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], E[P, e]
        th = spin * dt  # Cayley (Hughes-Winget) rotation: orthogonal, angle 2 atan(th) = 2 th + O(th^3)
        den = 1.0 / (1.0 + th * th)
        cs, sn = (1.0 - th * th) * den, 2.0 * th * den
        am, dm = 0.5 * (so0 + so1), 0.5 * (so0 - so1)
        dn = dm * cs + so3 * sn
        t0, t1, t3 = am + dn, am - dn, so3 * cs - dm * sn
        tv3 = tv * THIRD
        dev0, dev1, dev2 = drr - tv3, dzz - tv3, dtt - tv3
        rate = math.sqrt(2.0 / 3.0 * (dev0 * dev0 + dev1 * dev1 + dev2 * dev2 + 2.0 * drz * drz))
        # one length for viscosity, hourglass and time step: area over the longest side
        s12 = (r2 - r1) ** 2 + (z2 - z1) ** 2
        s23 = (r3 - r2) ** 2 + (z3 - z2) ** 2
        s34 = (r4 - r3) ** 2 + (z4 - z3) ** 2
        s41 = (r1 - r4) ** 2 + (z1 - z4) ** 2
        lc = 0.5 * A2 / math.sqrt(max(max(s12, s23), max(s34, s41)))
        # ---- HJC in its elastic region (the same result as update_point there)
        de0, de1, de2, de3 = drr * dt, dzz * dt, dtt * dt, drz * dt
        valid, n0, n1_, n2, n3, pn, mm, dep, c2 = quick_update(t0, t1, so2, t3, mu_ratio - 1.0, E[MUMAX, e], E[DMG, e],
                                                               E[EPSP, e], de0, de1, de2, de3, rate, q, chords)
        live = alive[e] == 1
        fast = live & ok & hjc & valid
        rho = q[0] * mu_ratio
        c = math.sqrt(c2 / rho)
        qv = rho * lc * (q1 * q1 * lc * tv * tv - q2 * c * tv) if tv < 0.0 else 0.0
        die = Vh * (0.5 * ((so0 - po + n0 - pn) * de0 + (so1 - po + n1_ - pn) * de1 + (so2 - po + n2 - pn) * de2)
                    + (so3 + n3) * de3 - qv * tv * dt)
        Q = q2 * c + q1 * q1 * lc * abs(tv)
        dte = lc / (Q + math.sqrt(Q * Q + c * c)) if tv < 0.0 else lc / c
        # phase 2's checks of an element completed here (finite results, no erosion, no step collapse): one that
        # passes them (state 1) has nothing left for phase 2 but its stable step (the volumetric-tension criterion
        # is left to phase 2: its division would cost every element)
        ie_new = E[IE, e] + die
        ep_new = E[EPSP, e] + dep
        ee_new = E[EPSEFF, e] + rate * dt
        gone = (((erosion == 1) & (ep_new >= ev)) | ((erosion == 2) & (ee_new >= ev)) | (erosion == 3)
                | ((erosion == 4) & (E[DMG, e] >= ev)))
        clean = (fast & math.isfinite(dte) & math.isfinite(ie_new) & math.isfinite(pn) & math.isfinite(n0) & (not gone)
                 & (dte >= dtmin))
        E[SRR, e] = n0 if fast else so0
        E[SZZ, e] = n1_ if fast else so1
        E[STT, e] = n2 if fast else so2
        E[SRZ, e] = n3 if fast else so3
        E[P, e] = pn if fast else po
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
        S[S_STATE, i] = (1.0 if clean else 4.0) if fast else (0.0 if not live else (2.0 if ok else 3.0))
        S[S_R0, i] = t0
        S[S_R1, i] = t1
        S[S_R3, i] = t3
        S[S_LC, i] = lc
        S[S_C, i] = c if fast else 0.0
        S[S_DT, i] = dte


@njit(cache=True, inline="always", error_model="numpy")
def _clean_min(S, nr):
    """The smallest stable step of a row's state-1 elements, in four interleaved running minima (a minimum is
    exact in any order; a single chain would wait on each comparison)."""
    m0 = m1 = m2 = m3 = 1e30
    i = 0
    while i + 4 <= nr:
        m0 = min(m0, S[S_DT, i] if S[S_STATE, i] == 1.0 else 1e30)
        m1 = min(m1, S[S_DT, i + 1] if S[S_STATE, i + 1] == 1.0 else 1e30)
        m2 = min(m2, S[S_DT, i + 2] if S[S_STATE, i + 2] == 1.0 else 1e30)
        m3 = min(m3, S[S_DT, i + 3] if S[S_STATE, i + 3] == 1.0 else 1e30)
        i += 4
    while i < nr:
        m0 = min(m0, S[S_DT, i] if S[S_STATE, i] == 1.0 else 1e30)
        i += 1
    return min(min(m0, m1), min(m2, m3))


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def _row_forces(j, nr, r, z, vr, vz, E, F, alive, qh, dt, S):
    """Phase 3 of a row (vectorised): internal and hourglass forces of every element at the new geometry
    (the node pass reads only live elements' forces); returns the hourglass work of the live ones."""
    un = np.uint64(nr)
    b = np.uint64(j) * (un + _ONE)
    e0 = np.uint64(j) * un
    for i in range(un):
        e = e0 + i
        n1 = b + i
        n4 = n1 + un + _ONE
        r1, r2, r3, r4 = r[n1], r[n1 + _ONE], r[n4 + _ONE], r[n4]
        z1, z2, z3, z4 = z[n1], z[n1 + _ONE], z[n4 + _ONE], z[n4]
        A2 = (r3 - r1) * (z4 - z2) + (r2 - r4) * (z3 - z1)
        W, m1, m2, m3, m4 = _moment(r1, r2, r3, r4, z1, z2, z3, z4)
        V = TWO_PI * W
        ia = 1.0 / A2
        b1r, b2r = (z2 - z4) * ia, (z3 - z1) * ia
        b1z, b2z = (r4 - r2) * ia, (r1 - r3) * ia
        pq = E[P, e] + E[QV, e]
        sn3 = E[SRZ, e]
        srr = E[SRR, e] - pq
        szz = E[SZZ, e] - pq
        stt = E[STT, e] - pq
        # hoop force 2 pi (dW/dr_I - W b_rI) sigma_tt: with V b_rI sigma_rr it is 2 pi sigma dW/dr_I when
        # sigma_rr = sigma_tt, which sums to zero at interior nodes (the patch test)
        ht = TWO_PI * stt
        f0 = V * (b1r * (srr - stt) + b1z * sn3)
        f1 = V * (b1z * szz + b1r * sn3)
        f2 = V * (b2r * (srr - stt) + b2z * sn3)
        f3 = V * (b2z * szz + b2r * sn3)
        # hourglass (Flanagan-Belytschko, viscous; qh = 0 switches it off)
        u1, u2, u3, u4 = vr[n1], vr[n1 + _ONE], vr[n4 + _ONE], vr[n4]
        w1, w2, w3, w4 = vz[n1], vz[n1 + _ONE], vz[n4 + _ONE], vz[n4]
        hr = r1 - r2 + r3 - r4
        hz = z1 - z2 + z3 - z4
        g1 = 0.25 * (1.0 - hr * b1r - hz * b1z)
        g2 = 0.25 * (-1.0 - hr * b2r - hz * b2z)
        g3 = 0.25 * (1.0 + hr * b1r + hz * b1z)
        g4 = 0.25 * (-1.0 + hr * b2r + hz * b2z)
        qr = g1 * u1 + g2 * u2 + g3 * u3 + g4 * u4
        qz = g1 * w1 + g2 * w2 + g3 * w3 + g4 * w4
        kap = qh * E[MASS, e] * S[S_C, i] / S[S_LC, i]
        kr, kz = kap * qr, kap * qz
        F[0, e] = f0 + ht * m1 + g1 * kr
        F[1, e] = f1 + g1 * kz
        F[2, e] = f2 + ht * m2 + g2 * kr
        F[3, e] = f3 + g2 * kz
        F[4, e] = -f0 + ht * m3 + g3 * kr
        F[5, e] = -f1 + g3 * kz
        F[6, e] = -f2 + ht * m4 + g4 * kr
        F[7, e] = -f3 + g4 * kz
        S[S_HG, i] = (kr * qr + kz * qz) * dt if alive[e] == 1 else 0.0
    # the hourglass work of the row, summed in order (a reduction inside the loop above would need
    # reassociation to vectorise, and reassociated sums differ between compilations)
    hg = 0.0
    for i in range(nr):
        hg += S[S_HG, i]
    return hg


@njit(parallel=True, cache=True, error_model="numpy", fastmath=FAST)
def element_pass(nr, nz, j0, j1, r, z, vr, vz, E, alive, F, kind, q, ctl, rowdt, rowhg, rowero, rowfail):
    """Strain rates, stress update, internal energy, forces, hourglass, stable time step and erosion, per row.

    Rows j0 <= j < j1 only (the active window), in chunks of ROWS_PER_CHUNK
    rows per task. Each row in three phases: a vectorised kinematics pass
    that also completes every HJC element that neither crushes nor flows
    plastically, or is fully damaged outside compression (hjc.quick_update),
    and checks it (finite, not eroding, step above the floor); a scalar pass
    with the full material update, the erosion criteria and guards of the
    others; a vectorised force pass. alive: 1 live, 0 eroded, 3 not
    yet active, 4 retired behind the window; an element that erodes in this
    pass is set to 2.
    Per row j: rowdt[j] the smallest stable step, rowhg[j] the hourglass work,
    rowero[j] the internal energy of the elements eroded, rowfail[j] = the
    element index of a failure (-1 none) with its code in rowfail[nz + j].
    """
    dt = ctl[C_DT]
    qh, q1, q2 = ctl[C_QH], ctl[C_Q1], ctl[C_Q2]
    erosion, ev, guard, dtmin = int(ctl[C_EROSION]), ctl[C_EROSION_VALUE], ctl[C_GUARD] > 0.5, ctl[C_DTMIN]
    # phase 1 evaluates the HJC shortcut for every element (selects, not branches): other materials get a
    # stand-in HJC parameter array so that it reads in bounds (its results are discarded for them)
    qh_ = q if kind == HJC_KIND else np.ones(N_HJC)
    chords = power_chords(qh_)
    nchunk = (j1 - j0 + ROWS_PER_CHUNK - 1) // ROWS_PER_CHUNK
    for ch in prange(nchunk):
        S = np.empty((N_SCRATCH, nr))
        for j in range(j0 + ch * ROWS_PER_CHUNK, min(j1, j0 + (ch + 1) * ROWS_PER_CHUNK)):
            _row_kinematics(j, nr, r, z, vr, vz, E, alive, kind, qh_, chords, dt, q1, q2, erosion, ev, dtmin, S)
            dt_row, ero_row, fail, code = 1e30, 0.0, -1, 0
            for i in range(nr):
                state = S[S_STATE, i]
                if state == 0.0 or state == 1.0:
                    continue
                e = j * nr + i
                if state == 3.0:
                    if guard:
                        alive[e] = 2
                        ero_row += E[IE, e]
                    elif fail < 0:
                        fail, code = e, INVERTED
                    continue
                mu_ratio = S[S_MU, i]
                if state == 2.0:
                    drr, dzz, dtt, drz, tv = S[S_DRR, i], S[S_DZZ, i], S[S_DTT, i], S[S_DRZ, i], S[S_TV, i]
                    rate, lc = S[S_RATE, i], S[S_LC, i]
                    so0, so1, so2, so3, po = E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], E[P, e]
                    E[SRR, e], E[SZZ, e], E[SRZ, e] = S[S_R0, i], S[S_R1, i], S[S_R3, i]
                    de0, de1, de2, de3 = drr * dt, dzz * dt, dtt * dt, drz * dt
                    if kind == HJC_KIND:
                        n0, n1, n2, n3, _, _, pn, mumax, mup, dmg, dep = update_voigt(
                            E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], 0.0, 0.0, mu_ratio - 1.0, E[MUMAX, e],
                            E[MUP, e], E[DMG, e], E[EPSP, e], de0, de1, de2, de3, 0.0, 0.0, rate, q)
                        E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e] = n0, n1, n2, n3
                        E[P, e], E[MUMAX, e], E[MUP, e], E[DMG, e] = pn, mumax, mup, dmg
                    else:
                        dep = _simple_update(kind, q, E, e, de0, de1, de2, de3, mu_ratio)
                    E[EPSP, e] += dep
                    E[EPSEFF, e] += rate * dt
                    rho = q[0] * mu_ratio
                    c = _wave_speed(kind, q, mu_ratio - 1.0, E[MUMAX, e], rho)
                    S[S_C, i] = c
                    qv = rho * lc * (q1 * q1 * lc * tv * tv - q2 * c * tv) if tv < 0.0 else 0.0
                    pn = E[P, e]
                    sn0, sn1, sn2, sn3 = E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e]
                    E[IE, e] += S[S_VH, i] * (0.5 * ((so0 - po + sn0 - pn) * de0 + (so1 - po + sn1 - pn) * de1
                                                     + (so2 - po + sn2 - pn) * de2) + (so3 + sn3) * de3 - qv * tv * dt)
                    E[QV, e] = qv
                    if tv < 0.0:
                        Q = q2 * c + q1 * q1 * lc * abs(tv)
                        dte = lc / (Q + math.sqrt(Q * Q + c * c))
                    else:
                        dte = lc / c
                else:
                    dte = S[S_DT, i]
                if not (math.isfinite(dte) and math.isfinite(E[IE, e]) and math.isfinite(E[P, e])
                        and math.isfinite(E[SRR, e])):
                    if fail < 0:
                        fail, code = e, NON_FINITE
                    continue
                # ---- erosion and guards
                gone = False
                if erosion == 1:
                    gone = E[EPSP, e] >= ev
                elif erosion == 2:
                    gone = E[EPSEFF, e] >= ev
                elif erosion == 3:
                    gone = 1.0 / mu_ratio - 1.0 >= ev
                elif erosion == 4:
                    gone = E[DMG, e] >= ev
                if dte < dtmin:
                    if guard:
                        gone = True
                    elif fail < 0:
                        fail, code = e, DT_COLLAPSE
                if gone:
                    alive[e] = 2
                    ero_row += E[IE, e]
                    continue
                dt_row = min(dt_row, dte)
            dt_row = min(dt_row, _clean_min(S, nr))
            rowhg[j] = _row_forces(j, nr, r, z, vr, vz, E, F, alive, qh, dt, S)
            rowdt[j] = dt_row
            rowero[j] = ero_row
            rowfail[j] = fail
            rowfail[nz + j] = code


@njit(cache=True, inline="always", error_model="numpy")
def _node_velocity(ur, uz, fr, fz, m, dtv, da, nr_, nz_, fx, zp, zs):
    """A node's new velocity from its force, its dashpot (area da > 0, normal (nr_, nz_)) and its fixity, without
    branches; returns (v_r, v_z, power absorbed by the dashpot, its axial force)."""
    ur0, uz0 = ur, uz
    ur = ur - dtv * fr / m
    uz = uz - dtv * fz / m
    # dashpot implicit in the new velocity: v' = v*/(1 + dtv Z da/m) per direction (stable for any damping; an
    # explicit dashpot at the wave impedance is near-critically damped and needs a smaller step); its work is
    # the impulse times the mean of the old and new velocities
    vn = ur * nr_ + uz * nz_
    tr_, tz_ = ur - vn * nr_, uz - vn * nz_
    vn1 = vn / (1.0 + dtv * zp * da / m)
    cn = 1.0 / (1.0 + dtv * zs * da / m)
    ur1 = vn1 * nr_ + tr_ * cn
    uz1 = vn1 * nz_ + tz_ * cn
    ir = m * (ur1 - ur)  # impulse of the dashpot
    iz = m * (uz1 - uz)
    dashed = da > 0.0
    pw = (ir * 0.5 * (ur0 + ur1) + iz * 0.5 * (uz0 + uz1)) / dtv if dashed else 0.0
    fb = iz / dtv if dashed else 0.0
    ur = ur1 if dashed else ur
    uz = uz1 if dashed else uz
    ur = 0.0 if (fx & 1) != 0 else ur
    uz = 0.0 if (fx & 2) != 0 else uz
    return ur, uz, pw, fb


@njit(cache=True, inline="always", error_model="numpy")
def _update_node(n, i, fr, fz, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, zp, zs, W):
    """Store node n's new velocity (its old one in vr0, vz0; dropped nodes keep theirs) and its dashpot's
    power and axial force in W[:, i]."""
    ur, uz = vr[n], vz[n]
    u1, w1, pw, fb = _node_velocity(ur, uz, fr, fz, mass[n], dtv, dash[0, n], dash[1, n], dash[2, n], fix[n], zp, zs)
    _store_node(n, i, ur, uz, u1, w1, pw, fb, nstate, vr, vz, vr0, vz0, W)


@njit(cache=True, inline="always", error_model="numpy")
def _store_node(n, i, ur, uz, u1, w1, pw, fb, nstate, vr, vz, vr0, vz0, W):
    """Store node n's old velocity (ur, uz) in vr0, vz0 and its new one (u1, w1; dropped nodes keep theirs), and
    its dashpot's power and axial force in W[:, i]."""
    keep = nstate[n] < 2
    vr0[n] = ur
    vz0[n] = uz
    vr[n] = u1 if keep else ur
    vz[n] = w1 if keep else uz
    W[0, i] = pw if keep else 0.0
    W[1, i] = fb if keep else 0.0


@njit(cache=True, inline="always", error_model="numpy")
def _gather(i, ue, un, F, alive):
    """Force on the interior node i of a row from its four elements (ue: the row's first element)."""
    ea = ue + i          # element (i, j): the node is its corner 1
    eb = ea - _ONE       # element (i - 1, j): corner 2
    ec = eb - un         # element (i - 1, j - 1): corner 3
    ed = ea - un         # element (i, j - 1): corner 4
    fr = ((F[0, ea] if alive[ea] == 1 else 0.0) + (F[2, eb] if alive[eb] == 1 else 0.0)
          + (F[4, ec] if alive[ec] == 1 else 0.0) + (F[6, ed] if alive[ed] == 1 else 0.0))
    fz = ((F[1, ea] if alive[ea] == 1 else 0.0) + (F[3, eb] if alive[eb] == 1 else 0.0)
          + (F[5, ec] if alive[ec] == 1 else 0.0) + (F[7, ed] if alive[ed] == 1 else 0.0))
    return fr, fz


@njit(cache=True, inline="always", error_model="numpy")
def _free_node(n, i, fr, fz, mass, vr, vz, vr0, vz0, nstate, dtv, fix, W):
    """_update_node for a node without a dashpot (the same arithmetic as _node_velocity with da = 0)."""
    ur, uz = vr[n], vz[n]
    m = mass[n]
    u1 = ur - dtv * fr / m
    w1 = uz - dtv * fz / m
    fx = fix[n]
    u1 = 0.0 if (fx & 1) != 0 else u1
    w1 = 0.0 if (fx & 2) != 0 else w1
    _store_node(n, i, ur, uz, u1, w1, 0.0, 0.0, nstate, vr, vz, vr0, vz0, W)


@njit(cache=True, inline="always", error_model="numpy")
def _edge_node(n, i, j, nr, nz, F, alive, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, zp, zs, W):
    """_node_velocity for a node on an edge of the grid (fewer than four elements around it)."""
    fr = 0.0
    fz = 0.0
    if i < nr and j < nz:
        e = j * nr + i
        if alive[e] == 1:
            fr += F[0, e]
            fz += F[1, e]
    if i > 0 and j < nz:
        e = j * nr + i - 1
        if alive[e] == 1:
            fr += F[2, e]
            fz += F[3, e]
    if i > 0 and j > 0:
        e = (j - 1) * nr + i - 1
        if alive[e] == 1:
            fr += F[4, e]
            fz += F[5, e]
    if i < nr and j > 0:
        e = (j - 1) * nr + i
        if alive[e] == 1:
            fr += F[6, e]
            fz += F[7, e]
    _update_node(n, i, fr, fz, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, zp, zs, W)


@njit(parallel=True, cache=True, error_model="numpy")
def node_pass(nr, nz, j0, j1, F, alive, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, rowdash, zp, zs, rowbnd):
    """Gather element forces (internal + hourglass), add boundary dashpots, update velocities by dtv.

    fix[n]: 1 holds v_r = 0 (axis, roller), 2 holds v_z = 0, 3 both. dash[:, n]
    = (area, n_r, n_z): a non-reflecting (Lysmer) dashpot on the node's share
    of the boundary, traction -rho c_p v_n n - rho c_s v_t, taken at the new
    velocity; rowdash[j] = 1 where a node of row j off the grid's edges has
    one (the interior nodes of the other rows skip the dashpot's arithmetic).
    rowbnd[0, j]: power absorbed, rowbnd[1, j]: axial force of the dashpots,
    per node row. vr0, vz0 receive the velocities before the update
    (for the contact's work). Dropped nodes (nstate >= 2) keep their velocity.
    Interior nodes of a row go through a branch-free (vectorised) loop, with
    unsigned indices as in the element pass; nodes on the grid's edges one by one.
    """
    nchunk = (j1 - j0 + 1 + ROWS_PER_CHUNK - 1) // ROWS_PER_CHUNK
    for ch in prange(nchunk):
        W = np.empty((2, nr + 1))
        for j in range(j0 + ch * ROWS_PER_CHUNK, min(j1 + 1, j0 + (ch + 1) * ROWS_PER_CHUNK)):
            base = j * (nr + 1)
            if j == 0 or j == nz:
                for i in range(nr + 1):
                    _edge_node(base + i, i, j, nr, nz, F, alive, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash,
                               zp, zs, W)
            else:
                _edge_node(base, 0, j, nr, nz, F, alive, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, zp, zs, W)
                _edge_node(base + nr, nr, j, nr, nz, F, alive, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash,
                           zp, zs, W)
                un = np.uint64(nr)
                ub = np.uint64(base)
                ue = np.uint64(j) * un
                if rowdash[j] != 0:
                    for i in range(_ONE, un):
                        n = ub + i
                        fr, fz = _gather(i, ue, un, F, alive)
                        _update_node(n, i, fr, fz, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, zp, zs, W)
                else:
                    for i in range(_ONE, un):
                        n = ub + i
                        fr, fz = _gather(i, ue, un, F, alive)
                        _free_node(n, i, fr, fz, mass, vr, vz, vr0, vz0, nstate, dtv, fix, W)
            pw = 0.0
            fb = 0.0
            for i in range(nr + 1):
                pw -= W[0, i]
                fb += W[1, i]
            rowbnd[0, j] = pw
            rowbnd[1, j] = fb


@njit(parallel=True, cache=True)
def move(r, z, vr, vz, nstate, dt, n0, n1):
    """x += dt v for the nodes n0 <= n < n1 that are not dropped (the window's node rows: every node outside
    them is retired or not yet active)."""
    for k in prange(n1 - n0):
        n = n0 + k
        if nstate[n] < 2:
            r[n] += dt * vr[n]
            z[n] += dt * vz[n]


@njit(cache=True)
def contact(r, z, vr, vz, vr0, vz0, mass, nstate, on_axis, dt, Zt, V, V0, M, zeta, rho, rho_max, mu_f, buf_i, buf, n0, n1):
    """Kinematic contact of the target nodes n0 <= n < n1 with the rigid projectile (tip at z = Zt, moving +z at V).

    Nodes whose predicted positions lie inside the body are moved onto its
    surface (closest point of the outline; along the axis for nodes on it)
    by normal impulses lam_I >= 0 shared with the projectile: the exact
    solution of the rank-one system lam_I/m_I + n_zI S/M = g_I/dt,
    S = sum lam_J n_zJ (an active set drops nodes that would pull).
    Optional Coulomb friction (mu_f) stops the tangential slip up to mu_f lam.

    Work of the contact (returned as the energy it removes): each impulse
    times the mean of the half-step velocities before the step (vr0, vz0, V0)
    and after the contact, which is what the leapfrog kinetic energy sees.

    Returns (new V, normal impulse S on the projectile incl. friction, energy removed,
    number of nodes in contact, largest nodal normal force).
    """
    Zp = Zt + dt * V
    Lb = zeta[-1]
    K = zeta.size
    m_act = 0
    for n in range(n0, n1):  # the window's nodes (every other node is retired or not yet active)
        if nstate[n] >= 2:
            continue
        rp = r[n] + dt * vr[n]
        if rp >= rho_max:
            continue
        zp = z[n] + dt * vz[n]
        ze = Zp - zp
        if ze <= 0.0 or ze >= Lb:
            continue
        if on_axis[n]:
            g, nrm_r, nrm_z = ze, 0.0, 1.0
        else:
            k = np.searchsorted(zeta, ze, side="right") - 1
            if k >= K - 1:
                k = K - 2
            rs = rho[k] + (rho[k + 1] - rho[k]) * (ze - zeta[k]) / (zeta[k + 1] - zeta[k])
            if rp >= rs:
                continue
            dh = rs - rp
            best, pr, pz = dh, rs, ze
            kk = k
            while kk >= 0 and zeta[kk + 1] >= ze - best:
                kk -= 1
            kk = max(kk, 0)
            while kk < K - 1 and zeta[kk] <= ze + best:
                ar, az = rho[kk], zeta[kk]
                tr, tz = rho[kk + 1] - ar, zeta[kk + 1] - az
                L2 = tr * tr + tz * tz
                t = ((rp - ar) * tr + (ze - az) * tz) / L2 if L2 > 0.0 else 0.0
                t = min(max(t, 0.0), 1.0)
                cr, cz = ar + t * tr, az + t * tz
                d = math.sqrt((cr - rp) ** 2 + (cz - ze) ** 2)
                if d < best:
                    best, pr, pz = d, cr, cz
                kk += 1
            g = best
            if g <= 0.0:
                continue
            nrm_r, nrm_z = (pr - rp) / g, -(pz - ze) / g
        buf_i[m_act] = n
        buf[0, m_act] = g
        buf[1, m_act] = nrm_r
        buf[2, m_act] = nrm_z
        buf[3, m_act] = 1.0
        m_act += 1
    if m_act == 0:
        return V, 0.0, 0.0, 0, 0.0
    S = 0.0
    for it in range(50):
        num, den = 0.0, 1.0
        for a in range(m_act):
            if buf[3, a] > 0.0:
                m = mass[buf_i[a]]
                num += m * buf[0, a] * buf[2, a] / dt
                den += m * buf[2, a] * buf[2, a] / M
        S = num / den
        changed = False
        for a in range(m_act):
            if buf[3, a] > 0.0:
                lam = mass[buf_i[a]] * (buf[0, a] / dt - buf[2, a] * S / M)
                if lam < 0.0:
                    buf[3, a] = 0.0
                    changed = True
        if not changed:
            break
    V1 = V - S / M
    fmax = 0.0
    Sf = 0.0
    work = 0.0
    for a in range(m_act):
        n = buf_i[a]
        m = mass[n]
        ur, uz = vr[n], vz[n]
        if buf[3, a] > 0.0:
            lam = m * (buf[0, a] / dt - buf[2, a] * S / M)
            fmax = max(fmax, lam / dt)
            vr[n] += lam * buf[1, a] / m
            vz[n] += lam * buf[2, a] / m
            if mu_f > 0.0:
                tr, tz = -buf[2, a], buf[1, a]
                vt = vr[n] * tr + (vz[n] - V1) * tz
                jt = min(m * abs(vt), mu_f * lam)
                sg = 1.0 if vt > 0.0 else -1.0
                vr[n] -= sg * jt * tr / m
                vz[n] -= sg * jt * tz / m
                Sf -= sg * jt * tz
        work += m * ((vr[n] - ur) * 0.5 * (vr0[n] + vr[n]) + (vz[n] - uz) * 0.5 * (vz0[n] + vz[n]))
    V1 -= Sf / M
    work += M * (V1 - V) * 0.5 * (V0 + V1)
    return V1, S + Sf, -work, m_act, fmax
