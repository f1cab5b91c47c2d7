"""Verification problems of the finite-element level, each against a closed form or a published solution.

Each function sets up and runs one small model and returns its Checks: the quantity we compute, the
independent reference and the interval accepted around it. ``tests/test_fe.py`` asserts that every check
holds; the pipeline (rule ``fe_verification``) writes them to ``figures/fe_verification.csv``. SI units
throughout (the ``unit`` column names them).
"""
from __future__ import annotations

import math

import numpy as np

from .. import cavity
from ..checks import Check, below as _below, near as _near, run_all
from ..geometry import Flat
from ..hjc import HJC
from . import kernels as K
from .materials import Elastic, VonMises
from .mesh import Grid, body_outline, polar
from .solver import Controls, Model, Projectile, run


def _elastic(rho, K, G):
    """Linear elastic material from its bulk and shear moduli."""
    return Elastic(rho, 9 * K * G / (3 * K + G), (3 * K - 2 * G) / (2 * (3 * K + G)))


def _energy(problem, result, bound):
    return _below(problem, "|energy error| at the end (share of the energy put in)", abs(result.audit[-1]["energy_error"]),
                  bound, "1", "conservation (the audit)")


def uniaxial_wave():
    """Piston at 1 m/s on a column with rollers: the plateau stress rho c_L v behind a front at c_L t, no radial
    motion."""
    name = "uniaxial-strain wave (piston 1 m/s, column 2 m of 200 elements, 300 us)"
    Kb, G, rho, v = 16e9, 14.86e9, 2440.0, 1.0
    g = Grid.tensor(np.linspace(0, 0.05, 6), np.linspace(0, 2.0, 201))
    m = Model(g, _elastic(rho, Kb, G), Controls(lateral="roller", bottom="roller", end_time=3e-4, output_interval=1e-4,
                                                progress=False))
    m.prescribe(np.arange(g.nr + 1), 0.0, v)
    res = run(m)
    cL = math.sqrt((Kb + 4 * G / 3) / rho)
    rc, zc = m.centroids()
    szz = m.E[K.SZZ] - m.E[K.P] - m.E[K.QV]
    plateau = -np.median(szz[zc < 0.5 * cL * m.t])
    col = -szz[: g.nr * g.nz: g.nr][: g.nz]
    front = zc[::g.nr][np.argmin(np.abs(col - 0.5 * plateau))]
    return [_near(name, "plateau stress", plateau, rho * cL * v, 1e-3, "Pa", "rho c_L v (closed form)"),
            Check(name, "front position (half the plateau)", float(front), cL * m.t, cL * m.t - 0.02, cL * m.t + 0.02,
                  "m", "c_L t (closed form; within two elements)"),
            _below(name, "largest |v_r|", np.abs(m.vr).max(), 1e-8, "m/s", "0 (uniaxial strain)"),
            _energy(name, res, 5e-3)]


