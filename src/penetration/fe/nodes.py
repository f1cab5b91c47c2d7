"""The node pass: forces gathered from the elements, boundary dashpots, fixities, new velocities; and the move.

Node (i, j) of the grid gathers the corner forces of its (up to) four elements: (i, j) whose corner 1 it is,
(i-1, j) corner 2, (i-1, j-1) corner 3 and (i, j-1) corner 4 (``gather``, the one force gather of the solver).
Its velocity is updated by the central-difference step from v^{n-1/2} to v^{n+1/2} (``new_velocity``, the one node
update), with a non-reflecting (Lysmer) dashpot where the node has one and its fixity.

Boundary.fix[n]: FIX_R holds v_r = 0 (axis, roller), FIX_Z holds v_z = 0. Boundary.dash[:, n] = (area, n_r, n_z):
the dashpot on the node's share of the boundary, traction -rho c_p v_n n - rho c_s v_t, taken at the mean of the
old and new velocity;
rowdash[j] = 1 where a node of row j off the grid's edges has one (the interior nodes of the other rows pass a
zero area, which the compiler folds away). Rows.f[RF_POWER, j]: power the dashpots absorb, Rows.f[RF_IMPULSE, j]:
their axial force, per node row. The rows VR0, VZ0 of V receive the velocities before the update (for the contact's work).
Dropped nodes keep their velocity.
"""
from __future__ import annotations

import numpy as np
from numba import njit, prange

from .state import A_EXTERNAL, DROPPED, FIX_R, FIX_Z, LIVE, RF_IMPULSE, RF_POWER, ROWS_PER_CHUNK, VR, VR0, VZ, VZ0

_ONE = np.uint64(1)


@njit(cache=True, inline="always", error_model="numpy")
def _corner(F, alive, k, e):
    """Force row k of element e if the element is live, else 0: the one place an element's force is read."""
    return F[k, e] if alive[e] == LIVE else 0.0


@njit(cache=True, inline="always", error_model="numpy")
def gather(F, alive, ea, eb, ec, ed):
    """Force on an interior node from its four elements: ea (the node is its corner 1), eb (corner 2), ec (corner
    3), ed (corner 4)."""
    fr = _corner(F, alive, 0, ea) + _corner(F, alive, 2, eb) + _corner(F, alive, 4, ec) + _corner(F, alive, 6, ed)
    fz = _corner(F, alive, 1, ea) + _corner(F, alive, 3, eb) + _corner(F, alive, 5, ec) + _corner(F, alive, 7, ed)
    return fr, fz


@njit(cache=True, inline="always", error_model="numpy")
def new_velocity(ur, uz, fr, fz, m, dtv, fx, da, nr_, nz_, zp, zs):
    """A node's new velocity from its force, its dashpot (area da > 0, normal (nr_, nz_); impedances zp, zs) and its
    fixity fx, without branches; returns (v_r, v_z, power absorbed by the dashpot, its axial force)."""
    ur0, uz0 = ur, uz
    ur = ur - dtv * fr / m
    uz = uz - dtv * fz / m
    # dashpot at the mean of the old and new velocity (trapezoidal, second order in the step; A-stable: its
    # amplification (1 - b/2)/(1 + b/2), b = dtv Z da/m, stays in [-1, 1] for any damping, where an explicit dashpot
    # at the wave impedance needs a smaller step and a backward-Euler one reflects at first order), per direction:
    # v' = (v* - b/2 v_old)/(1 + b/2); its work is the impulse times the mean of the old and new velocities
    vn = ur * nr_ + uz * nz_
    vn0 = ur0 * nr_ + uz0 * nz_
    tr_, tz_ = ur - vn * nr_, uz - vn * nz_
    tr0, tz0 = ur0 - vn0 * nr_, uz0 - vn0 * nz_
    hp = 0.5 * dtv * zp * da / m
    hs = 0.5 * dtv * zs * da / m
    vn1 = (vn - hp * vn0) / (1.0 + hp)
    ur1 = vn1 * nr_ + (tr_ - hs * tr0) / (1.0 + hs)
    uz1 = vn1 * nz_ + (tz_ - hs * tz0) / (1.0 + hs)
    ir = m * (ur1 - ur)  # impulse of the dashpot
    iz = m * (uz1 - uz)
    dashed = da > 0.0
    pw = (ir * 0.5 * (ur0 + ur1) + iz * 0.5 * (uz0 + uz1)) / dtv if dashed else 0.0
    fb = iz / dtv if dashed else 0.0
    ur = ur1 if dashed else ur
    uz = uz1 if dashed else uz
    ur = 0.0 if (fx & FIX_R) != 0 else ur
    uz = 0.0 if (fx & FIX_Z) != 0 else uz
    return ur, uz, pw, fb


