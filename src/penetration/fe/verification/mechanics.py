"""Verification problems of the FE level (registered in ``PROBLEMS``, which ``fe.verification`` joins): waves, cavities and the bar;
plasticity (Taylor's bar, Verney's shells); the formulation (patch test, rigid motion, the penetration audit)."""
from __future__ import annotations

import math

import numpy as np

from ...cavity import expansion as cavity
from ...checks import Check, below as _below, near as _near
from ...concrete.hjc import HJC
from ...nose.geometry import Ogive
from .. import state as fe_state
from ..constitutive import Elastic, VonMises
from ..contact import Projectile
from ..mesh import Grid, MeshSpec, body_outline, build, polar
from ..model import Controls, Model
from ..erosion_free.controls import ErosionFree
from ..erosion_free.rezone import R_MOVED
from ..solver import run
from . import chain_reference, closed_forms as cf
from .cavity_reference import wall_stress
from .common import _energy, _order_limit_gci, _stress, problems
from .setups import bar_on_face, distorted_grid, elastic, element_pass, nodal_forces, taylor_run

PROBLEMS, problem = problems()


# ------------------------------------------------------------------ waves, cavities, the bar

@problem("uniaxial wave")
def uniaxial_wave():
    """Piston at 1 m/s on a column with rollers: the plateau stress rho c_L v behind a front at c_L t, no radial
    motion."""
    name = "uniaxial-strain wave (piston 1 m/s, column 2 m of 200 elements, 300 us)"
    Kb, G, rho, v = 16e9, 14.86e9, 2440.0, 1.0
    g = Grid.tensor(np.linspace(0, 0.05, 6), np.linspace(0, 2.0, 201))
    m = Model(g, elastic(rho, Kb, G), Controls(lateral="roller", bottom="roller", end_time=3e-4, output_interval=1e-4))
    m.prescribe(np.arange(g.nr + 1), 0.0, v)
    res = run(m)
    cL = math.sqrt((Kb + 4 * G / 3) / rho)
    rc, zc = m.centroids()
    szz = _stress(m)
    plateau = -np.median(szz[zc < 0.5 * cL * m.t])
    col = -szz[: g.nr * g.nz: g.nr][: g.nz]
    front = zc[::g.nr][np.argmin(np.abs(col - 0.5 * plateau))]
    return [_near(name, "plateau stress", plateau, rho * cL * v, 1e-3, "Pa", "rho c_L v (closed form)"),
            Check(name, "front position (half the plateau)", float(front), cL * m.t, cL * m.t - 0.02, cL * m.t + 0.02,
                  "m", "c_L t (closed form; within two elements)"),
            _below(name, "largest |v_r|", np.abs(m.vr).max(), 1e-8, "m/s", "0 (uniaxial strain; round-off)"),
            _energy(name, res, 5e-3)]


def _rezoned_checks(name, m):
    """For a rezoned run: that the rezones moved nodes at all (a problem that is not rezoned shows nothing), and
    that the kinetic energy the velocity remap changed is small against the kinetic and internal energy now."""
    if not m.controls.erosion_free:
        return []
    moves = float(m.ledger.remapped[R_MOVED])
    scale = m.kinetic_energy() + m.internal_energy()
    return [Check(name, "node moves made by the rezones", moves, math.nan, 1.0, math.inf, "1",
                  ">= 1: the rezoning acted"),
            _below(name, "|kinetic energy changed by the remap| / (kinetic + internal energy)",
                   abs(m.ledger.remap) / scale, 1e-3, "1", "conservation (small: the velocity remap is not exactly conservative, fe.erosion_free.rezone)")]


# the erosion-free target's rezoning forced on every node of a problem's zone, every 5 steps (a node moves half-way to
# its elements' area-weighted centre whatever its elements' shape): material flows through the mesh all the time
REZONED = dict(erosion_free=ErosionFree(rezone_quality=1.0))
REZONED_NAME = ", rezoned every 5 steps (the erosion-free target's remap)"


