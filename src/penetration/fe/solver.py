"""The explicit solver: state, time loop, erosion bookkeeping, energy and momentum audit.

``Model`` holds the mesh, the material, the boundary conditions and the
controls; ``run`` advances it (optionally with a rigid projectile) and
returns histories and an audit. Energy balance (every output step):

    KE_target + KE_projectile + IE + W_hourglass + E_eroded + W_contact + W_boundary = E_0

with E_eroded the internal energy of eroded elements plus the kinetic energy
of dropped free nodes, W_contact the kinetic energy the kinematic contact
removes (its impulses are perfectly inelastic), W_boundary the work absorbed
by non-reflecting boundaries. The error is reported relative to E_0.
"""
from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..errors import ParameterError
from . import kernels as K
from .materials import kind_of
from .mesh import Grid


@dataclass(frozen=True)
class Controls:
    """Numerical controls; defaults follow LS-DYNA's (QH 0.1, Q1 1.5, Q2 0.06, time-step factor 0.9)."""
    dt_factor: float = 0.9
    hourglass: float = 0.1
    q1: float = 1.5
    q2: float = 0.06
    erosion: str = "none"
    erosion_value: float = math.inf
    guard: bool = True          # erode inverted or time-step-collapsed elements (else stop with a diagnostic)
    dt_floor: float = 1e-3      # guard threshold: element step below this fraction of the initial step
    drop_free_nodes: bool = True
    lateral: str = "free"
    bottom: str = "free"
    end_time: float = 0.05
    output_interval: float = 1e-4
    max_energy_error: float = 0.5  # stop (unstable) when the audit's relative error exceeds this
    window_ahead: float | None = None   # m: rows computed down to this far ahead of the tip (None: whole domain)
    window_behind: float | None = None  # m: rows further behind the tip than this are retired (None: kept)
    progress: bool | None = None   # None: on a terminal only

    def __post_init__(self):
        if not 0.0 < self.dt_factor <= 1.0:
            raise ParameterError("fe controls", "dt_factor", self.dt_factor, "0 < dt_factor <= 1")
        if not 0.0 <= self.hourglass <= 0.15:
            raise ParameterError("fe controls", "hourglass", self.hourglass, "0 <= hourglass <= 0.15 (unstable above)")
        if self.erosion not in K.EROSION_KINDS:
            raise ParameterError("fe controls", "erosion", self.erosion, f"one of {sorted(K.EROSION_KINDS)}")
        if self.erosion != "none" and not self.erosion_value > 0:
            raise ParameterError("fe controls", "erosion_value", self.erosion_value, "> 0")
        for key in ("lateral", "bottom"):
            if getattr(self, key) not in K.BOUNDARIES:
                raise ParameterError("fe controls", key, getattr(self, key), f"one of {sorted(K.BOUNDARIES)}")
        for key in ("window_ahead", "window_behind"):
            v = getattr(self, key)
            if v is not None and not v > 0:
                raise ParameterError("fe controls", key, v, "> 0 (m) or None")
        if not (self.end_time > 0 and self.output_interval > 0):
            raise ParameterError("fe controls", "end_time, output_interval", (self.end_time, self.output_interval), "> 0 (s)")


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


class Unstable(RuntimeError):
    """A run stopped early: names the quantity, where and when."""


