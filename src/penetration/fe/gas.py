"""An ideal gas on the FE solver's kernels, for Noh's problem (verification of the shock viscosity).

The solver's materials have no energy-dependent pressure (``fe.constitutive``: elastic, von Mises, HJC), so this
module steps a ``Model`` itself with the solver's own kernels: ``nodes.node_pass`` (velocities from the element
forces, fixities), ``nodes.move`` and ``element_pass.element_pass``, the last with the shear modulus at 0 and a bulk
modulus negligible next to the flow's pressures (by default; 0 itself would make the pass's stable step
infinite, which it reports as non-finite). The element pass so contributes the geometry and the bulk viscosity
q: its formula, its forces and its work booked in E[IE]. This module adds the gas pressure p = (gamma - 1) e/V of
each element's internal energy e (J): its forces, those the element pass forms for the stress -p I (the same
b-matrix and hoop terms), and its work, time-centred, e' = e - (p + p')/2 (V' - V), solved for p' in closed
form. The step is this module's: the kernel's length and viscosity terms with the gas sound speed
sqrt(gamma p/rho). With the negligible modulus the kernel's own sound speed is 0, so its linear viscosity term
and its hourglass control are off. What ``fe.constitutive`` would need to hold the gas itself: a kind whose update
sets p from E[IE] by the centred update above and whose wave speed is sqrt(gamma p/rho).
"""
from __future__ import annotations

import math

import numpy as np

from . import state as fe_state
from .model import Model
from .nodes import move, node_pass


def _geometry(m: Model):
    """Per element: volume V = 2 pi W, dW/dr at the four corners, b_z at corners 1 and 2, the length l (area over
    the longest side) and the density, at the current node positions."""
    c = m.conn
    r, z = m.r[c], m.z[c]
    r1, r2, r3, r4 = r.T
    z1, z2, z3, z4 = z.T
    c12, c23, c34, c41 = r1 * z2 - r2 * z1, r2 * z3 - r3 * z2, r3 * z4 - r4 * z3, r4 * z1 - r1 * z4
    W = ((r1 + r2) * c12 + (r2 + r3) * c23 + (r3 + r4) * c34 + (r4 + r1) * c41) / 6.0
    dW = np.stack([c41 + c12 - (r4 + r1) * z4 + (r1 + r2) * z2, c12 + c23 - (r1 + r2) * z1 + (r2 + r3) * z3,
                   c23 + c34 - (r2 + r3) * z2 + (r3 + r4) * z4, c34 + c41 - (r3 + r4) * z3 + (r4 + r1) * z1]) / 6.0
    A2 = (r3 - r1) * (z4 - z2) + (r2 - r4) * (z3 - z1)
    bz = np.stack([(r4 - r2) / A2, (r1 - r3) / A2])
    sides = np.stack([(r2 - r1) ** 2 + (z2 - z1) ** 2, (r3 - r2) ** 2 + (z3 - z2) ** 2,
                      (r4 - r3) ** 2 + (z4 - z3) ** 2, (r1 - r4) ** 2 + (z1 - z4) ** 2]).max(axis=0)
    V = 2.0 * math.pi * W
    return V, dW, bz, 0.5 * A2 / np.sqrt(sides), m.E[fe_state.MASS] / V


def volumes_and_density(m: Model):
    """Volume (m^3) and density (kg/m^3) of every element at the current node positions."""
    V, _, _, _, rho = _geometry(m)
    return V, rho


def _add_pressure_forces(m: Model, p, V, dW, bz):
    """Element forces of the stress -p I, as the element pass forms them (F = V B^T sigma, hoop 2 pi sigma dW/dr)."""
    hoop = -2.0 * math.pi * p * dW
    fz1, fz2 = -p * V * bz[0], -p * V * bz[1]
    m.F[0] += hoop[0]
    m.F[1] += fz1
    m.F[2] += hoop[1]
    m.F[3] += fz2
    m.F[4] += hoop[2]
    m.F[5] -= fz1
    m.F[6] += hoop[3]
    m.F[7] -= fz2