@problem("Blake's cavity, rezoned", rezoned=True)
@problem("Blake's cavity")
def blake_cavity(rezoned=False):
    """Step pressure of 1 MPa in a spherical cavity of 0.1 m (Blake's problem) on a polar RZ mesh (``rezoned``:
    with the erosion-free target's rezoning and remap forced on)."""
    name = "Blake's spherical cavity (step 1 MPa, a = 0.1 m)" + (REZONED_NAME if rezoned else "")
    source = "ExactPack blake (closed form)"
    rho, lam, G = 3000.0, 25e9, 25e9
    Kb = lam + 2 * G / 3
    a, nth = 0.1, 48
    radii = [a]
    while radii[-1] < 1.5:
        radii.append(radii[-1] + min(radii[-1] * np.pi / nth, 0.004))
    g = polar(np.array(radii), nth)
    m = Model(g, elastic(rho, Kb, G), Controls(lateral="non_reflecting", end_time=400e-6, output_interval=4e-6,
                                               **(REZONED if rezoned else {})))
    if rezoned:   # the zone: radii up to 3 a (the polar grid's columns are its radii)
        m.rezone_columns = int(np.searchsorted(radii, 3 * a))
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
    # rezoned: the donor-cell remap is first order, and every 5 steps it diffuses the stresses a little: the static
    # displacement is accepted within 1 % and the spread over the angle below 2.5 % (rather than 0.3 % and 1.5 %)
    static, spread = (1e-2, 0.025) if rezoned else (3e-3, 0.015)
    return _rezoned_checks(name, m) + [
            _near(name, "wall displacement at 160 us (equator)", np.interp(160e-6, ts, uw), 1.0018e-6, 3e-3, "m", source),
            _near(name, "peak wall displacement (equator)", uw.max(), 1.259e-6, 5e-3, "m", source),
            _near(name, "static wall displacement (last 40 us, equator)", uw[-10:].mean(), 1.000e-6, static, "m",
                  source),
            _below(name, "spread of the wall displacement over the polar angle / its mean", np.ptp(u_wall) / u_wall.mean(),
                   spread, "1", "0 (spherical symmetry)")]


@problem("driven HJC cavity")
def driven_hjc_cavity(v=400.0):
    """The HJC spherical cavity driven at constant speed from a0 to 4 a0 in the RZ mesh: the mean wall stress
    over the last quarter (the driving work over 4 pi v times the integral of a^2 dt) against an independent
    1-D reference (its own Lagrangian spherical scheme and HJC point model, ``cavity_reference``: nothing shared
    with the solver or with the cavity level) and against the cavity level's steady sigma_n at the final radius.
    The FE mesh (radial spacing pi/40 of the radius) is 0.14 % above the reference; 20 and 80 angular zones
    give 1158.6 and 1147.7 MPa, so the 0.5 % accepted is about three times its own discretisation error."""
    name = f"HJC spherical cavity driven at {v:g} m/s (a0 = 10 mm to 4 a0)"
    a0, nth = 0.01, 40
    radii = [a0]
    while radii[-1] < 1.0:
        radii.append(radii[-1] * (1 + np.pi / nth))
    g = polar(np.array(radii), nth)
    T = 3 * a0 / v
    m = Model(g, HJC(), Controls(lateral="non_reflecting", end_time=T, output_interval=T / 40))
    th = np.linspace(0, np.pi, nth + 1)
    m.prescribe(np.arange(g.nz + 1) * (g.nr + 1), v * np.sin(th), -v * np.cos(th))
    res = run(m)
    t = np.array([x["t"] for x in res.audit])
    W = np.array([x["external"] for x in res.audit])
    i = int(np.searchsorted(t, 0.75 * T - 1e-12))
    area_time = ((a0 + v * t[-1]) ** 3 - (a0 + v * t[i]) ** 3) / (3 * v)      # integral of a^2 dt
    sigma = (W[-1] - W[i]) / (4 * np.pi * v * area_time)
    reference = wall_stress(HJC(), v, a0, t[-1], t[i], zones=400)
    s_cavity, _ = cavity.stress_table(HJC(), [v], radius=a0 + v * T)
    quantity = "mean wall stress over the last quarter (driving work)"
    return [_near(name, quantity, sigma, reference, 0.005, "Pa",
                  "independent 1-D spherical Lagrangian solution, HJC from its equations (fe.cavity_reference, 400 zones; "
                  "200 zones differ by 1e-4)"),
            _near(name, quantity, sigma, float(s_cavity[0]), 0.02, "Pa",
                  "the cavity level's steady sigma_n at the final radius (1-D, similarity cycles, penetration.concrete.hjc)"),
            _energy(name, res, 5e-3)]


