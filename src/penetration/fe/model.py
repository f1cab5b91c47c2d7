"""The model: mesh, material, boundary conditions, controls and the state arrays they set up.

``Model`` builds the node and element arrays of a grid (``state``'s named groups), the boundary conditions
(fixities, non-reflecting dashpots), loads and prescribed velocities, and keeps the quantities the audit books
(hourglass, boundary, contact and eroded energy, dropped mass and momentum). The solver (``solver.run``) advances
it; ``element_pass`` and ``node_pass`` run one pass of the kernels on its state (the verification problems and the
speed benchmark use them).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import element_pass as _element_pass, erosion, nodes as _nodes, window
from .erosion_free import rezone as _rezone
from .constitutive import impedances, material_of
from .contact import Projectile
from .mesh import Grid
from .ledger import Ledger
from .spec import Controls
from .state import (ACTIVE, C_DT, C_DTMIN, C_EROSION, C_EROSION_VALUE, C_GUARD, C_Q1, C_Q2, C_QH, DROPPED,
                    EROSION_KINDS, FIX_R, FIX_Z, FREE, IE, LIVE, MASS, N_CTL, N_FIELDS, V0, Body, Boundary, Loads,
                    Nodes, Rows, Span)


def _edges(r, z):
    """The edges of a boundary line through the points (r, z): each one's surface of revolution, a unit normal
    (n_r, n_z) and its midpoint (r, z)."""
    dr, dz = np.diff(r), np.diff(z)
    length = np.hypot(dr, dz)
    area = np.pi * (r[:-1] + r[1:]) * length
    return area, dz / length, -dr / length, 0.5 * (r[:-1] + r[1:]), 0.5 * (z[:-1] + z[1:])


def _boundary_shares(r, z, nodes, centre):
    """Each node's share (area of revolution) of a boundary line through ``nodes`` and the line's normal there,
    pointing away from ``centre`` (r, z): (area, n_r, n_z) per node."""
    area, nr_, nz_, mid_r, mid_z = _edges(r[nodes], z[nodes])
    flip = (mid_r - centre[0]) * nr_ + (mid_z - centre[1]) * nz_ < 0
    nr_[flip], nz_[flip] = -nr_[flip], -nz_[flip]
    a = np.zeros(nodes.size)
    vn = np.zeros((2, nodes.size))
    for k in (0, 1):
        sl = slice(k, k + area.size)
        a[sl] += area / 2
        vn[0, sl] += nr_ * area / 2
        vn[1, sl] += nz_ * area / 2
    norm = np.hypot(vn[0], vn[1])
    return a, vn[0] / norm, vn[1] / norm


@dataclass
class Model:
    grid: Grid
    material: object
    controls: Controls = field(default_factory=Controls)

    def __post_init__(self):
        g, c = self.grid, self.controls
        self.nr, self.nz = g.nr, g.nz
        self.X = np.vstack(g.nodes())   # node positions (rows r, z)
        self.r, self.z = self.X
        nn, ne = self.r.size, g.elements
        self.V = np.zeros((4, nn))   # velocities (rows VR, VZ) and those before the node pass (VR0, VZ0)
        self.vr, self.vz, self.vr0, self.vz0 = self.V
        self.kind, self.q = material_of(self.material)
        rho0 = self.material.rho0
        self.E = np.zeros((N_FIELDS, ne))
        self.alive = np.full(ne, LIVE, np.uint8)
        self.F = np.zeros((8, ne))
        conn = g.connectivity()
        rr, zz = self.r[conn], self.z[conn]
        rn, zn = np.roll(rr, -1, axis=1), np.roll(zz, -1, axis=1)
        V = 2 * np.pi * np.sum((rr + rn) * (rr * zn - rn * zz), axis=1) / 6.0  # 2 pi integral of r dA
        self.E[V0] = V
        self.E[MASS] = rho0 * V
        self.mass = np.zeros(nn)
        np.add.at(self.mass, conn.ravel(), np.repeat(self.E[MASS] / 4, 4))
        self.count = np.zeros(nn, np.int32)
        np.add.at(self.count, conn.ravel(), 1)
        self.nstate = np.full(nn, ACTIVE, np.int8)
        self.on_axis = (self.r == 0.0)
        self.conn = conn
        self.zp, self.zs = impedances(self.material)
        self.fix = np.zeros(nn, np.int8)
        self.fix[self.on_axis] |= FIX_R
        self.dash = np.zeros((3, nn))
        self.rowdash = np.zeros(g.nz + 1, np.int8)  # 1: a node of the row off the grid's edges has a dashpot
        side_i = np.arange(g.nz + 1) * (g.nr + 1) + g.nr     # i = nr (lateral face of a cylinder)
        side_j = g.nz * (g.nr + 1) + np.arange(g.nr + 1)     # j = nz (bottom face)
        for nodes, kind, bit in ((side_i, c.lateral, FIX_R), (side_j, c.bottom, FIX_Z)):
            if kind == "roller":
                self.fix[nodes] |= bit
            elif kind == "non_reflecting":
                self.add_dashpots(nodes)
        self.ctl = np.zeros(N_CTL)
        self.ctl[[C_QH, C_Q1, C_Q2]] = c.hourglass, c.q1, c.q2
        self.ctl[C_EROSION] = EROSION_KINDS[c.erosion]
        self.ctl[C_EROSION_VALUE] = c.erosion_value if math.isfinite(c.erosion_value) else 1e300
        self.ctl[C_GUARD] = float(c.guard)
        self.rows = Rows(g.nz)
        # booked quantities
        self.t = 0.0
        self.steps = 0
        self.ledger = Ledger()   # what leaves the mechanical state and where it goes (fe.ledger)
        self.j0, self.j1 = 0, g.nz
        self.window_started = False
        self.dash_base = self.dash.copy()
        self.presc_i, self.presc_v = np.zeros(0, np.int64), np.zeros((2, 0))
        self.load_i, self.load_f = np.zeros(0, np.int64), np.zeros((2, 0))
        self.tip = -np.inf   # the projectile tip's depth at the last set_window (m)
        free = c.erosion_free   # the erosion-free target's controls, None on the eroding one
        rz = np.inf if free is None or free.rezone_radius is None else free.rezone_radius
        self.rezone_columns = int(min(g.nr, max(2, np.searchsorted(g.R[0], rz))))
        self.element_size = float(g.Z[1, 0] - g.Z[0, 0])   # the core's (its first row)
        # the pilot hole's guide: its radius (the hole's wall, node column 0), 0 without one
        self.guide = float(g.R[0, 0]) if free is not None and free.pilot_guide and g.R[0, 0] > 0.0 else 0.0
        self.dt = self._initial_dt()
        self.dt0 = self.dt
        self.ctl[C_DTMIN] = c.dt_floor * self.dt0 / c.dt_factor

    # ---------------------------------------------------------------- the kernels' view
    def span(self):
        return Span(self.nr, self.nz, self.j0, self.j1)

    def nodes(self):
        return Nodes(self.r, self.z, self.vr, self.vz, self.vr0, self.vz0, self.mass, self.nstate, self.on_axis)


    def boundary(self):
        return Boundary(self.fix, self.dash, self.rowdash, self.zp, self.zs, self.guide)

    def loads(self):
        return Loads(self.presc_i, self.presc_v, self.load_i, self.load_f)

    def element_pass(self, dt):
        """One element pass over the active rows at step dt (stresses, energies, forces, Rows)."""
        self.ctl[C_DT] = dt
        _element_pass.element_pass(self.span(), self.X, self.V, self.kind, self.q, self.ctl, self.E, self.F, self.alive,
                                   self.rows.f, self.rows.i)

    def node_pass(self, dtv):
        """One node pass over the active node rows (velocities by dtv)."""
        _nodes.node_pass(self.span(), self.F, self.alive, self.mass, self.nstate, self.fix, self.dash, self.rowdash,
                         (self.zp, self.zs), dtv, self.V, self.rows.f)

    # ---------------------------------------------------------------- set-up
    def prescribe(self, nodes, vr, vz):
        """Prescribe the velocity (vr, vz) of ``nodes`` (their work is booked as external work)."""
        nodes = np.asarray(nodes, np.int64)
        self.presc_i = nodes
        self.presc_v = np.vstack([np.broadcast_to(vr, nodes.shape), np.broadcast_to(vz, nodes.shape)]).astype(float)
        self.vr[nodes], self.vz[nodes] = self.presc_v

    def load(self, nodes, fr, fz):
        """Constant external nodal forces (N) on ``nodes`` (their work is booked as external work)."""
        nodes = np.asarray(nodes, np.int64)
        self.load_i = nodes
        self.load_f = np.vstack([np.broadcast_to(fr, nodes.shape), np.broadcast_to(fz, nodes.shape)]).astype(float)

    def pressure(self, nodes, p):
        """Nodal forces of a pressure p (Pa) on the boundary line through ``nodes`` (in order), pushing into
        the mesh: each edge's surface of revolution times p, half to each end node."""
        nodes = np.asarray(nodes, np.int64)
        area, nr_, nz_, mid_r, mid_z = _edges(self.r[nodes], self.z[nodes])
        rc, zc = self.centroids()
        near = [int(np.argmin((rc - a) ** 2 + (zc - c) ** 2)) for a, c in zip(mid_r, mid_z)]  # the element behind each edge
        inward = np.sign((rc[near] - mid_r) * nr_ + (zc[near] - mid_z) * nz_)
        f = np.zeros((2, nodes.size))
        for k in (0, 1):
            f[0, k:k + area.size] += 0.5 * p * area * nr_ * inward
            f[1, k:k + area.size] += 0.5 * p * area * nz_ * inward
        self.load(nodes, f[0], f[1])

    def add_dashpots(self, nodes):
        """Non-reflecting dashpots on the boundary line through ``nodes`` (normals outward from the mesh centre)."""
        a, nr_, nz_ = _boundary_shares(self.r, self.z, nodes, (self.r.mean(), self.z.mean()))
        self.dash[0, nodes] += a
        self.dash[1, nodes] = nr_
        self.dash[2, nodes] = nz_
        self.mark_dashpot_rows()

    def mark_dashpot_rows(self):
        """rowdash from dash (the node pass skips the dashpot's arithmetic in the other rows)."""
        g = self.grid
        inner = self.dash[0].reshape(g.nz + 1, g.nr + 1)[:, 1:g.nr]
        self.rowdash[:] = (inner > 0.0).any(axis=1)

    def _initial_dt(self):
        """Stable step of the undeformed mesh (one element pass at rest)."""
        E0 = self.E.copy()
        self.element_pass(0.0)
        self.E[:] = E0
        self.F[:] = 0.0
        return self.controls.dt_factor * float(self.rows.dt.min())

    def set_window(self, Zt):
        """Move the window of active rows with the projectile's tip (``window.follow``)."""
        self.tip = Zt
        window.follow(self, Zt)

    def drop_nodes(self, nodes):
        """Take ``nodes`` out of the model (state DROPPED, velocity 0), booking their axial momentum; returns their
        kinetic energy and mass, for the caller to book where they went."""
        m = self.mass[nodes]
        kinetic = 0.5 * float(np.sum(m * (self.vr[nodes] ** 2 + self.vz[nodes] ** 2)))
        self.ledger.dropped_momentum_z += float(np.sum(m * self.vz[nodes]))
        self.nstate[nodes] = DROPPED
        self.vr[nodes] = 0.0
        self.vz[nodes] = 0.0
        return kinetic, float(m.sum())

    def rezone(self):
        """Eject the lip above the struck face (a penetration shot's: eject_height set), then rezone and remap the
        window's zone (``fe.erosion_free.rezone``); returns 0 or the element that stopped the remap."""
        c = self.controls.erosion_free
        zone = (self.nr, self.j0, self.j1, self.rezone_columns)
        thin_crater = c.crater_thin_after is not None and self.tip > c.crater_thin_after
        crater = (c.crater_depth or 0.0) if thin_crater else 0.0
        if c.eject_height is not None and _rezone.eject(zone, self.X, self.alive, c.eject_length * self.element_size,
                                                        c.eject_height, crater, self.ledger.remapped):
            self.retire_eroded()
        state = self.nstate
        if self.presc_i.size:   # a node whose velocity is prescribed stays where its material is
            state = state.copy()
            state[self.presc_i] = FREE
        return _rezone.rezone(zone, self.X, self.V, self.E, self.alive, state, self.mass, self.material.rho0,
                              c.rezone_quality, c.rezone_weight, self.ledger.remapped)

    def retire_eroded(self):
        """Remove the elements eroded in the last pass (``erosion.retire``)."""
        return erosion.retire(self)

    # ---------------------------------------------------------------- measures
    def kinetic_energy(self):
        keep = self.nstate < DROPPED
        return 0.5 * float(np.sum(self.mass[keep] * (self.vr[keep] ** 2 + self.vz[keep] ** 2)))

    def internal_energy(self):
        return float(self.E[IE, self.alive == LIVE].sum())

    def momentum_z(self):
        keep = self.nstate < DROPPED
        return float(np.sum(self.mass[keep] * self.vz[keep]))

    def centroids(self):
        return self.r[self.conn].mean(axis=1), self.z[self.conn].mean(axis=1)

    def where(self, e):
        """Element e's index, grid position and centre, for people."""
        rc, zc = self.centroids()
        i, j = e % self.nr, e // self.nr
        return f"element {e} (i {i}, j {j}) at r = {rc[e]:.4g} m, z = {zc[e]:.4g} m"


def body_of(projectile: Projectile | None, nn):
    """The kernels' view of a projectile (outline and contact buffers for nn nodes); a stand-in when there is none."""
    if projectile is None:
        return Body(np.array([0.0, 1.0]), np.array([0.0, 0.0]), 0.0, np.zeros(nn, np.int64), np.zeros((4, nn)))
    rho = np.ascontiguousarray(projectile.rho, float)
    return Body(np.ascontiguousarray(projectile.zeta, float), rho, float(rho.max()), np.zeros(nn, np.int64),
                np.zeros((4, nn)))

