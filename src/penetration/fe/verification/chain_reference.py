"""A 1-D lumped-mass chain: an independent discrete reference for the FE level's bar and boundary problems.

Written apart from the FE kernels: n elements of length h along a bar of section A, node masses rho A h (half at
the ends), central differences in time (velocities at half steps), uniaxial stress sigma = E ln(l/h) in each
element plus the FE level's bulk viscosity q = rho l (Q1^2 l d^2 - Q2 c d) where the strain rate d < 0, the
stable step f l/(Q + sqrt(Q^2 + c^2)), Q = Q2 c + Q1^2 l |d|, growing by at most 1.2 a step. Ends: free, a
rigid wall the first node cannot pass (perfectly inelastic, as the FE level's kinematic contact), or a Lysmer
dashpot of impedance rho c A on the last node, taken implicitly in the new velocity (v' = v*/(1 + dt Z/m), as
the FE node pass does) or centred (trapezoidal). The chain shows what the discretisation alone does to the
continuum answer: a rebound below the impact speed, a reflection off the dashpot.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def _march(u, v, m, bar, controls, t_end, wall, dashpot):
    """Advance displacements u and half-step velocities v (nodal masses m) of the bar (cell length h, modulus E,
    density rho, wave speed c, area A) to t_end, with the viscosity and step controls (q1, q2, Courant factor f).
    wall: the first node stays at u >= its start (a rigid face behind it); dashpot 0 none, 1 implicit, 2 centred on
    the last node. Returns the time the wall last pushed and the impulse it gave (N s, towards +x)."""
    h, E, rho, c, A = bar
    q1, q2, f = controls
    n = u.size - 1
    t, dt_old, last_push, impulse = 0.0, 0.0, -1.0, 0.0
    d = np.zeros(n)
    force = np.zeros(n + 1)
    Z = rho * c * A
    while t < t_end:
        dt = 1e300
        for j in range(n):
            l = h + u[j + 1] - u[j]
            Q = q2 * c + q1 * q1 * l * max(-d[j], 0.0)
            dt = min(dt, f * l / (Q + math.sqrt(Q * Q + c * c)))
        if dt_old > 0.0:
            dt = min(dt, 1.2 * dt_old)
        dt = min(dt, t_end - t)
        dtv = dt if dt_old == 0.0 else 0.5 * (dt + dt_old)
        for i in range(n + 1):
            v[i] += dtv * force[i] / m[i]
        if dashpot == 1:
            v[n] = v[n] / (1.0 + dtv * Z / m[n])
        elif dashpot == 2:
            vs = v[n] - dtv * force[n] / m[n]           # the velocity before this step's force
            v[n] = (vs * (1.0 - 0.5 * dtv * Z / m[n]) + dtv * force[n] / m[n]) / (1.0 + 0.5 * dtv * Z / m[n])
        if wall and u[0] + dt * v[0] < 0.0:
            target = -u[0] / dt
            impulse += m[0] * (target - v[0])
            v[0] = target
            last_push = t + dt
        for j in range(n):
            l_old = h + u[j + 1] - u[j]
            l_new = l_old + dt * (v[j + 1] - v[j])
            d[j] = math.log(l_new / l_old) / dt
        for i in range(n + 1):
            u[i] += dt * v[i]
        for i in range(n + 1):
            force[i] = 0.0
        for j in range(n):
            l = h + u[j + 1] - u[j]
            s = E * math.log(l / h)
            if d[j] < 0.0:
                s -= rho * (h / l) * l * (q1 * q1 * l * d[j] * d[j] - q2 * c * d[j])
            force[j] += s * A          # tension pulls the left node right: f[i] is the force on node i
            force[j + 1] -= s * A
        t += dt
        dt_old = dt
    return last_push, impulse


def masses(n, h, rho, A):
    m = np.full(n + 1, rho * A * h)
    m[0] = m[-1] = 0.5 * rho * A * h
    return m


def bar_on_wall(n, length, v, E, rho, t_end, q1=1.5, q2=0.06, f=0.9, area=1.0):
    """A free bar of n elements moving at -v onto a rigid wall at its first node: (rebound speed = the mean
    velocity at t_end, time the contact ends)."""
    h = length / n
    u, vel = np.zeros(n + 1), np.full(n + 1, -v)
    m = masses(n, h, rho, area)
    end, _ = _march(u, vel, m, (h, E, rho, math.sqrt(E / rho), area), (q1, q2, f), t_end, True, 0)
    return float(np.sum(m * vel) / np.sum(m)), end


def dashpot_reflection(per_pulse, courant=0.9, centred=False):
    """Reflected amplitude over incident of a sin^2 velocity pulse ``per_pulse`` elements wide meeting the
    dashpot end of the chain at normal incidence (no viscosity): the chain against a chain twice as long,
    compared when the pulse has entered the dashpot."""
    h, E, rho, amp = 1.0, 1.0, 1.0, 1e-4    # a small amplitude: the strain amp/c stays linear
    w, x1 = per_pulse * h, 10.0 * h
    n = int(x1 + w + 40 * h)
    t_end = (n * h - x1) + 15.0 * h

    def run(nodes, dashpot):
        x = np.arange(nodes + 1) * h
        s = np.clip((x - x1) / w, 0.0, 1.0)
        vel = amp * np.sin(np.pi * s) ** 2
        u = amp * 0.5 * w * (1.0 - (s - np.sin(2.0 * np.pi * s) / (2.0 * np.pi)))   # the right-going wave's u
        _march(u, vel, masses(nodes, h, rho, 1.0), (h, E, rho, 1.0, 1.0), (0.0, 0.0, courant), t_end, False, dashpot)
        return vel

    return float(np.abs(run(n, 2 if centred else 1) - run(2 * n, 0)[:n + 1]).max()) / amp
