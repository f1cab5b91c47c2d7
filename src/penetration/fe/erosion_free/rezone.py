"""Rezoning of an erosion-free target: the mesh near the path is kept regular while the material flows through it.

Arbitrary Lagrangian-Eulerian in the operator-split form (Lagrangian steps, then now and then a rezone and a
remap; Benson, Comput. Methods Appl. Mech. Eng. 99, 1992):

1. **Rezone.** An interior node of the zone (off the tunnel wall, the struck face and the window's edge rows, its
   four elements live) whose elements have lost their shape (the smallest corner Jacobian below ``quality`` times
   the mean of the four; every node at ``quality`` 1) moves by ``weight`` of the way to the area-weighted mean of
   its four elements' centres: the volumetric smoothing of Walker & Yu's ALE for deep penetration (Acta Geotech.
   1, 2006) with the plane areas as weights (the revolved volumes would pull every node away from the axis). A move
   is limited to a quarter of the node's shortest edge, so that each face sweeps only into its two elements. A node
   of the struck face or of the tunnel wall slides along it (the polyline through it and its neighbours) toward
   the middle of its neighbours' arc, so the boundary keeps its place (the nose slides on the wall without friction,
   or nearly).
2. **Remap of the elements** by swept faces and donor cells (first order): each face's swept volume (exact for the
   axisymmetric volume, so the new volumes are the new geometry's) carries the donor's density, specific internal
   energy, stress and state variables. Mass and internal energy are conserved exactly; the reference volume
   V0 = m / rho0 follows the mass.
3. **Remap of the nodes**: nodal masses follow the elements' (m_e / 4 to each corner); a moved node takes the
   velocity at its new place from its four elements' velocity gradients. This is not exactly conservative: the
   kinetic energy and axial momentum it changes are returned, and the audit books them as the remap's terms.

What the nose throws out above the struck face (a lip of fully damaged concrete jetting up along the nose) is
ejected, not rezoned: before each rezone ``eject`` marks the elements above the face that have become thinner than
a share of the element size or nearly inverted, or that have flown farther than a set height above it (a length
of the shot, not of the mesh), and the guard those that invert between rezones; both are booked
as ejecta by ``fe.erosion_free.debris`` (no stress from then on, their mass and momentum kept on their nodes). An element
that loses its shape inside the target stops the run.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from ..element import area2, corner_jacobians, length as element_length, moment
from ..state import (ACTIVE, DMG, EPSEFF, EPSP, ERODING, IE, LIVE, MASS, MUMAX, MUP, QV, SRR, SRZ, STT, SZZ, TWO_PI, V0,
                    VR, VZ, P)

# the element fields carried per unit mass (IE is carried as specific energy, MASS is the conserved quantity)
CARRIED = np.array([SRR, SZZ, STT, SRZ, P, QV, MUMAX, MUP, DMG, EPSP, EPSEFF], np.int64)
# rezone's report (out): remapped kinetic energy lost, axial momentum lost, nodes moved, largest move / edge, elements
# marked for ejection by the last rezone, rezones
R_ENERGY, R_MOMENTUM, R_MOVED, R_LARGEST, R_EJECT, R_COUNT = range(6)


@njit(cache=True)
def _nodes_of(nr, e):
    i, j = e % nr, e // nr
    n1 = j * (nr + 1) + i
    return n1, n1 + 1, n1 + nr + 2, n1 + nr + 1


@njit(cache=True)
def _corners(X, nr, e):
    """Element e's corner coordinates (r1..r4), (z1..z4), counter-clockwise (``fe.element``'s tuples)."""
    a, b, c, d = _nodes_of(nr, e)
    return (X[0, a], X[0, b], X[0, c], X[0, d]), (X[1, a], X[1, b], X[1, c], X[1, d])


@njit(cache=True)
def _quality(X, nr, e):
    """Smallest corner Jacobian over their mean (1 for a parallelogram, <= 0 when inverted)."""
    r, z = _corners(X, nr, e)
    c1, c2, c3, c4 = corner_jacobians(r, z)
    s = c1 + c2 + c3 + c4
    return 4.0 * min(min(c1, c2), min(c3, c4)) / s if s > 0.0 else -1.0


@njit(cache=True)
def _area(X, nr, e):
    """Element e's area in the (r, z) plane."""
    r, z = _corners(X, nr, e)
    return 0.5 * area2(r, z)


