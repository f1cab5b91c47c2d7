"""The axisymmetric quadrilateral: geometry, kinematics, the work of a stress update, and its nodal forces.

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

Strain rate and spin come from the half-step geometry; the deviatoric stress
is rotated by the spin angle (Jaumann, Cayley's exact in-plane rotation).

Hourglass: Flanagan-Belytschko viscous form; the hourglass shape vector is
orthogonal to every linear velocity field (patch test) and the coefficient
QH rho c V/sqrt(A) uses the bulk wave speed, so it stays active where the
material has lost its shear strength.

Every helper here is compiled inline into the element pass's row loops (``fe.element_pass``); corner values are
4-tuples in the element's counter-clockwise order (nodes (i, j), (i+1, j), (i+1, j+1), (i, j+1)).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .state import FAST, LIVE, MASS, P, QV, S_C, S_HG, S_LC, SIXTH, SRR, SRZ, STT, SZZ, THIRD, TWO_PI, VR, VZ

_ONE = np.uint64(1)


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def corners(a, k, n1, n4):
    """The four corner values of row k of a node array (positions X or velocities V) for an element whose corner 1
    is node n1 and corner 4 node n4."""
    return a[k, n1], a[k, n1 + _ONE], a[k, n4 + _ONE], a[k, n4]


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def moment(r1, r2, r3, r4, z1, z2, z3, z4):
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


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def rates(r, z, u, w):
    """Strain rate (rr, zz, tt, rz), spin and W of the quad at corners (r, z) moving with velocities (u, w); the
    hoop rate (1/W) sum (dW/dr_I - W b_rI) v_rI is consistent with the exact volume (= alpha for v_r = alpha r)."""
    r1, r2, r3, r4 = r
    z1, z2, z3, z4 = z
    u1, u2, u3, u4 = u
    w1, w2, w3, w4 = w
    ih = 1.0 / area2(r, z)
    br1, br2 = (z2 - z4) * ih, (z3 - z1) * ih
    bz1, bz2 = (r4 - r2) * ih, (r1 - r3) * ih
    drr = br1 * (u1 - u3) + br2 * (u2 - u4)
    dzz = bz1 * (w1 - w3) + bz2 * (w2 - w4)
    dvr_dz = bz1 * (u1 - u3) + bz2 * (u2 - u4)
    dvz_dr = br1 * (w1 - w3) + br2 * (w2 - w4)
    W, h1, h2, h3, h4 = moment(r1, r2, r3, r4, z1, z2, z3, z4)
    dtt = (h1 * u1 + h2 * u2 + h3 * u3 + h4 * u4) / W - drr
    return drr, dzz, dtt, 0.5 * (dvr_dz + dvz_dr), 0.5 * (dvr_dz - dvz_dr), W


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def area2(r, z):
    """Twice the area of the quad."""
    r1, r2, r3, r4 = r
    z1, z2, z3, z4 = z
    return (r3 - r1) * (z4 - z2) + (r2 - r4) * (z3 - z1)


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def corner_jacobians(r, z):
    """Twice the areas of the quad's four corner triangles (corners counter-clockwise): all positive for a convex
    quad, one <= 0 once a corner folds."""
    r1, r2, r3, r4 = r
    z1, z2, z3, z4 = z
    return ((r2 - r1) * (z4 - z1) - (z2 - z1) * (r4 - r1), (r3 - r2) * (z1 - z2) - (z3 - z2) * (r1 - r2),
            (r4 - r3) * (z2 - z3) - (z4 - z3) * (r2 - r3), (r1 - r4) * (z3 - z4) - (z1 - z4) * (r3 - r4))


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def sound_shape(r, z, rh, zh):
    """Whether the quad is valid now (corners r, z) and at the half step (rh, zh): positive area at both, every
    corner Jacobian positive now, off the axis (a positive radius sum) at both."""
    r1, r2, r3, r4 = r
    c1, c2, c3, c4 = corner_jacobians(r, z)
    return ((area2(rh, zh) > 0.0) & (area2(r, z) > 0.0) & (min(min(c1, c2), min(c3, c4)) > 0.0)
            & (r1 + r2 + r3 + r4 > 0.0) & (rh[0] + rh[1] + rh[2] + rh[3] > 0.0))


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def length(r, z):
    """The element's one length for viscosity, hourglass and time step: area over the longest side."""
    r1, r2, r3, r4 = r
    z1, z2, z3, z4 = z
    s12 = (r2 - r1) ** 2 + (z2 - z1) ** 2
    s23 = (r3 - r2) ** 2 + (z3 - z2) ** 2
    s34 = (r4 - r3) ** 2 + (z4 - z3) ** 2
    s41 = (r1 - r4) ** 2 + (z1 - z4) ** 2
    return 0.5 * area2(r, z) / math.sqrt(max(max(s12, s23), max(s34, s41)))


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def rotate(s0, s1, s3, spin, dt):
    """The in-plane deviator (rr, zz, rz) rotated by the spin over dt: Cayley (Hughes-Winget), orthogonal, angle
    2 atan(spin dt) = 2 spin dt + O(dt^3). The hoop component is out of the plane and keeps its value."""
    th = spin * dt
    den = 1.0 / (1.0 + th * th)
    cs, sn = (1.0 - th * th) * den, 2.0 * th * den
    am, dm = 0.5 * (s0 + s1), 0.5 * (s0 - s1)
    dn = dm * cs + s3 * sn
    return am + dn, am - dn, s3 * cs - dm * sn


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def equivalent_rate(drr, dzz, dtt, drz, tv):
    """Equivalent deviatoric strain rate sqrt(2/3 d':d') of the rate (rr, zz, tt, rz) with trace tv."""
    tv3 = tv * THIRD
    dev0, dev1, dev2 = drr - tv3, dzz - tv3, dtt - tv3
    return math.sqrt(2.0 / 3.0 * (dev0 * dev0 + dev1 * dev1 + dev2 * dev2 + 2.0 * drz * drz))


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def energy_increment(Vh, old, new, de, q_old, q_new, tv, dt):
    """Internal energy gained over a step: the mean of the old and new stress (deviator and pressure:
    (s_rr, s_zz, s_tt, s_rz, p)) on the strain increment de = (rr, zz, tt, rz), with the bulk viscosity's work at
    the mean of its old and new value (time-centred like the stress: the forces that did work over the step came
    from the old q; booking the new one alone gains a fixed share of the energy every shock processes), on the
    half-step volume Vh."""
    so0, so1, so2, so3, po = old
    n0, n1, n2, n3, pn = new
    de0, de1, de2, de3 = de
    return Vh * (0.5 * ((so0 - po + n0 - pn) * de0 + (so1 - po + n1 - pn) * de1 + (so2 - po + n2 - pn) * de2)
                 + (so3 + n3) * de3 - 0.5 * (q_old + q_new) * tv * dt)