@dataclass
class Model:
    grid: Grid
    material: object
    controls: Controls = field(default_factory=Controls)

    def __post_init__(self):
        g = self.grid
        self.nr, self.nz = g.nr, g.nz
        self.r, self.z = g.nodes()
        nn, ne = self.r.size, g.elements
        self.vr = np.zeros(nn)
        self.vz = np.zeros(nn)
        self.kind, self.q, rho0 = kind_of(self.material)
        self.E = np.zeros((K.N_FIELDS, ne))
        self.alive = np.ones(ne, np.uint8)
        self.F = np.zeros((8, ne))
        conn = g.connectivity()
        rr, zz = self.r[conn], self.z[conn]
        rn, zn = np.roll(rr, -1, axis=1), np.roll(zz, -1, axis=1)
        V = 2 * np.pi * np.sum((rr + rn) * (rr * zn - rn * zz), axis=1) / 6.0  # 2 pi integral of r dA
        self.E[K.V0] = V
        self.E[K.MASS] = rho0 * V
        self.mass = np.zeros(nn)
        np.add.at(self.mass, conn.ravel(), np.repeat(self.E[K.MASS] / 4, 4))
        self.count = np.zeros(nn, np.int32)
        np.add.at(self.count, conn.ravel(), 1)
        self.nstate = np.zeros(nn, np.int8)
        self.on_axis = (self.r == 0.0)
        self.conn = conn
        c = self.controls
        G = self.q[1]
        Kb = self.material.Ke if self.kind == K.HJC_KIND else self.q[2]
        self.zp = rho0 * math.sqrt((Kb + 4 * G / 3) / rho0)
        self.zs = rho0 * math.sqrt(G / rho0)
        self.fix = np.zeros(nn, np.int8)
        self.fix[self.on_axis] |= 1
        self.dash = np.zeros((3, nn))
        self.rowdash = np.zeros(g.nz + 1, np.int8)  # 1: a node of the row off the grid's edges has a dashpot
        side_i = np.arange(g.nz + 1) * (g.nr + 1) + g.nr     # i = nr (lateral face of a cylinder)
        side_j = g.nz * (g.nr + 1) + np.arange(g.nr + 1)     # j = nz (bottom face)
        for nodes, kind in ((side_i, c.lateral), (side_j, c.bottom)):
            if kind == "roller":
                self.fix[nodes] |= 1 if nodes is side_i else 2
            elif kind == "non_reflecting":
                self._dashpots(nodes)
        self.ctl = np.zeros(K.N_CTL)
        self.ctl[[K.C_QH, K.C_Q1, K.C_Q2]] = c.hourglass, c.q1, c.q2
        self.ctl[K.C_EROSION] = K.EROSION_KINDS[c.erosion]
        self.ctl[K.C_EROSION_VALUE] = c.erosion_value if math.isfinite(c.erosion_value) else 1e300
        self.ctl[K.C_GUARD] = float(c.guard)
        self.rowdt = np.zeros(g.nz)
        self.rowhg = np.zeros(g.nz)
        self.rowero = np.zeros(g.nz)
        self.rowfail = np.full(2 * g.nz, -1, np.int64)
        self.rowbnd = np.zeros((2, g.nz + 1))
        # booked quantities
        self.t = 0.0
        self.steps = 0
        self.W_hourglass = 0.0
        self.W_boundary = 0.0
        self.W_contact = 0.0
        self.E_eroded = 0.0
        self.eroded_mass = 0.0
        self.dropped_mass = 0.0
        self.dropped_momentum_z = 0.0
        self.j0, self.j1 = 0, g.nz
        self._window_started = False
        self.E_window = 0.0
        self.window_mass = 0.0
        self.dash_base = self.dash.copy()
        self.presc_i = np.zeros(0, np.int64)
        self.presc_v = np.zeros((2, 0))
        self.load_i = np.zeros(0, np.int64)
        self.load_f = np.zeros((2, 0))
        self.dt = self._initial_dt()
        self.dt0 = self.dt
        self.ctl[K.C_DTMIN] = c.dt_floor * self.dt0 / c.dt_factor

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
        r, z = self.r[nodes], self.z[nodes]
        dr, dz = np.diff(r), np.diff(z)
        length = np.hypot(dr, dz)
        area = np.pi * (r[:-1] + r[1:]) * length
        nr_, nz_ = dz / length, -dr / length
        mid_r, mid_z = 0.5 * (r[:-1] + r[1:]), 0.5 * (z[:-1] + z[1:])
        rc, zc = self.centroids()
        near = [int(np.argmin((rc - a) ** 2 + (zc - c) ** 2)) for a, c in zip(mid_r, mid_z)]  # the element behind each edge
        inward = np.sign((rc[near] - mid_r) * nr_ + (zc[near] - mid_z) * nz_)
        f = np.zeros((2, nodes.size))
        for k in (0, 1):
            f[0, k:k + area.size] += 0.5 * p * area * nr_ * inward
            f[1, k:k + area.size] += 0.5 * p * area * nz_ * inward
        self.load(nodes, f[0], f[1])

    def _dashpots(self, nodes):
        """Boundary share (area of revolution) and outward normal of each node of a boundary line."""
        r, z = self.r[nodes], self.z[nodes]
        dr, dz = np.diff(r), np.diff(z)
        length = np.hypot(dr, dz)
        area = np.pi * (r[:-1] + r[1:]) * length          # surface of revolution of each edge
        nr_, nz_ = dz / length, -dr / length              # a normal of each edge
        mid_r, mid_z = 0.5 * (r[:-1] + r[1:]), 0.5 * (z[:-1] + z[1:])
        rc, zc = self.r.mean(), self.z.mean()
        flip = (mid_r - rc) * nr_ + (mid_z - zc) * nz_ < 0  # outward: away from the mesh centre
        nr_[flip], nz_[flip] = -nr_[flip], -nz_[flip]
        a = np.zeros(nodes.size)
        vn = np.zeros((2, nodes.size))
        for k in (0, 1):
            sl = slice(k, k + area.size)
            a[sl] += area / 2
            vn[0, sl] += nr_ * area / 2
            vn[1, sl] += nz_ * area / 2
        norm = np.hypot(vn[0], vn[1])
        self.dash[0, nodes] += a
        self.dash[1, nodes] = vn[0] / norm
        self.dash[2, nodes] = vn[1] / norm
        self._mark_dashpot_rows()

    def _mark_dashpot_rows(self):
        """rowdash from dash (the node pass skips the dashpot's arithmetic in the other rows)."""
        g = self.grid
        inner = self.dash[0].reshape(g.nz + 1, g.nr + 1)[:, 1:g.nr]
        self.rowdash[:] = (inner > 0.0).any(axis=1)

    # ------------------------------------------------------------------
    def _initial_dt(self):
        """Stable step of the undeformed mesh (one element pass at rest)."""
        self.ctl[K.C_DT] = 0.0
        E0 = self.E.copy()
        K.element_pass(self.nr, self.nz, 0, self.nz, self.r, self.z, self.vr, self.vz, self.E, self.alive, self.F, self.kind,
                       self.q, self.ctl, self.rowdt, self.rowhg, self.rowero, self.rowfail)
        self.E[:] = E0
        self.F[:] = 0.0
        return self.controls.dt_factor * float(self.rowdt.min())

    def set_window(self, Zt):
        """Activate rows down to window_ahead below the tip, retire rows more than window_behind above it.

        Retired elements' internal energy and their nodes' kinetic energy and
        momentum are booked (E_window, dropped_momentum_z); a non-reflecting
        dashpot sits on the bottom node row of the window while it is above
        the domain's bottom.
        """
        c, g = self.controls, self.grid
        if c.window_ahead is None and c.window_behind is None:
            return
        z0 = g.Z[:, 0]  # initial depth of each node row (the mesh is a tensor grid)
        changed = False
        if c.window_ahead is not None:
            j1 = int(min(g.nz, np.searchsorted(z0, Zt + c.window_ahead) + 1))
            nn_row = g.nr + 1
            if not self._window_started:
                self.alive[j1 * g.nr:][self.alive[j1 * g.nr:] == 1] = 3
                self.nstate[(j1 + 1) * nn_row:][self.nstate[(j1 + 1) * nn_row:] == 0] = 3
                self.j1 = j1
                changed = True
            elif j1 > self.j1:
                el = slice(self.j1 * g.nr, j1 * g.nr)
                self.alive[el][self.alive[el] == 3] = 1
                nodes = slice((self.j1 + 1) * nn_row, (j1 + 1) * nn_row)
                self.nstate[nodes][self.nstate[nodes] == 3] = 0
                self.j1 = j1
                changed = True
        if c.window_behind is not None:
            j0 = int(np.searchsorted(z0, Zt - c.window_behind) - 1)
            if j0 > self.j0:
                el = np.arange(self.j0 * g.nr, j0 * g.nr)
                live = el[self.alive[el] == 1]
                self.E_window += float(self.E[K.IE, live].sum())
                self.window_mass += float(self.E[K.MASS, live].sum())
                self.alive[live] = 4
                nodes = np.arange(self.j0 * (g.nr + 1), j0 * (g.nr + 1))
                nodes = nodes[self.nstate[nodes] < 2]
                m = self.mass[nodes]
                self.E_window += 0.5 * float(np.sum(m * (self.vr[nodes] ** 2 + self.vz[nodes] ** 2)))
                self.dropped_momentum_z += float(np.sum(m * self.vz[nodes]))
                self.nstate[nodes] = 2
                self.vr[nodes] = 0.0
                self.vz[nodes] = 0.0
                self.rowdt[self.j0:j0] = 1e30
                self.j0 = j0
                changed = True
        if changed or not self._window_started:
            self._window_started = True
            self.rowdt[self.j1:] = 1e30
            self.rowhg[:self.j0] = 0.0
            self.rowhg[self.j1:] = 0.0
            self.rowero[:self.j0] = 0.0
            self.rowero[self.j1:] = 0.0
            self.rowfail[:] = -1
            self.rowbnd[:, :self.j0] = 0.0
            self.rowbnd[:, self.j1 + 1:] = 0.0
            self.dash[:] = self.dash_base
            self._mark_dashpot_rows()
            if self.j1 < g.nz:
                self._dashpots(self.j1 * (g.nr + 1) + np.arange(g.nr + 1))

    def kinetic_energy(self):
        keep = self.nstate < 2
        return 0.5 * float(np.sum(self.mass[keep] * (self.vr[keep] ** 2 + self.vz[keep] ** 2)))

    def internal_energy(self):
        return float(self.E[K.IE, self.alive == 1].sum())

    def momentum_z(self):
        keep = self.nstate < 2
        return float(np.sum(self.mass[keep] * self.vz[keep]))

    def centroids(self):
        return self.r[self.conn].mean(axis=1), self.z[self.conn].mean(axis=1)

    def _where(self, e):
        rc, zc = self.centroids()
        i, j = e % self.nr, e // self.nr
        return f"element {e} (i {i}, j {j}) at r = {rc[e]:.4g} m, z = {zc[e]:.4g} m"

    def _erode_bookkeeping(self):
        """Retire elements eroded in the last pass; free or drop nodes left without elements."""
        just = np.flatnonzero(self.alive == 2)
        if just.size == 0:
            return 0
        self.alive[just] = 0
        self.eroded_mass += float(self.E[K.MASS, just].sum())
        nodes = self.conn[just].ravel()
        np.subtract.at(self.count, nodes, 1)
        free = np.unique(nodes[self.count[nodes] == 0])
        free = free[self.nstate[free] == 0]
        if self.controls.drop_free_nodes:
            m = self.mass[free]
            self.E_eroded += 0.5 * float(np.sum(m * (self.vr[free] ** 2 + self.vz[free] ** 2)))
            self.dropped_mass += float(m.sum())
            self.dropped_momentum_z += float(np.sum(m * self.vz[free]))
            self.nstate[free] = 2
            self.vr[free] = 0.0
            self.vz[free] = 0.0
        else:
            self.nstate[free] = 1
        return just.size