def blake_cavity():
    """Step pressure of 1 MPa in a spherical cavity of 0.1 m (Blake's problem) on a polar RZ mesh."""
    name = "Blake's spherical cavity (step 1 MPa, a = 0.1 m)"
    source = "ExactPack blake (closed form)"
    rho, lam, G = 3000.0, 25e9, 25e9
    Kb = lam + 2 * G / 3
    a, nth = 0.1, 48
    radii = [a]
    while radii[-1] < 1.5:
        radii.append(radii[-1] + min(radii[-1] * np.pi / nth, 0.004))
    g = polar(np.array(radii), nth)
    m = Model(g, _elastic(rho, Kb, G), Controls(lateral="non_reflecting", end_time=400e-6, output_interval=4e-6,
                                                progress=False))
    wall = np.arange(g.nz + 1) * (g.nr + 1)
    m.pressure(wall, 1e6)
    R0, Z0 = m.r.copy(), m.z.copy()
    th = np.arctan2(R0, -Z0)
    ts, uw = [], []

    def radial(model):
        return (model.r - R0) * np.sin(th) - (model.z - Z0) * np.cos(th)

    run(m, callback=lambda model, t: (ts.append(t), uw.append(radial(model)[wall[nth // 2]])))
    ts, uw = np.array(ts), np.array(uw)
    u_wall = radial(m)[wall]
    return [_near(name, "wall displacement at 160 us (equator)", np.interp(160e-6, ts, uw), 1.0018e-6, 3e-3, "m", source),
            _near(name, "peak wall displacement (equator)", uw.max(), 1.259e-6, 5e-3, "m", source),
            _near(name, "static wall displacement (last 40 us, equator)", uw[-10:].mean(), 1.000e-6, 3e-3, "m", source),
            _below(name, "spread of the wall displacement over the polar angle / its mean", np.ptp(u_wall) / u_wall.mean(),
                   0.015, "1", "0 (spherical symmetry)")]


def driven_hjc_cavity(v=400.0):
    """The HJC spherical cavity driven at constant speed from a0 to 4 a0 in the RZ mesh: the wall stress (from the
    driving power) against the cavity level's sigma_n(v) at the final radius."""
    name = f"HJC spherical cavity driven at {v:g} m/s (a0 = 10 mm to 4 a0)"
    a0, nth = 0.01, 40
    radii = [a0]
    while radii[-1] < 1.0:
        radii.append(radii[-1] * (1 + np.pi / nth))
    g = polar(np.array(radii), nth)
    T = 3 * a0 / v
    m = Model(g, HJC(), Controls(lateral="non_reflecting", end_time=T, output_interval=T / 40, progress=False))
    th = np.linspace(0, np.pi, nth + 1)
    m.prescribe(np.arange(g.nz + 1) * (g.nr + 1), v * np.sin(th), -v * np.cos(th))
    res = run(m)
    t = np.array([x["t"] for x in res.audit])
    W = np.array([x["external"] for x in res.audit])
    sigma = np.gradient(W, t) / (4 * np.pi * (a0 + v * t) ** 2 * v)
    s_cavity, _ = cavity.stress_table(HJC(), [v], radius=a0 + v * T)
    return [_near(name, "wall stress (last quarter of the driving power)", sigma[-10:].mean(), float(s_cavity[0]), 0.02, "Pa",
                  "the cavity level's sigma_n (1-D spherical solver, the same HJC)"),
            _energy(name, res, 5e-3)]


def elastic_bar_rebound(nz=200, v=50.0):
    """A nu = 0 steel bar at v on the rigid flat face of a projectile at rest: it separates at (nearly) its
    impact speed, and the contact's kinematic loss is the struck row's kinetic energy, 1/(2 nz) of it."""
    name = f"elastic bar rebounding through the contact ({nz} elements along it, {v:g} m/s)"
    g = Grid.tensor(np.linspace(0, 0.005, 11), np.linspace(0.0, 0.05, nz + 1) + 1e-9)
    m = Model(g, Elastic(7850, 210e9, 0.0), Controls(end_time=60e-6, output_interval=1e-6, progress=False))
    m.vz[:] = -v
    zeta, rho = body_outline(Flat(0.02), 0.05)
    res = run(m, Projectile(zeta, rho, 1e9, 0.0, 0.0))
    rebound = (m.mass * m.vz).sum() / m.mass.sum()
    last = res.audit[-1]
    return [Check(name, "rebound speed", float(rebound), v, 0.98 * v, v, "m/s", "v (elastic bar on a rigid wall)"),
            _below(name, "nodes in contact at the end", res.history["contacts"][-1], 0.0, "1", "separated"),
            _near(name, "contact loss / impact kinetic energy", last["contact"] / (0.5 * m.mass.sum() * v * v), 1 / (2 * nz),
                  0.05, "1", "the struck row's share of the kinetic energy, 1/(2 nz)"),
            _energy(name, res, 5e-3)]


def taylor_bar(across=10):
    """Copper bar 32.4 mm x 3.2 mm at 227 m/s on a frictionless rigid wall, J2 with yield 400 MPa and hardening
    100 MPa, 80 us: the final impact-face radius and length against the published range, within 1 %."""
    name = f"Taylor bar, copper at 227 m/s ({across} elements across)"
    source = "7.11-7.22 mm, 21.42-21.48 mm (Zienkiewicz et al. 1998, Simo 1992, Foulk et al. 2021), within 1 %"
    R, L = 3.2e-3, 32.4e-3
    g = Grid.tensor(np.linspace(0, R, across + 1), np.linspace(0, L, round(10.1 * across) + 1))
    m = Model(g, VonMises(8930.0, 117e9, 0.35, 400e6, 100e6),
              Controls(bottom="roller", end_time=80e-6, output_interval=4e-6, progress=False))
    m.vz[:] = 227.0
    res = run(m)
    face = g.nz * (g.nr + 1) + np.arange(g.nr + 1)
    radius, length = m.r[face].max(), m.z[face].max() - m.z[: g.nr + 1].min()
    last = res.audit[-1]
    return [Check(name, "impact-face radius", float(radius), 0.5 * (7.11e-3 + 7.22e-3), 0.99 * 7.11e-3, 1.01 * 7.22e-3, "m",
                  source),
            Check(name, "final length", float(length), 0.5 * (21.42e-3 + 21.48e-3), 0.99 * 21.42e-3, 1.01 * 21.48e-3, "m",
                  source),
            Check(name, "largest plastic strain", float(m.E[K.EPSP].max()), math.nan, 2.5, math.inf, "1",
                  "a lower bound: large strain at the impact face"),
            _energy(name, res, 0.01),
            _below(name, "hourglass / internal energy", last["hourglass"] / last["internal"], 0.10, "1",
                   "at most a tenth of the internal energy")]


def all_checks(log=print):
    """Every problem (the Taylor bar at 10 and 20 elements across; the tests run it at 10)."""
    return run_all([("uniaxial wave", uniaxial_wave), ("Blake's cavity", blake_cavity),
                    ("driven HJC cavity", driven_hjc_cavity), ("elastic bar", elastic_bar_rebound),
                    ("Taylor bar, 10 across", lambda: taylor_bar(10)), ("Taylor bar, 20 across", lambda: taylor_bar(20))],
                   log)