@njit(cache=True, inline="always", error_model="numpy")
def _update(n, i, fr, fz, V, m, fx, keep, dtv, dash, Z, W):
    """Node n's new velocity into V (its old one into the VR0, VZ0 rows; a node not kept keeps its velocity) from
    its force, mass m, fixity fx, dashpot (area, n_r, n_z) and the impedances Z = (zp, zs); its dashpot's power and
    axial force into W[:, i]."""
    ur, uz = V[VR, n], V[VZ, n]
    da, nr_, nz_ = dash
    zp, zs = Z
    u1, w1, pw, fb = new_velocity(ur, uz, fr, fz, m, dtv, fx, da, nr_, nz_, zp, zs)
    V[VR0, n] = ur
    V[VZ0, n] = uz
    V[VR, n] = u1 if keep else ur
    V[VZ, n] = w1 if keep else uz
    W[0, i] = pw if keep else 0.0
    W[1, i] = fb if keep else 0.0


@njit(cache=True, inline="always", error_model="numpy")
def _edge_force(i, j, nr, nz, F, alive):
    """The force on node (i, j) on an edge of a grid of nr x nz elements: the elements of the interior gather that
    exist, each index computed under its test (so that no absent element's index is formed: with the tests as
    flags of the interior gather, the node pass ran twice as slow)."""
    fr = 0.0
    fz = 0.0
    if i < nr and j < nz:
        e = j * nr + i
        fr += _corner(F, alive, 0, e)
        fz += _corner(F, alive, 1, e)
    if i > 0 and j < nz:
        e = j * nr + i - 1
        fr += _corner(F, alive, 2, e)
        fz += _corner(F, alive, 3, e)
    if i > 0 and j > 0:
        e = (j - 1) * nr + i - 1
        fr += _corner(F, alive, 4, e)
        fz += _corner(F, alive, 5, e)
    if i < nr and j > 0:
        e = (j - 1) * nr + i
        fr += _corner(F, alive, 6, e)
        fz += _corner(F, alive, 7, e)
    return fr, fz