@njit(cache=True)
def _advance(nr, nz, j0, j1, r, z, vr, vz, vr0, vz0, mass, nstate, on_axis, E, alive, F, kind, q, ctl, rowdt, rowhg, rowero, rowfail,
             rowbnd, fix, dash, rowdash, zp, zs, dt_prev, t, t_stop, dt_factor, proj, zeta, rho, rho_max, buf_i, buf, hist, k0,
             acc, presc_i, presc_v, load_i, load_f):
    """Steps until t_stop, the projectile at rest, an erosion (bookkeeping in Python) or a failure.

    proj = [Zt, V, M, friction, active, exit depth of the tail, stop at rest, rest velocity]; hist rows (t, Zt, V, impulse/dt, contacts, max nodal force) from k0;
    acc = [hourglass work, boundary work, contact loss, eroded IE, work of prescribed velocities,
    axial impulse of the boundary dashpots];
    presc_i, presc_v: nodes whose velocity (vr, vz) is prescribed, with the values;
    load_i, load_f: nodes carrying constant external forces (fr, fz), work booked in acc[4].
    Returns (status, dt, t, k): status 0 reached t_stop, 1 erosion happened, 2 at rest, 3 failure, 4 history full, 5 the tail left the target.
    """
    k = k0
    dt = dt_prev
    while t < t_stop:
        dt_new = dt_factor * rowdt.min() if t > 0.0 else dt_prev
        dt_new = min(dt_new, 1.2 * dt)
        dtv = 0.5 * (dt + dt_new) if t > 0.0 else dt_new
        dt = dt_new
        K_node_pass(nr, nz, j0, j1, F, alive, mass, vr, vz, vr0, vz0, nstate, dtv, fix, dash, rowdash, zp, zs, rowbnd)
        acc[1] += rowbnd[0].sum() * dtv
        acc[5] += rowbnd[1].sum() * dtv
        for a in range(load_i.size):
            n = load_i[a]
            ur, uz = vr[n], vz[n]
            vr[n] += dtv * load_f[0, a] / mass[n]
            vz[n] += dtv * load_f[1, a] / mass[n]
            if on_axis[n]:
                vr[n] = 0.0
            acc[4] += dtv * (load_f[0, a] * 0.5 * (vr0[n] + vr[n]) + load_f[1, a] * 0.5 * (vz0[n] + vz[n]))
        for a in range(presc_i.size):
            n = presc_i[a]
            acc[4] += mass[n] * ((presc_v[0, a] - vr[n]) * presc_v[0, a] + (presc_v[1, a] - vz[n]) * presc_v[1, a])
            vr[n] = presc_v[0, a]
            vz[n] = presc_v[1, a]
        imp = 0.0
        nc = 0
        fmax = 0.0
        if proj[4] > 0.5:
            V1, imp, loss, nc, fmax = K_contact(r, z, vr, vz, vr0, vz0, mass, nstate, on_axis, dt, proj[0], proj[1],
                                                proj[1], proj[2], zeta, rho, rho_max, proj[3], buf_i, buf,
                                                j0 * (nr + 1), (j1 + 1) * (nr + 1))
            acc[2] += loss
            proj[1] = V1
            proj[0] += dt * V1
        K_move(r, z, vr, vz, nstate, dt, j0 * (nr + 1), (j1 + 1) * (nr + 1))
        ctl[0] = dt
        K_element_pass(nr, nz, j0, j1, r, z, vr, vz, E, alive, F, kind, q, ctl, rowdt, rowhg, rowero, rowfail)
        acc[0] += rowhg.sum()
        acc[3] += rowero.sum()
        t += dt
        if k < hist.shape[1]:
            hist[0, k] = t
            hist[1, k] = proj[0]
            hist[2, k] = proj[1]
            hist[3, k] = imp / dt
            hist[4, k] = nc
            hist[5, k] = fmax
            k += 1
        for jj in range(nz):
            if rowfail[jj] >= 0:
                return 3, dt, t, k
        for jj in range(nz):
            if rowero[jj] != 0.0:
                return 1, dt, t, k
        if proj[6] > 0.5 and proj[1] <= proj[7]:
            return 2, dt, t, k
        if proj[4] > 0.5 and proj[0] - zeta[-1] > proj[5]:
            return 5, dt, t, k
        if k >= hist.shape[1]:
            return 4, dt, t, k
    return 0, dt, t, k