@njit(cache=True)
def _volume(X, nr, e):
    r, z = _corners(X, nr, e)
    return TWO_PI * moment(r[0], r[1], r[2], r[3], z[0], z[1], z[2], z[3])[0]


@njit(cache=True)
def _swept(Xo, Xn, p, q):
    """Volume swept by the face p -> q (in an element's counter-clockwise order) moving from Xo to Xn: positive
    when the element grows."""
    return TWO_PI * moment(Xo[0, p], Xn[0, p], Xn[0, q], Xo[0, q], Xo[1, p], Xn[1, p], Xn[1, q], Xo[1, q])[0]


@njit(cache=True)
def _gradient(X, V, nr, e):
    """Velocity gradient (dvr/dr, dvr/dz, dvz/dr, dvz/dz) at element e's centre."""
    a, b, c, d = _nodes_of(nr, e)
    (r1, r2, r3, r4), (z1, z2, z3, z4) = _corners(X, nr, e)
    A2 = area2((r1, r2, r3, r4), (z1, z2, z3, z4))
    br1, br2 = (z2 - z4) / A2, (z3 - z1) / A2
    bz1, bz2 = (r4 - r2) / A2, (r1 - r3) / A2
    u1, u2, u3, u4 = V[VR, a], V[VR, b], V[VR, c], V[VR, d]
    w1, w2, w3, w4 = V[VZ, a], V[VZ, b], V[VZ, c], V[VZ, d]
    return (br1 * (u1 - u3) + br2 * (u2 - u4), bz1 * (u1 - u3) + bz2 * (u2 - u4),
            br1 * (w1 - w3) + br2 * (w2 - w4), bz1 * (w1 - w3) + bz2 * (w2 - w4))


@njit(cache=True)
def _slide(X, n, prev, nxt, weight):
    """Where boundary node n goes sliding along the boundary's polyline prev - n - nxt: ``weight`` of the way to the
    middle of the arc between its neighbours; (r, z, the move over the shorter side)."""
    l1 = np.sqrt((X[0, n] - X[0, prev]) ** 2 + (X[1, n] - X[1, prev]) ** 2)
    l2 = np.sqrt((X[0, nxt] - X[0, n]) ** 2 + (X[1, nxt] - X[1, n]) ** 2)
    s = l1 + weight * (0.5 * (l1 + l2) - l1)  # arc length from prev
    if s < l1:
        f = s / l1
        tr, tz = X[0, prev] + f * (X[0, n] - X[0, prev]), X[1, prev] + f * (X[1, n] - X[1, prev])
    else:
        f = (s - l1) / l2
        tr, tz = X[0, n] + f * (X[0, nxt] - X[0, n]), X[1, n] + f * (X[1, nxt] - X[1, n])
    return tr, tz, abs(s - l1) / min(l1, l2)


@njit(cache=True)
def _thin(X, nr, e, length):
    """Whether element e is thinner than ``length`` (its area over its longest side: ``fe.element.length``, the
    solver's own element length) or nearly inverted."""
    r, z = _corners(X, nr, e)
    return element_length(r, z) < length or _quality(X, nr, e) < 0.2


@njit(cache=True)
def eject(zone, X, alive, length, height, crater, out):
    """Mark for ejection (ERODING; ``fe.erosion_free.debris`` books them as ejecta) the live elements of the window's rows
    whose centre lies above the struck face (z < 0) and that are thinner than ``length`` or nearly inverted, or
    whose centre has flown more than ``height`` above it: the lip the nose throws out, which would otherwise set the
    time step. With ``crater`` > 0 (m), those thinner than ``length`` or nearly inverted whose centre lies less than
    ``crater`` below the face are ejected too: the crater's wall, thinning as it flows up and out behind the
    projectile. Returns how many."""
    nr, j0, j1, i_max = zone
    limit = max(crater, 0.0)
    count = 0
    for j in range(j0, j1):
        near = False
        for i in range(nr + 1):   # a row with no node above the limit has no element to eject
            if X[1, j * (nr + 1) + i] < limit or X[1, (j + 1) * (nr + 1) + i] < limit:
                near = True
                break
        if not near:
            continue
        for i in range(nr):
            e = j * nr + i
            if alive[e] != LIVE:
                continue
            a, b, c, d = _nodes_of(nr, e)
            zc = 0.25 * (X[1, a] + X[1, b] + X[1, c] + X[1, d])
            if zc < -height or (zc < limit and _thin(X, nr, e, length)):
                alive[e] = ERODING
                count += 1
    out[R_EJECT] = count
    return count