@problem("elastic bar")
def elastic_bar_rebound(v=50.0):
    """A nu = 0 steel bar at 50 m/s on the rigid flat face of a projectile at rest, through the kinematic contact.

    The bar leaves below its impact speed (49.26 m/s at 200 elements along it). The deficit is understood:
    at 200 elements the energy missing from the rebound (2.94 % of the impact energy) is the bulk viscosity's
    heat (2.45 %: its linear term q = rho l Q2 c |tr D| acts as a Kelvin-Voigt viscosity on the compressive
    loading front, whose width grows diffusively and which dissipates about 2 sqrt(Q2 l/(pi L)), 1.95 %,
    ``closed_forms.viscous_front_share``), the vibration left in the bar (0.42 %, dispersion), the contact's
    inelastic loss (0.25 %, 1/(2 nz)), less the audit's error (+0.19 %). Without the viscosity the deficit is
    0.56 %. It vanishes as the square root of the element size (1.48, 1.05, 0.75 % at 200, 400, 800
    elements). The reference is therefore an independent 1-D lumped chain with the same discretisation
    (``chain_reference``: masses, central differences, the same viscosity, a perfectly inelastic wall), which
    shares no code with the solver: the FE bar must rebound as the chain does, with and without viscosity."""
    name = f"elastic bar rebounding through the contact ({v:g} m/s, nu = 0)"
    chain = "independent 1-D lumped chain of the same discretisation (fe.chain_reference)"
    E, rho, L = 210e9, 7850.0, 0.05
    rows, rebound = [], {}
    for nz, q in ((200, True), (400, True), (200, False)):
        m, res = bar_on_face(nz, v, q)
        speed = float((m.mass * m.vz).sum() / m.mass.sum())
        viscosity = dict(q1=1.5, q2=0.06) if q else dict(q1=0.0, q2=0.0)
        ref, _ = chain_reference.bar_on_wall(nz, L, v, E, rho, 60e-6, **viscosity)
        label = f"rebound speed ({nz} elements along{'' if q else ', bulk viscosity off'})"
        rows.append(_near(name, label, speed, ref, 1e-3, "m/s", chain))
        rebound[(nz, q)] = (m, res, speed)
    m, res, speed = rebound[(200, True)]
    order = math.log2((v - speed) / (v - rebound[(400, True)][2]))
    t_contact = res.history["t"][res.history["contacts"] > 0].max()
    last = res.audit[-1]
    return rows + [
        Check(name, "observed order of the rebound deficit in the element size (200 -> 400 along)", order, 0.5, 0.35,
              0.65, "1", "1/2: the viscous loading front's width grows as sqrt(Q2 c l t) (closed_forms.viscous_front_share)"),
        _near(name, "end of contact / (2 L / c) (200 along)", t_contact / (2 * L / math.sqrt(E / rho)), 1.0, 0.01, "1",
              "the unloading wave's return (closed form; within a few steps)"),
        _near(name, "contact loss / impact kinetic energy (200 along)", last["contact"] / (0.5 * m.mass.sum() * v * v), 1 / 400,
              0.05, "1", "the struck row's share of the kinetic energy, 1/(2 nz)"),
        _energy(name, res, 5e-3)]