K_node_pass, K_contact, K_move, K_element_pass = K.node_pass, K.contact, K.move, K.element_pass


@dataclass
class Result:
    status: str
    time: float
    steps: int
    history: dict
    audit: list
    wall_time: float
    projectile: Projectile | None = None
    diagnostic: str = ""


def run(model: Model, projectile: Projectile | None = None, callback=None, log=None):
    """Advance ``model`` (and ``projectile``) until rest, end_time or a failure.

    callback(model, t) at every output interval (e.g. to sample fields);
    progress lines on a terminal (or to ``log``, a callable taking a string).
    Raises Unstable with a diagnostic when the run fails.
    """
    c = model.controls
    show = c.progress if c.progress is not None else bool(getattr(sys.stderr, "isatty", lambda: False)())
    nn = model.r.size
    buf_i = np.zeros(nn, np.int64)
    buf = np.zeros((4, nn))
    vr0, vz0 = np.zeros(nn), np.zeros(nn)
    if projectile is not None:
        proj = np.array([projectile.Zt, projectile.V, projectile.mass, projectile.friction, 1.0, model.z.max(),
                         float(projectile.V > 0), projectile.rest_velocity])
        zeta, rho = np.ascontiguousarray(projectile.zeta, float), np.ascontiguousarray(projectile.rho, float)
        rho_max = float(rho.max())
    else:
        proj = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        zeta, rho, rho_max = np.array([0.0, 1.0]), np.array([0.0, 0.0]), 0.0
    cap = 200_000
    hist = np.zeros((6, cap))
    k = 0
    acc = np.zeros(6)
    E0 = model.kinetic_energy() + model.internal_energy() + 0.5 * proj[2] * proj[1] ** 2 * proj[4]
    P0 = model.momentum_z() + proj[2] * proj[1] * proj[4]
    audit = []
    t0 = time.perf_counter()
    status, diag = "end_time", ""
    next_out = model.t
    dt = model.dt
    last_print = 0.0

    def record():
        ke_t = model.kinetic_energy()
        ke_p = 0.5 * proj[2] * proj[1] ** 2 * proj[4]
        ie = model.internal_energy()
        total = ke_t + ke_p + ie + acc[0] + acc[1] + acc[2] + acc[3] + model.E_eroded + model.E_window - acc[4]
        pz = model.momentum_z() + proj[2] * proj[1] * proj[4] + model.dropped_momentum_z - acc[5]
        row = dict(t=model.t, steps=model.steps, ke_target=ke_t, ke_projectile=ke_p, internal=ie, hourglass=acc[0],
                   boundary=acc[1], contact=acc[2], eroded=acc[3] + model.E_eroded, window=model.E_window, external=acc[4], total=total,
                   energy_error=(total - E0) / (E0 + abs(acc[4])) if E0 + abs(acc[4]) > 0 else 0.0, momentum_z=pz,
                   momentum_error=(pz - P0) / abs(P0) if P0 != 0 else pz, eroded_mass=model.eroded_mass,
                   dropped_mass=model.dropped_mass, window_mass=model.window_mass, depth=proj[0], velocity=proj[1], dt=dt,
                   alive=int((model.alive == 1).sum()))
        audit.append(row)
        return row

    if projectile is not None:
        model.set_window(proj[0])
    record()
    while True:
        t_stop = min(next_out + c.output_interval, c.end_time)
        st, dt, model.t, k_new = _advance(model.nr, model.nz, model.j0, model.j1, model.r, model.z, model.vr, model.vz, vr0, vz0, model.mass,
                                          model.nstate, model.on_axis, model.E, model.alive, model.F, model.kind,
                                          model.q, model.ctl, model.rowdt, model.rowhg, model.rowero, model.rowfail,
                                          model.rowbnd, model.fix, model.dash, model.rowdash, model.zp, model.zs, dt, model.t, t_stop,
                                          c.dt_factor, proj, zeta, rho, rho_max, buf_i, buf, hist, k, acc,
                                          model.presc_i, model.presc_v, model.load_i, model.load_f)
        model.steps += k_new - k
        k = k_new
        if st == 1:
            model._erode_bookkeeping()
        if projectile is not None and st in (0, 1):
            model.set_window(proj[0])
        if st == 3:
            bad = model.rowfail[:model.nz]
            jj = int(np.flatnonzero(bad >= 0)[0])
            code = int(model.rowfail[model.nz + jj])
            status = "failed"
            diag = f"{K.FAILURES.get(code, code)} at t = {model.t:.6g} s, step {model.steps}: {model._where(int(bad[jj]))}"
            break
        if st == 4:
            hist = np.concatenate([hist, np.zeros((6, cap))], axis=1)
        if st == 2:
            status = "rest"
        if st == 5:
            status = "perforated"
        if model.t >= next_out + c.output_interval - 1e-15 or st in (0, 2, 5):
            next_out = model.t
            row = record()
            if callback is not None:
                if projectile is not None:  # the callback sees the projectile's current state
                    projectile.Zt, projectile.V = float(proj[0]), float(proj[1])
                callback(model, model.t)
            if abs(row["energy_error"]) > c.max_energy_error:
                status = "failed"
                diag = (f"energy error {row['energy_error']:.3g} exceeds {c.max_energy_error} at t = {model.t:.6g} s "
                        f"(hourglass {acc[0]:.4g} J, contact {acc[2]:.4g} J, internal {row['internal']:.4g} J)")
                break
            now = time.perf_counter()
            if show or log is not None:
                if now - last_print > 2.0 or st in (2, 5):
                    last_print = now
                    line = (f"t {model.t * 1e3:8.3f} ms  steps {model.steps:7d}  depth {proj[0]:7.4f} m  "
                            f"v {proj[1]:8.2f} m/s  energy error {row['energy_error']:+.2e}  "
                            f"eroded {model.eroded_mass:8.2f} kg  wall {now - t0:6.1f} s")
                    if log is not None:
                        log(line)
                    if show:
                        print("\r" + line, end="", file=sys.stderr, flush=True)
        if st in (2, 5) or (st == 0 and model.t >= c.end_time - 1e-15):
            break
    if show:
        print(file=sys.stderr)
    model.dt = dt
    names = ("t", "depth", "velocity", "contact_force", "contacts", "max_node_force")
    history = {n: hist[i, :k].copy() for i, n in enumerate(names)}
    if projectile is not None:
        projectile.Zt, projectile.V = float(proj[0]), float(proj[1])
    res = Result(status, model.t, model.steps, history, audit, time.perf_counter() - t0, projectile, diag)
    if status == "failed":
        raise Unstable(diag)
    return res
