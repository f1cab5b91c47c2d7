"""The rigid projectile and its kinematic contact with the target's nodes.

``Projectile``: an axisymmetric rigid body given by its outline (zeta behind the tip, rho), mass, tip position and
velocity (+z into the target) and a Coulomb friction coefficient. ``contact`` moves the nodes whose predicted
positions lie inside the body onto its surface by impulses shared with the projectile (perfectly inelastic: the
energy they remove is booked as the contact's work).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .state import B_FRICTION, B_MASS, B_TIP, B_VELOCITY, DROPPED


@dataclass
class Projectile:
    """Rigid axisymmetric projectile: outline (zeta behind the tip, rho), mass, tip position Zt and velocity V (+z)."""
    zeta: np.ndarray
    rho: np.ndarray
    mass: float
    Zt: float = 0.0
    V: float = 0.0
    friction: float = 0.0
    rest_velocity: float = 0.1  # m/s: at rest once V falls to this (a projectile held by the target creeps towards 0)


@njit(cache=True)
def contact(span, nodes, body, proj, dt):
    """Kinematic contact of the window's target nodes with the rigid projectile (state proj: tip at z = Zt, moving
    +z at V, mass M, friction coefficient mu_f; outline body).

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
    r, z, vr, vz, vr0, vz0, mass, nstate, on_axis = nodes
    zeta, rho, rho_max, buf_i, buf = body
    Zt, V, M, mu_f = proj[B_TIP], proj[B_VELOCITY], proj[B_MASS], proj[B_FRICTION]
    V0 = V
    n0, n1 = span.j0 * (span.nr + 1), (span.j1 + 1) * (span.nr + 1)
    Zp = Zt + dt * V
    Lb = zeta[-1]
    K = zeta.size
    m_act = 0
    for n in range(n0, n1):  # the window's nodes (every other node is retired or not yet active)
        if nstate[n] >= DROPPED:
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