# ------------------------------------------------------------------ plasticity: Taylor bar, Verney's shells
@problem("Taylor bar")
def taylor_bar(meshes=(5, 10, 20)):
    """Copper bar 32.4 mm x 3.2 mm at 227 m/s on a frictionless rigid wall, J2 with yield 400 MPa and hardening
    100 MPa (E 117 GPa, nu 0.35, rho 8930), 80 us, at 5, 10 and 20 elements across.

    Published final impact-face radius: 7.11 mm (Zienkiewicz et al. 1998), 7.12 mm (Simo 1992), 7.22 mm (Foulk
    et al. 2021, converged Q1/P0 hexahedra), 7.226 mm (their composite tetrahedron extrapolated to h = 0);
    final length 21.42-21.48 mm (Foulk et al. 2021's tetrahedra, 21.42-21.43 mm converged). Each mesh is
    checked against the published range widened by its own grid convergence index (from the three meshes,
    Roache), and the Richardson limit against the converged values. The largest plastic strain is left out:
    it sits at the axis of the impact face and keeps growing with refinement. In its place a mesh-objective
    integral: the share of the bar's volume with eps_p >= 0.2 (0.607, 0.612, 0.6125 at 5, 10, 20 across),
    which must lie within 0.5 % (the convergence criterion of the cavity level) of its own Richardson limit."""
    runs = {n: taylor_run(n) for n in meshes}
    radius, length, share = ([runs[n][k] for n in meshes] for k in (2, 3, 4))
    rows = []
    for label, values, (low, high), converged, source in (
            ("impact-face radius", radius, (7.11e-3, 7.23e-3), (7.22e-3, 7.226e-3),
             "7.11-7.23 mm: Zienkiewicz et al. 1998, Simo 1992, Foulk et al. 2021 (converged 7.22-7.226)"),
            ("final length", length, (21.42e-3, 21.48e-3), (21.42e-3, 21.43e-3),
             "21.42-21.48 mm: Foulk et al. 2021 (converged 21.42-21.43)")):
        p, limit, gci = _order_limit_gci(values)
        for n, value, u in ((meshes[1], values[1], gci * 2.0 ** p), (meshes[2], values[2], gci)):
            rows.append(Check(f"Taylor bar, copper at 227 m/s ({n} elements across)", label, value, 0.5 * (low + high),
                              low * (1 - u), high * (1 + u), "m", source + "; widened by this mesh's grid convergence index"))
        rows.append(Check(f"Taylor bar, copper at 227 m/s ({'/'.join(map(str, meshes))} across)",
                          f"{label} extrapolated to h -> 0 (Richardson)", limit, 0.5 * sum(converged),
                          converged[0] * (1 - gci), converged[1] * (1 + gci), "m",
                          source + "; the converged values widened by the finest mesh's grid convergence index"))
    _, limit, _ = _order_limit_gci(share)
    name = f"Taylor bar, copper at 227 m/s ({meshes[1]} elements across)"
    m, res = runs[meshes[1]][:2]
    last = res.audit[-1]
    return rows + [
        _near(name, "share of the volume with eps_p >= 0.2", share[1], limit, 0.005, "1",
              f"its Richardson limit over {'/'.join(map(str, meshes))} across; within 0.5 %"),
        _energy(name, res, 0.01),
        _below(name, "hourglass / internal energy", last["hourglass"] / last["internal"], 0.10, "1",
               "at most a tenth of the internal energy")]


@problem("Verney's cylinder")
def verney_cylinder(nr=20, Y=200e6, stop=0.08):
    """Verney's collapsing shell in its cylindrical form: a steel shell a0 = 0.1 m, b0 = 0.12 m (E 200 GPa,
    nu 0.3, elastic-perfectly plastic, yield 200 MPa) in plane strain (one element row between rollers), given
    the incompressible inward flow v = v0 a0/r with v0 from the closed-form energy balance
    (``closed_forms.collapse_work``) for an inner radius of 0.08 m at rest. The closed form neglects elasticity:
    its share of the collapse, about the elastic strain to yield over the strain of the collapse (Y/E a0 /
    (a0 - a1) = 0.5 %), sets the 1 % accepted on the collapse distance."""
    a0, b0, rho, E = 0.1, 0.12, 7850.0, 200e9
    name = f"Verney's cylindrical shell collapsing to 80 mm (plane strain, {nr} elements through the wall)"
    g = Grid.tensor(np.linspace(a0, b0, nr + 1), [0.0, (b0 - a0) / nr])
    v0 = cf.collapse_speed(rho, a0, stop, b0, Y)
    T = 2.5 * (a0 - stop) / v0
    m = Model(g, VonMises(rho, E, 0.3, Y, 0.0), Controls(end_time=T, output_interval=T / 400))
    m.fix[:] |= 2
    m.vr[:] = -v0 * a0 / m.r
    inner = np.arange(g.nz + 1) * (g.nr + 1)
    radii = []
    res = run(m, callback=lambda model, t: radii.append(model.r[inner].mean()))
    return [_near(name, "collapse distance of the inner wall (at rest)", a0 - min(radii), a0 - stop, 0.01, "m",
                  "incompressible rigid-plastic energy balance (closed_forms.collapse_work; Verney 1968)"),
            _energy(name, res, 1e-3)]