@njit(cache=True)
def rezone(zone, X, V, E, alive, nstate, mass, rho0, quality, weight, out):
    """One rezone and remap of the zone (nr, j0, j1, i_max): element columns i < i_max of the window's rows
    j0 <= j < j1 of a grid nr elements wide, material density rho0. Returns 0, or the element whose remapped mass
    would not be positive (nothing is changed then)."""
    nr, j0, j1, i_max = zone
    nrow = nr + 1
    nz = X.shape[1] // nrow - 1
    force = quality >= 1.0   # every node, whatever its elements' shape
    lo = max(j0 + 1, 1)
    # ---- 1. new positions (Jacobi: every target from the Lagrangian positions)
    moved = []
    targets = []
    largest = 0.0
    for j in range(lo, j1):
        for i in range(1, i_max):
            n = j * nrow + i
            if nstate[n] != ACTIVE:
                continue
            ea, eb, ec, ed = j * nr + i, j * nr + i - 1, (j - 1) * nr + i - 1, (j - 1) * nr + i
            if not (alive[ea] == LIVE and alive[eb] == LIVE and alive[ec] == LIVE and alive[ed] == LIVE):
                continue
            qmin = min(min(_quality(X, nr, ea), _quality(X, nr, eb)), min(_quality(X, nr, ec), _quality(X, nr, ed)))
            if qmin >= quality and not force:
                continue
            sv, sr, sz = 0.0, 0.0, 0.0
            for e in (ea, eb, ec, ed):
                v = _area(X, nr, e)
                p, q, s, t = _nodes_of(nr, e)
                sv += v
                sr += v * 0.25 * (X[0, p] + X[0, q] + X[0, s] + X[0, t])
                sz += v * 0.25 * (X[1, p] + X[1, q] + X[1, s] + X[1, t])
            dr, dz = weight * (sr / sv - X[0, n]), weight * (sz / sv - X[1, n])
            edge = 1e300
            for m in (n - 1, n + 1, n - nrow, n + nrow):
                edge = min(edge, (X[0, m] - X[0, n]) ** 2 + (X[1, m] - X[1, n]) ** 2)
            edge = np.sqrt(edge)
            step = np.sqrt(dr * dr + dz * dz)
            if step > 0.25 * edge:
                dr, dz = dr * 0.25 * edge / step, dz * 0.25 * edge / step
                step = 0.25 * edge
            largest = max(largest, step / edge)
            moved.append(n)
            targets.append((X[0, n] + dr, X[1, n] + dz))
    if j0 == 0:   # the struck face: a node slides along it
        for i in range(1, i_max):
            if nstate[i] == ACTIVE and alive[i] == LIVE and alive[i - 1] == LIVE and (
                    force or min(_quality(X, nr, i), _quality(X, nr, i - 1)) < quality):
                tr, tz, ratio = _slide(X, i, i - 1, i + 1, weight)
                largest = max(largest, ratio)
                moved.append(i)
                targets.append((tr, tz))
    for j in range(lo, j1):   # the tunnel wall: a node slides along it (the nose is frictionless or nearly)
        n = j * nrow
        ea, ed = j * nr, (j - 1) * nr
        if nstate[n] == ACTIVE and alive[ea] == LIVE and alive[ed] == LIVE and (
                force or min(_quality(X, nr, ea), _quality(X, nr, ed)) < quality):
            tr, tz, ratio = _slide(X, n, n - nrow, n + nrow, weight)
            largest = max(largest, ratio)
            moved.append(n)
            targets.append((tr, tz))
    if len(moved) == 0:
        return 0
    # ---- 2. remap of the elements
    e_lo, e_hi = j0 * nr, j1 * nr
    ne = e_hi - e_lo
    Xn = X.copy()  # new positions (the whole array: simple indexing; the zone is most of the window anyway)
    for k in range(len(moved)):
        Xn[0, moved[k]], Xn[1, moved[k]] = targets[k]
    dm = np.zeros(ne)
    dphi = np.zeros((CARRIED.size, ne))
    die = np.zeros(ne)
    for j in range(j0, j1):
        for i in range(i_max):
            e = j * nr + i
            if alive[e] != LIVE:
                continue
            n1, n2, n3, n4 = _nodes_of(nr, e)
            for face in range(2):
                if face == 0:     # the face to element (i-1, j): edge n4 -> n1
                    if i == 0:
                        continue
                    other = e - 1
                    s = _swept(X, Xn, n4, n1)
                else:             # the face to element (i, j-1): edge n1 -> n2
                    if j == j0:
                        continue
                    other = e - nr
                    s = _swept(X, Xn, n1, n2)
                if s == 0.0 or alive[other] != LIVE:
                    continue
                donor, taker = (other, e) if s > 0.0 else (e, other)
                md = E[MASS, donor] / _volume(X, nr, donor) * abs(s)
                dm[taker - e_lo] += md
                dm[donor - e_lo] -= md
                for k in range(CARRIED.size):
                    f = CARRIED[k]
                    dphi[k, taker - e_lo] += md * E[f, donor]
                    dphi[k, donor - e_lo] -= md * E[f, donor]
                spec = E[IE, donor] / E[MASS, donor]
                die[taker - e_lo] += md * spec
                die[donor - e_lo] -= md * spec
    for k in range(ne):
        if dm[k] != 0.0 and E[MASS, e_lo + k] + dm[k] <= 0.0:
            return e_lo + k
    # ---- 3. nodes: kinetic energy and momentum before, velocities at the new places, masses after
    ke0, pz0 = 0.0, 0.0
    touched = np.zeros(X.shape[1], np.bool_)
    for k in range(ne):
        if dm[k] != 0.0:
            for n in _nodes_of(nr, e_lo + k):
                touched[n] = True
    for n in moved:
        touched[n] = True
    idx = np.flatnonzero(touched)
    for n in idx:
        ke0 += 0.5 * mass[n] * (V[VR, n] ** 2 + V[VZ, n] ** 2)
        pz0 += mass[n] * V[VZ, n]
    vnew = np.empty((2, len(moved)))
    for k in range(len(moved)):
        n = moved[k]
        i, j = n % nrow, n // nrow
        g0, g1, g2, g3, sw = 0.0, 0.0, 0.0, 0.0, 0.0
        for di, dj in ((0, 0), (-1, 0), (-1, -1), (0, -1)):   # the node's elements (two on a boundary)
            ie, je = i + di, j + dj
            if ie < 0 or ie >= nr or je < 0 or je >= nz:
                continue
            e = je * nr + ie
            if alive[e] != LIVE:
                continue
            w = _volume(X, nr, e)
            a, b, c, d = _gradient(X, V, nr, e)
            g0 += w * a
            g1 += w * b
            g2 += w * c
            g3 += w * d
            sw += w
        dr, dz = Xn[0, n] - X[0, n], Xn[1, n] - X[1, n]
        vnew[0, k] = V[VR, n] + (g0 * dr + g1 * dz) / sw
        vnew[1, k] = V[VZ, n] + (g2 * dr + g3 * dz) / sw
    for k in range(len(moved)):
        n = moved[k]
        X[0, n], X[1, n] = Xn[0, n], Xn[1, n]
        V[VR, n], V[VZ, n] = vnew[0, k], vnew[1, k]
    for k in range(ne):
        if dm[k] == 0.0:
            continue
        e = e_lo + k
        m_old = E[MASS, e]
        m_new = m_old + dm[k]
        for c in range(CARRIED.size):
            f = CARRIED[c]
            E[f, e] = (m_old * E[f, e] + dphi[c, k]) / m_new
        E[IE, e] += die[k]
        E[MASS, e] = m_new
        E[V0, e] = m_new / rho0
        for n in _nodes_of(nr, e):
            mass[n] += 0.25 * dm[k]
    ke1, pz1 = 0.0, 0.0
    for n in idx:
        ke1 += 0.5 * mass[n] * (V[VR, n] ** 2 + V[VZ, n] ** 2)
        pz1 += mass[n] * V[VZ, n]
    out[R_ENERGY] += ke0 - ke1
    out[R_MOMENTUM] += pz0 - pz1
    out[R_MOVED] += len(moved)
    out[R_LARGEST] = max(out[R_LARGEST], largest)
    out[R_COUNT] += 1.0
    return 0