@njit(cache=True, inline="always", error_model="numpy", fastmath=FAST)
def row_forces(j, nr, X, V, E, F, alive, qh, dt, S):
    """The internal and hourglass forces of every element of row j at the new geometry into elems.F (the node pass
    reads only live elements' forces), each element's hourglass work into S[S_HG]; returns the row's hourglass
    work over its live elements (the scratch S holds each element's wave speed and length)."""
    un = np.uint64(nr)
    b = np.uint64(j) * (un + _ONE)
    e0 = np.uint64(j) * un
    for i in range(un):
        e = e0 + i
        n1 = b + i
        n4 = n1 + un + _ONE
        r1, r2, r3, r4 = corners(X, 0, n1, n4)
        z1, z2, z3, z4 = corners(X, 1, n1, n4)
        A2 = area2((r1, r2, r3, r4), (z1, z2, z3, z4))
        W, m1, m2, m3, m4 = moment(r1, r2, r3, r4, z1, z2, z3, z4)
        vol = TWO_PI * W
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
        f0 = vol * (b1r * (srr - stt) + b1z * sn3)
        f1 = vol * (b1z * szz + b1r * sn3)
        f2 = vol * (b2r * (srr - stt) + b2z * sn3)
        f3 = vol * (b2z * szz + b2r * sn3)
        # hourglass (Flanagan-Belytschko, viscous; qh = 0 switches it off)
        u1, u2, u3, u4 = corners(V, VR, n1, n4)
        w1, w2, w3, w4 = corners(V, VZ, n1, n4)
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
        S[S_HG, i] = (kr * qr + kz * qz) * dt if alive[e] == LIVE else 0.0
    # the hourglass work of the row, summed in order (a reduction inside the loop above would need
    # reassociation to vectorise, and reassociated sums differ between compilations)
    hg = 0.0
    for i in range(nr):
        hg += S[S_HG, i]
    return hg