@problem("Verney's sphere")
def verney_sphere(nr=40, nth=48, Y=200e6, stop=0.08):
    """Verney's collapsing spherical shell (a0 = 0.1 m, b0 = 0.12 m, the steel of ``verney_cylinder``) on a polar
    RZ mesh, given v = v0 a0^2/r^2 with v0 from the closed-form energy balance of an incompressible rigid-plastic
    sphere (kinetic energy 2 pi rho v0^2 a0^4 (1/a0 - 1/b0) = plastic work (8 pi Y/9) [x ln(1 + c/x) +
    c ln(x + c)] from x1 = a1^3 to x0, c = b0^3 - a0^3, derived as in ``closed_forms.collapse_work``). The mean
    stop radius converges (-0.97, -0.31, -0.12 % at 10x12, 20x24, 40x48 zones); the spread over the polar angle,
    the polar mesh's departure from spherical symmetry, shrinks with it (4.3, 1.5, 0.5 mm)."""
    a0, b0, rho = 0.1, 0.12, 7850.0
    c = b0 ** 3 - a0 ** 3

    def work(a):
        return a ** 3 * math.log(1 + c / a ** 3) + c * math.log(a ** 3 + c)
    v0 = math.sqrt(8 * math.pi * Y / 9 * (work(a0) - work(stop)) / (2 * math.pi * rho * a0 ** 4 * (1 / a0 - 1 / b0)))
    name = f"Verney's spherical shell collapsing to 80 mm ({nr} x {nth} polar zones)"
    g = polar(np.linspace(a0, b0, nr + 1), nth)
    T = 2.5 * (a0 - stop) / v0
    m = Model(g, VonMises(rho, 200e9, 0.3, Y, 0.0), Controls(end_time=T, output_interval=T / 400))
    R = np.hypot(m.r, m.z)
    m.vr[:], m.vz[:] = -v0 * a0 ** 2 / R ** 3 * m.r, -v0 * a0 ** 2 / R ** 3 * m.z
    m.vr[m.on_axis] = 0.0
    inner = np.arange(g.nz + 1) * (g.nr + 1)
    radii = []
    res = run(m, callback=lambda model, t: radii.append(np.hypot(model.r[inner], model.z[inner])))
    radii = np.array(radii)
    k = int(radii.mean(axis=1).argmin())
    return [_near(name, "mean inner radius at rest", radii[k].mean(), stop, 0.003, "m",
                  "incompressible rigid-plastic energy balance of the sphere (Verney 1968; derived in the docstring)"),
            _below(name, "spread of the inner radius over the polar angle / collapse distance", np.ptp(radii[k]) / (a0 - stop),
                   0.05, "1", "0 (spherical symmetry)"),
            _energy(name, res, 1e-3)]


# ------------------------------------------------------------------ the formulation: patch test, rigid motion
@problem("patch test")
def patch_test(alpha=0.3, beta=-0.2, dt=1e-6):
    """v_r = alpha r, v_z = beta z on a distorted mesh (one step): every element gets the same strain, the
    closed-form stress, no hourglass work, and the interior and axis nodes are in equilibrium."""
    name = "patch test (v_r = 0.3 r, v_z = -0.2 z, distorted 5 x 5 mesh, one step of 1 us)"
    g = distorted_grid()
    m = Model(g, Elastic(1000.0, 1e9, 0.25), Controls(hourglass=0.1))
    m.vr[:], m.vz[:] = alpha * m.r, beta * m.z
    m.r += dt * m.vr
    m.z += dt * m.vz
    element_pass(m, dt)
    G, Kb = m.q[1], m.q[2]
    # strain increments at the half-step geometry (the solver's rate times dt), and the volume ratio
    drr, dzz = alpha * dt / (1 + 0.5 * alpha * dt), beta * dt / (1 + 0.5 * beta * dt)
    mean = (2 * drr + dzz) / 3
    fr, fz = (f.reshape(g.nz + 1, g.nr + 1) for f in nodal_forces(m))
    scale = np.abs(m.F).max()
    spread = max(np.ptp(m.E[f]) / np.abs(m.E[f]).max() for f in (fe_state.SRR, fe_state.SZZ, fe_state.STT, fe_state.P))
    return [_near(name, "radial deviatoric stress", m.E[fe_state.SRR].mean(), 2 * G * (drr - mean), 1e-9, "Pa",
                  "2 G (d_rr - tr d/3) of the half-step increments (closed form; exact in the discrete algebra, to round-off)"),
            _near(name, "pressure", m.E[fe_state.P].mean(), Kb * math.log(1 / ((1 + alpha * dt) ** 2 * (1 + beta * dt))), 1e-6,
                  "Pa", "K ln(V0/V) (closed form; the logarithm of a ratio within 1e-6 of 1 keeps ~1e-10 of it)"),
            _below(name, "largest spread of a stress component over the elements / its size", spread, 1e-6, "1",
                   "0: uniform strain (round-off)"),
            _below(name, "|s_rr - s_tt| / |s_rr| and |s_rz| / |s_rr| (largest)",
                   max(np.abs(m.E[fe_state.SRR] - m.E[fe_state.STT]).max(), np.abs(m.E[fe_state.SRZ]).max()) / np.abs(m.E[fe_state.SRR]).max(),
                   1e-12, "1", "0: e_rr = e_tt, no shear (round-off)"),
            _below(name, "hourglass work / internal energy", m.rows.hg.sum() / m.E[fe_state.IE].sum(), 1e-20, "1",
                   "0: the hourglass mode is orthogonal to linear fields (round-off)"),
            _below(name, "largest interior and axis nodal force / largest element force",
                   max(np.abs(fr[1:-1, 1:-1]).max(), np.abs(fz[1:-1, :-1]).max()) / scale, 1e-7, "1",
                   "0: equilibrium of a uniform stress (round-off)")]


