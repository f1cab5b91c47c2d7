"""A 1-D spherical (or cylindrical, plane-strain) cavity driven at constant wall speed, the independent reference of
the FE level's driven HJC cavity (``verification.driven_hjc_cavity``) and of the erosion-free target's steady
force (``verification_erosion_free``).

It shares nothing with the FE solver or with the cavity level (``penetration.cavity.expansion``): its own Lagrangian
spherical scheme and the independent HJC point model of ``hjc_reference``. Nodes at radii r_i carry the
velocities, zones the stresses; zone masses are fixed. Momentum: rho du/dt = d sigma_r/dr + 2 (sigma_r -
sigma_theta)/r, lumped on the nodes (half of each neighbouring zone). Kinematics exact in the volume: the
volumetric increment ln(V'/V) and the radial one ln(dr'/dr) of a zone, its hoop increment their difference
halved. Artificial viscosity in compressing zones q = rho (cq^2 du^2 + cl c |du|). The wall node moves at V,
the far node is held (the run ends before the elastic precursor reaches it: an infinite medium) or free (a body of
finite radius with a traction-free surface, the quasi-static limit of a dashpot boundary).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .hjc_reference import K1, RHO0, SHEAR, constants, update


@njit(cache=True)
def _zone(r0, r1, sphere):
    """A zone's volume over rho0 times it is its mass: r1^3 - r0^3 (times 4 pi / 3, a spherical shell) or
    r1^2 - r0^2 (times pi, a cylindrical ring per unit length)."""
    return r1 ** 3 - r0 ** 3 if sphere else r1 * r1 - r0 * r0


@njit(cache=True)
def _mass(rho0, r0, r1, sphere):
    return rho0 * 4.0 * math.pi / 3.0 * _zone(r0, r1, sphere) if sphere else rho0 * math.pi * _zone(r0, r1, sphere)


@njit(cache=True)
def _run(r, V, t_end, t_from, k, cfl, cq, cl, sphere, free):
    """March to t_end; returns the mean over t_from..t_end of the wall stress (compression positive) weighted by
    the wall area, and the number of steps. ``sphere``: a spherical cavity, else a cylindrical one in plane
    strain; ``free``: the far surface is traction-free, else held."""
    n = r.size - 1
    rho0 = k[RHO0]
    c = math.sqrt((k[K1] + 4.0 * k[SHEAR] / 3.0) / rho0)   # the stiffest (fully dense) wave speed
    mass = np.empty(n)
    for j in range(n):
        mass[j] = _mass(rho0, r[j], r[j + 1], sphere)
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
        for i in range(1, n + 1 if free else n):
            sr_l = s[i - 1, 0] - st[i - 1, 0] - q[i - 1]
            st_l = s[i - 1, 2] - st[i - 1, 0] - q[i - 1]
            outer = i == n   # the free surface: no zone beyond it, no traction
            sr_r = 0.0 if outer else s[i, 0] - st[i, 0] - q[i]
            st_r = 0.0 if outer else s[i, 2] - st[i, 0] - q[i]
            r_next = r[i] if outer else r[i + 1]
            if sphere:
                area = 4.0 * math.pi * r[i] ** 2
                # 2 (sigma_r - sigma_t)/r over the node's two half zones
                hoop = ((sr_l - st_l) * (r[i] ** 3 - r[i - 1] ** 3) + (sr_r - st_r) * (r_next ** 3 - r[i] ** 3)) \
                    * 4.0 * math.pi / 3.0 / r[i]
            else:
                area = 2.0 * math.pi * r[i]
                # (sigma_r - sigma_t)/r over the node's two half rings
                hoop = ((sr_l - st_l) * (r[i] ** 2 - r[i - 1] ** 2) + (sr_r - st_r) * (r_next ** 2 - r[i] ** 2)) \
                    * 0.5 * math.pi / r[i]
            u[i] += dt * (area * (sr_r - sr_l) + hoop) / node_mass[i]
        u[0] = V
        if not free:
            u[n] = 0.0
        r_old = r.copy()
        for i in range(n + 1):
            r[i] += dt * u[i]
        for j in range(n):
            d_vol = math.log(_zone(r[j], r[j + 1], sphere) / _zone(r_old[j], r_old[j + 1], sphere))
            d_rad = math.log((r[j + 1] - r[j]) / (r_old[j + 1] - r_old[j]))
            if sphere:
                d_hoop = 0.5 * (d_vol - d_rad)
                de[0], de[1], de[2], de[3] = d_rad, d_hoop, d_hoop, 0.0
                rate = abs(d_rad - d_hoop) * 2.0 / 3.0 / dt
            else:   # plane strain: no axial strain
                d_hoop = d_vol - d_rad
                de[0], de[1], de[2], de[3] = d_rad, 0.0, d_hoop, 0.0
                m3 = d_vol / 3.0
                rate = math.sqrt(2.0 / 3.0 * ((d_rad - m3) ** 2 + m3 * m3 + (d_hoop - m3) ** 2)) / dt
            mu = mass[j] / _mass(rho0, r[j], r[j + 1], sphere) - 1.0
            update(s[j], st[j], de, mu, rate, k)
            du = u[j + 1] - u[j]
            rho = rho0 * (1.0 + mu)
            q[j] = rho * (cq * cq * du * du + cl * c * abs(du)) if du < 0.0 else 0.0
        t += dt
        steps += 1
        if t > t_from:
            a2 = r[0] ** 2 if sphere else r[0]
            num += dt * a2 * (st[0, 0] + q[0] - s[0, 0])
            den += dt * a2
    return num / den, steps


def wall_stress(material, V, a0, t_end, t_from, r_out=1.0, zones=400, cfl=0.4, cq=1.5, cl=0.06, sphere=True,
                free=False):
    """Mean radial stress on a cavity wall (Pa, compression positive, weighted by the wall area) over
    t_from..t_end, the wall moving out at V from radius a0 at t = 0 in ``material`` (an hjc.HJC) at rest;
    geometric zones from a0 to r_out. ``sphere``: a spherical cavity, else a cylindrical one in plane strain;
    ``free``: the surface at r_out is traction-free (a body of that radius), else held."""
    r = a0 * np.geomspace(1.0, r_out / a0, zones + 1)
    value, _ = _run(r, float(V), float(t_end), float(t_from), constants(material), cfl, cq, cl, bool(sphere),
                    bool(free))
    return float(value)
