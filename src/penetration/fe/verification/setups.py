"""Set-ups of the FE level's verification problems (``fe.verification``): meshes, initial states and drivers
that run the solver for them and return what the problems measure. SI units."""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...nose.geometry import Flat
from .. import state as fe_state
from ..constitutive import Elastic, VonMises
from ..contact import Projectile
from ..gas import run_ideal_gas, volumes_and_density
from ..mesh import Grid, body_outline
from ..model import Controls, Model
from ..nodes import node_pass
from ..solver import run
from . import closed_forms as cf


def elastic(rho, K, G):
    """Linear elastic material from its bulk and shear moduli."""
    return Elastic(rho, 9 * K * G / (3 * K + G), (3 * K - 2 * G) / (2 * (3 * K + G)))


def distorted_grid(n=5, amp=0.06, seed=3):
    """A unit square of n x n elements (its axis at r = 0) with its interior and axis nodes moved at random by
    up to ``amp``."""
    rng = np.random.default_rng(seed)
    g = Grid.tensor(np.linspace(0.0, 1.0, n + 1), np.linspace(0.0, 1.0, n + 1))
    R, Z = g.R.copy(), g.Z.copy()
    R[1:-1, 1:-1] += amp * rng.uniform(-1, 1, (n - 1, n - 1))
    Z[1:-1, 1:-1] += amp * rng.uniform(-1, 1, (n - 1, n - 1))
    Z[1:-1, 0] += amp * rng.uniform(-1, 1, n - 1)
    return Grid(R, Z)


def element_pass(m, dt):
    """One element pass of the solver over every row with step dt (stresses, energy, forces)."""
    m.element_pass(dt)


def nodal_forces(m):
    """Nodal force sums (r, z) of the element forces, by the solver's own gather (its node pass with unit masses,
    a unit step and no fixity)."""
    V = np.zeros_like(m.V)
    node_pass(m.span(), m.F, m.alive, np.ones_like(m.mass), m.nstate, np.zeros_like(m.fix), m.dash, m.rowdash, (0.0, 0.0),
              1.0, V, m.rows.f.copy())
    return -V[fe_state.VR], -V[fe_state.VZ]


def element_path(material, phases, size=0.01, D0=0.0, every_step=True):
    """One axisymmetric FE element (r in [0, size], z in [0, size]) driven homogeneously: each phase (f_r, f_z,
    duration) multiplies the radial and axial stretches by f_r, f_z at constant node velocities (v_r = a r,
    v_z = b z from the phase's start). Returns the history at every step (or 50 per phase): time, the
    stretches lambda_r, lambda_z, pressure, equivalent stress, damage."""
    g = Grid.tensor([0.0, size], [0.0, size])
    m = Model(g, material, Controls(end_time=1.0, output_interval=1.0, max_energy_error=math.inf))
    m.E[fe_state.DMG] = D0
    out = {key: [] for key in ("t", "lr", "lz", "p", "seq", "D")}

    def record(model, t):
        E = model.E[:, 0]
        for key, value in (("t", t), ("lr", model.r[1] / size), ("lz", (model.z[2] - model.z[0]) / size), ("p", E[fe_state.P]),
                           ("seq", math.sqrt(1.5 * (E[fe_state.SRR] ** 2 + E[fe_state.SZZ] ** 2 + E[fe_state.STT] ** 2) + 3 * E[fe_state.SRZ] ** 2)),
                           ("D", E[fe_state.DMG])):
            out[key].append(value)

    record(m, 0.0)
    for fr, fz, duration in phases:
        m.prescribe(np.arange(4), (fr - 1) / duration * m.r, (fz - 1) / duration * m.z)
        m.controls = dataclasses.replace(m.controls, end_time=m.t + duration,
                                         output_interval=1e-12 if every_step else duration / 50)
        run(m, callback=record)
    return {key: np.array(v) for key, v in out.items()}