@problem("rigid translation")
def rigid_translation(v=30.0):
    """HJC on a distorted mesh translating at 30 m/s for 0.2 ms: no stress, no change of velocity, no energy."""
    name = "rigid axial translation (HJC, distorted 5 x 5 mesh, 30 m/s, 0.2 ms)"
    m = Model(distorted_grid(), HJC(), Controls(end_time=2e-4, output_interval=1e-4))
    m.vz[:] = v
    res = run(m)
    return [_below(name, "largest |stress|", np.abs(m.E[[fe_state.SRR, fe_state.SZZ, fe_state.STT, fe_state.SRZ, fe_state.P]]).max(), 1e-3, "Pa",
                   "0 (round-off of the positions)"),
            _below(name, "largest change of a node's velocity / v", max(np.abs(m.vz - v).max(), np.abs(m.vr).max()) / v,
                   1e-12, "1", "0 (round-off)"),
            _below(name, "|energy error|", abs(res.audit[-1]["energy_error"]), 1e-12, "1", "0 (round-off)")]


@problem("penetration audit")
def penetration_audit(v=835.0):
    """A CRH 4.5 ogive (81.1 kg, 70 mm shank radius) at 835 m/s into HJC for 1.5 ms (20 mm elements, erosion at
    plastic strain 1): the audit closes, the axial momentum is conserved with the eroded, dropped and boundary
    terms, and the hourglass work stays small."""
    name = "penetration audit (CRH 4.5 at 835 m/s into HJC, 20 mm elements, 1.5 ms)"
    zeta, rho = body_outline(Ogive(4.5, 0.07), 1.13)
    g = build(MeshSpec(0.02, 0.21, 2.0, 1.0, 2.5, 1.15))
    m = Model(g, HJC(), Controls(erosion="plastic_strain", erosion_value=1.0, end_time=1.5e-3, output_interval=1e-4, lateral="non_reflecting", bottom="non_reflecting"))
    p = Projectile(zeta, rho, 81.1, 0.0, v)
    res = run(m, p)
    last = res.audit[-1]
    return [_below(name, "|energy error|", abs(last["energy_error"]), 0.01, "1", "conservation (the audit)"),
            _below(name, "|momentum error|", abs(last["momentum_error"]), 1e-9, "1",
                   "conservation with the boundary impulse and the dropped nodes (round-off)"),
            _below(name, "hourglass work / (internal + eroded energy)", last["hourglass"] / (last["internal"] + last["eroded"]),
                   0.10, "1", "at most a tenth"),
            Check(name, "projectile speed at the end", p.V, math.nan, 0.0, v, "m/s", "decelerating, still moving"),
            Check(name, "depth at the end", p.Zt, math.nan, 0.5, v * 1.5e-3, "m", "beyond the crater, below v t")]