def run_ideal_gas(m: Model, gamma, end_time, modulus=0.0, dt_factor=0.5, outputs=0):
    """Advance ``m`` as an ideal gas (density from its material's rho0, internal energy E[IE], J per element) to
    end_time. ``modulus``: the bulk modulus left to the element pass (its shear modulus is set to 0), which sets
    the sound speed of its hourglass control and linear viscosity; its pressure is taken off again (forces, and
    its work from E[IE]: the pass books -V tr(D) dt ((p_old + p_new)/2 + (q_old + q_new)/2), of which the q share
    is kept), so
    that the flow sees the gas pressure and q only. Returns (audit, p): the audit of time, kinetic and internal
    energy at ``outputs`` evenly spaced times and the end, and the element pressures at the end."""
    m.q[1] = 0.0
    scale = float(m.q[0] * np.max(m.vr ** 2 + m.vz ** 2) + (gamma - 1.0) * m.E[fe_state.IE].sum() / m.E[fe_state.V0].sum())
    m.q[2] = max(modulus, 1e-12 * scale)   # a zero modulus would make the pass's stable step infinite (non-finite)
    m.ctl[fe_state.C_DTMIN] = 0.0
    V, dW, bz, lc, rho = _geometry(m)
    p = (gamma - 1.0) * m.E[fe_state.IE] / V
    t, dt_old, audit, tv = 0.0, None, [], _dilatation(m, V)
    marks = list(np.linspace(0.0, end_time, outputs + 1)[1:]) if outputs else []
    q1, q2 = m.ctl[fe_state.C_Q1], m.ctl[fe_state.C_Q2]

    def record():
        audit.append(dict(t=t, kinetic=m.kinetic_energy(), internal=float(m.E[fe_state.IE].sum())))

    record()
    _pass(m, 0.0)
    _add_pressure_forces(m, p - m.E[fe_state.P], V, dW, bz)
    while t < end_time - 1e-15:
        c = np.sqrt(gamma * np.maximum(p, 0.0) / rho)
        Q = q2 * c + q1 * q1 * lc * np.maximum(-tv, 0.0)
        dt = dt_factor * float(np.min(lc / (Q + np.sqrt(Q * Q + c * c) + 1e-300)))
        dt = min(dt, end_time - t, 1.2 * dt_old if dt_old else dt)
        dtv = dt if dt_old is None else 0.5 * (dt + dt_old)
        node_pass(m.span(), m.F, m.alive, m.mass, m.nstate, m.fix, m.dash, m.rowdash, (0.0, 0.0), dtv, m.V, m.rows.f)
        move(m.span(), m.X, m.V, m.nstate, dt)
        e_old, pk_old, q_old = m.E[fe_state.IE].copy(), m.E[fe_state.P].copy(), m.E[fe_state.QV].copy()
        _pass(m, dt)
        q_mean = 0.5 * (q_old + m.E[fe_state.QV])
        share = 0.5 * (pk_old + m.E[fe_state.P]) + q_mean
        heat = (m.E[fe_state.IE] - e_old) * q_mean / np.where(share != 0.0, share, 1.0)
        V_new, dW, bz, lc, rho = _geometry(m)
        dV = V_new - V
        tv = np.log(V_new / V) / dt
        e = (e_old + heat - 0.5 * p * dV) / (1.0 + 0.5 * (gamma - 1.0) * dV / V_new)
        m.E[fe_state.IE] = e
        p, V = (gamma - 1.0) * e / V_new, V_new
        _add_pressure_forces(m, p - m.E[fe_state.P], V, dW, bz)
        t += dt
        dt_old = dt
        m.t = t
        while marks and t >= marks[0] - 1e-15:
            marks.pop(0)
            record()
    if audit[-1]["t"] < t:
        record()
    return audit, p


def _dilatation(m: Model, V):
    """tr D of each element from the node velocities (the volume change over a short probe step)."""
    h = 1e-6 * float(np.min(_geometry(m)[3]) / max(np.max(np.hypot(m.vr, m.vz)), 1e-300))
    r, z = m.r.copy(), m.z.copy()
    m.r += h * m.vr
    m.z += h * m.vz
    V_h = _geometry(m)[0]
    m.r[:], m.z[:] = r, z
    return (V_h - V) / (h * V)


def _pass(m: Model, dt):
    """The solver's element pass (geometry, viscosity and its work, forces) over every row."""
    m.element_pass(dt)
    if (m.rows.fail >= 0).any() or (m.alive != fe_state.LIVE).any():
        raise RuntimeError(f"the gas mesh failed at t = {m.t:.4g} (an inverted element)")