@njit(parallel=True, cache=True, error_model="numpy")
def node_pass(span, F, alive, mass, state, fix, dash, rowdash, Z, dtv, V, rf):
    """Gather the element forces F (internal + hourglass) of live elements, add boundary dashpots (dash, rowdash;
    impedances Z = (zp, zs)), apply fixities, and update the velocities V of the node rows span.j0 <= j <= span.j1
    by dtv; each row's dashpot power and axial force into rf (Rows.f; see the module's docstring). Interior nodes of
    a row go through a branch-free (vectorised) loop, with unsigned indices as in the element pass; nodes on the
    grid's edges one by one. Nodes whose state is DROPPED or beyond keep their velocity."""
    nr, nz, j0, j1 = span.nr, span.nz, span.j0, span.j1
    nchunk = (j1 - j0 + 1 + ROWS_PER_CHUNK - 1) // ROWS_PER_CHUNK
    for ch in prange(nchunk):
        W = np.empty((2, nr + 1))
        for j in range(j0 + ch * ROWS_PER_CHUNK, min(j1 + 1, j0 + (ch + 1) * ROWS_PER_CHUNK)):
            base = j * (nr + 1)
            for i in range(0, nr + 1, 1 if j == 0 or j == nz else nr):   # the nodes on the grid's edges
                n = base + i
                fr, fz = _edge_force(i, j, nr, nz, F, alive)
                _update(n, i, fr, fz, V, mass[n], fix[n], state[n] < DROPPED, dtv, (dash[0, n], dash[1, n], dash[2, n]),
                        Z, W)
            if j != 0 and j != nz:
                un = np.uint64(nr)
                ub = np.uint64(base)
                ue = np.uint64(j) * un
                if rowdash[j] != 0:
                    for i in range(_ONE, un):
                        ea = ue + i
                        fr, fz = gather(F, alive, ea, ea - _ONE, ea - _ONE - un, ea - un)
                        n = ub + i
                        _update(n, i, fr, fz, V, mass[n], fix[n], state[n] < DROPPED, dtv,
                                (dash[0, n], dash[1, n], dash[2, n]), Z, W)
                else:
                    for i in range(_ONE, un):
                        ea = ue + i
                        fr, fz = gather(F, alive, ea, ea - _ONE, ea - _ONE - un, ea - un)
                        n = ub + i
                        _update(n, i, fr, fz, V, mass[n], fix[n], state[n] < DROPPED, dtv, (0.0, 0.0, 0.0), Z, W)
            pw = 0.0
            fb = 0.0
            for i in range(nr + 1):
                pw -= W[0, i]
                fb += W[1, i]
            rf[RF_POWER, j] = pw
            rf[RF_IMPULSE, j] = fb


@njit(cache=True)
def guide(span, nodes, radius, dt):
    """The pilot hole's rigid frictionless guide: a node of the hole's wall (column 0) that would move inside the
    radius ``radius`` in this step is stopped on it (its radial velocity set so that it lands at the radius; a
    perfectly inelastic radial impulse, no axial one). Returns the kinetic energy removed."""
    if radius <= 0.0:
        return 0.0
    loss = 0.0
    vr, r, m, state = nodes.vr, nodes.r, nodes.mass, nodes.state
    for j in range(span.j0, span.j1 + 1):
        n = j * (span.nr + 1)
        if state[n] < DROPPED and r[n] + dt * vr[n] < radius:
            v1 = (radius - r[n]) / dt
            loss += 0.5 * m[n] * (vr[n] * vr[n] - v1 * v1)
            vr[n] = v1
    return loss


@njit(parallel=True, cache=True)
def move(span, X, V, state, dt):
    """x += dt v for the window's nodes (positions X, rows r and z) that are not dropped (every node outside the
    window's node rows is retired or not yet active)."""
    n0 = span.j0 * (span.nr + 1)
    n1 = (span.j1 + 1) * (span.nr + 1)
    for k in prange(n1 - n0):
        n = n0 + k
        if state[n] < DROPPED:
            X[0, n] += dt * V[VR, n]
            X[1, n] += dt * V[VZ, n]


@njit(cache=True)
def external(nodes, loads, dtv, acc):
    """Constant external nodal forces and prescribed velocities after the node pass; their work into
    acc[A_EXTERNAL]."""
    vr, vz, mass = nodes.vr, nodes.vz, nodes.mass
    for a in range(loads.load_i.size):
        n = loads.load_i[a]
        vr[n] += dtv * loads.load_f[0, a] / mass[n]
        vz[n] += dtv * loads.load_f[1, a] / mass[n]
        if nodes.on_axis[n]:
            vr[n] = 0.0
        acc[A_EXTERNAL] += dtv * (loads.load_f[0, a] * 0.5 * (nodes.vr0[n] + vr[n])
                                  + loads.load_f[1, a] * 0.5 * (nodes.vz0[n] + vz[n]))
    for a in range(loads.presc_i.size):
        n = loads.presc_i[a]
        acc[A_EXTERNAL] += mass[n] * ((loads.presc_v[0, a] - vr[n]) * loads.presc_v[0, a]
                                      + (loads.presc_v[1, a] - vz[n]) * loads.presc_v[1, a])
        vr[n] = loads.presc_v[0, a]
        vz[n] = loads.presc_v[1, a]