def bar_on_face(nz, v, q=True):
    """A nu = 0 steel bar (5 mm x 50 mm, nz elements along, nz/20 across) at v onto the rigid flat face of a
    projectile at rest, for 60 us: (model, result)."""
    g = Grid.tensor(np.linspace(0, 0.005, nz // 20 + 1), np.linspace(0.0, 0.05, nz + 1) + 1e-9)
    viscosity = {} if q else dict(q1=0.0, q2=0.0)
    m = Model(g, Elastic(7850, 210e9, 0.0), Controls(end_time=60e-6, output_interval=1e-6, **viscosity))
    m.vz[:] = -v
    zeta, rho = body_outline(Flat(0.02), 0.05)
    return m, run(m, Projectile(zeta, rho, 1e9, 0.0, 0.0))


def taylor_run(across):
    """Copper bar 32.4 mm x 3.2 mm at 227 m/s on a frictionless rigid wall (roller), 80 us: (model, result,
    impact-face radius, length, share of the volume with eps_p >= 0.2)."""
    R, L = 3.2e-3, 32.4e-3
    g = Grid.tensor(np.linspace(0, R, across + 1), np.linspace(0, L, round(10.1 * across) + 1))
    m = Model(g, VonMises(8930.0, 117e9, 0.35, 400e6, 100e6),
              Controls(bottom="roller", end_time=80e-6, output_interval=4e-6))
    m.vz[:] = 227.0
    res = run(m)
    face = g.nz * (g.nr + 1) + np.arange(g.nr + 1)
    share = float(m.E[fe_state.V0, m.E[fe_state.EPSP] >= 0.2].sum() / m.E[fe_state.V0].sum())
    return m, res, float(m.r[face].max()), float(m.z[face].max() - m.z[: g.nr + 1].min()), share


def noh_cylinder_run(n, gamma=5.0 / 3.0, t=0.6):
    """Cylindrical Noh problem on n zones in r (0 to 1 m, one zone thick between rollers): (post-shock density,
    the mean over 0.05 < r < 0.15 m; shock radius, where the density crosses the mean of its two exact values;
    pre-shock density at r = 0.3 m; energy error)."""
    g = Grid.tensor(np.linspace(0.0, 1.0, n + 1), [0.0, 1.0 / n])
    m = Model(g, Elastic(1.0, 1.0, 0.0), Controls())
    m.fix[:] |= 2
    m.vr[:] = -1.0
    m.vr[m.on_axis] = 0.0
    audit, _ = run_ideal_gas(m, gamma, t)
    rho = volumes_and_density(m)[1]
    rc = m.centroids()[0]
    _, rho_post, _, pre = cf.noh(gamma, 1.0, 1.0, t, 2)
    mid = 0.5 * (rho_post + float(pre(0.2)))
    i = int(np.argmax((rho < mid) & (rc > 0.05)))
    shock = float(np.interp(mid, [rho[i], rho[i - 1]], [rc[i], rc[i - 1]]))
    E0, E1 = (a["kinetic"] + a["internal"] for a in (audit[0], audit[-1]))
    return float(rho[(rc > 0.05) & (rc < 0.15)].mean()), shock, float(np.interp(0.3, rc, rho)), (E1 - E0) / E0


def pulse_column(length, h, x1, width, bottom, t_end, amplitude=1.0):
    """A column with rollers (uniaxial strain, the concrete-like constants of the uniaxial wave) holding at t = 0
    a sin^2 velocity pulse from x1 over ``width`` travelling towards its bottom (its displacement, strain and
    stresses set consistently: v = -c du/dz), run to t_end: the node velocities v_z."""
    Kb, G, rho = 16e9, 14.86e9, 2440.0
    c = math.sqrt((Kb + 4 * G / 3) / rho)
    g = Grid.tensor(np.linspace(0, 0.025, 6), np.linspace(0, length, round(length / h) + 1))
    m = Model(g, elastic(rho, Kb, G), Controls(lateral="roller", bottom=bottom, end_time=t_end, output_interval=t_end))
    s = np.clip((m.z - x1) / width, 0.0, 1.0)
    z0 = m.z.copy()
    m.z += amplitude * width / (2 * c) * (1 - (s - np.sin(2 * np.pi * s) / (2 * np.pi)))
    m.vz[:] = amplitude * np.sin(np.pi * s) ** 2
    n = m.conn
    e = np.log((m.z[n[:, 3]] - m.z[n[:, 0]]) / (z0[n[:, 3]] - z0[n[:, 0]]))
    m.E[fe_state.SZZ], m.E[fe_state.SRR], m.E[fe_state.STT], m.E[fe_state.P] = 4 * G / 3 * e, -2 * G / 3 * e, -2 * G / 3 * e, -Kb * e
    m.E[fe_state.IE] = [cf.uniaxial_strain_energy(Kb + 4 * G / 3, V0, x) for V0, x in zip(m.E[fe_state.V0], e)]
    run(m)
    return m.vz, c
