"""A 1-D spherical cavity driven at constant wall speed, the independent reference of the FE level's driven HJC
cavity (``verification.driven_hjc_cavity``).

It shares nothing with the FE solver or with the cavity level (``penetration.cavity``): its own Lagrangian
spherical scheme and the independent HJC point model of ``hjc_reference``. Nodes at radii r_i carry the
velocities, zones the stresses; zone masses are fixed. Momentum: rho du/dt = d sigma_r/dr + 2 (sigma_r -
sigma_theta)/r, lumped on the nodes (half of each neighbouring zone). Kinematics exact in the volume: the
volumetric increment ln(V'/V) and the radial one ln(dr'/dr) of a zone, its hoop increment their difference
halved. Artificial viscosity in compressing zones q = rho (cq^2 du^2 + cl c |du|). The wall node moves at V,
the far node is held (the run ends before the elastic precursor reaches it).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .hjc_reference import K1, RHO0, SHEAR, constants, update


@njit(cache=True)
def _run(r, V, t_end, t_from, k, cfl, cq, cl):
    """March to t_end; returns the mean over t_from..t_end of the wall stress (compression positive) weighted by
    the wall area, and the number of steps."""
    n = r.size - 1
    rho0 = k[RHO0]
    c = math.sqrt((k[K1] + 4.0 * k[SHEAR] / 3.0) / rho0)   # the stiffest (fully dense) wave speed
    mass = np.empty(n)
    for j in range(n):
        mass[j] = rho0 * 4.0 * math.pi / 3.0 * (r[j + 1] ** 3 - r[j] ** 3)
    node_mass = np.zeros(n + 1)
    for j in range(n):
        node_mass[j] += 0.5 * mass[j]
        node_mass[j + 1] += 0.5 * mass[j]
    u = np.zeros(n + 1)
    u[0] = V
    s = np.zeros((n, 4))
    st = np.zeros((n, 5))
    q = np.zeros(n)
    de = np.zeros(4)
    t, num, den, steps = 0.0, 0.0, 0.0, 0
    while t < t_end:
        dt = 1e300
        for j in range(n):
            dt = min(dt, cfl * (r[j + 1] - r[j]) / (c + 2.0 * cq * cq * abs(min(u[j + 1] - u[j], 0.0))))
        dt = min(dt, t_end - t + 1e-15)
        # forces on the nodes from the zone stresses (sigma_r = s_rr - p - q, sigma_t = s_tt - p - q)
        for i in range(1, n):
            sr_l = s[i - 1, 0] - st[i - 1, 0] - q[i - 1]
            sr_r = s[i, 0] - st[i, 0] - q[i]
            st_l = s[i - 1, 2] - st[i - 1, 0] - q[i - 1]
            st_r = s[i, 2] - st[i, 0] - q[i]
            area = 4.0 * math.pi * r[i] ** 2
            # 2 (sigma_r - sigma_t)/r over the node's two half zones
            hoop = ((sr_l - st_l) * (r[i] ** 3 - r[i - 1] ** 3) + (sr_r - st_r) * (r[i + 1] ** 3 - r[i] ** 3)) \
                * 4.0 * math.pi / 3.0 / r[i]
            u[i] += dt * (area * (sr_r - sr_l) + hoop) / node_mass[i]
        u[0] = V
        u[n] = 0.0
        r_old = r.copy()
        for i in range(n + 1):
            r[i] += dt * u[i]
        for j in range(n):
            d_vol = math.log((r[j + 1] ** 3 - r[j] ** 3) / (r_old[j + 1] ** 3 - r_old[j] ** 3))
            d_rad = math.log((r[j + 1] - r[j]) / (r_old[j + 1] - r_old[j]))
            d_hoop = 0.5 * (d_vol - d_rad)
            de[0], de[1], de[2], de[3] = d_rad, d_hoop, d_hoop, 0.0
            mu = rho0 * 4.0 * math.pi / 3.0 * (r[j + 1] ** 3 - r[j] ** 3)
            mu = mass[j] / mu - 1.0
            rate = abs(d_rad - d_hoop) * 2.0 / 3.0 / dt
            update(s[j], st[j], de, mu, rate, k)
            du = u[j + 1] - u[j]
            rho = rho0 * (1.0 + mu)
            q[j] = rho * (cq * cq * du * du + cl * c * abs(du)) if du < 0.0 else 0.0
        t += dt
        steps += 1
        if t > t_from:
            a2 = r[0] ** 2
            num += dt * a2 * (st[0, 0] + q[0] - s[0, 0])
            den += dt * a2
    return num / den, steps


def wall_stress(material, V, a0, t_end, t_from, r_out=1.0, zones=400, cfl=0.4, cq=1.5, cl=0.06):
    """Mean radial stress on a spherical cavity wall (Pa, compression positive, weighted by the wall area) over
    t_from..t_end, the wall moving out at V from radius a0 at t = 0 in ``material`` (an hjc.HJC) at rest;
    geometric zones from a0 to r_out."""
    r = a0 * np.geomspace(1.0, r_out / a0, zones + 1)
    value, _ = _run(r, float(V), float(t_end), float(t_from), constants(material), cfl, cq, cl)
    return float(value)

