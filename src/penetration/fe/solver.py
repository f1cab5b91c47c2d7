"""The explicit solver: the central-difference step, the time loop, and a run with its audit.

One step (``step``), as the textbook writes it:

1. node pass: v^{n+1/2} = v^{n-1/2} + dt a^n from the element forces of step n, with the boundary dashpots and
   fixities (``nodes.node_pass``), then the external loads and prescribed velocities (``nodes.external``);
2. contact: the kinematic contact corrects v^{n+1/2} and the rigid projectile moves (``contact.contact``);
3. move: x^{n+1} = x^n + dt v^{n+1/2} (``nodes.move``);
4. element pass: strain rates and spin from the half-step geometry, stress update, internal energy, viscosity,
   erosion, the stable step and the forces at x^{n+1} (``element_pass.element_pass``).

``advance`` repeats it until a stop time, an erosion (its bookkeeping is ``erosion.retire``'s), the projectile's
rest or exit, or a failure; ``run`` loops over output intervals, records the audit (``audit.Audit``), moves the
window and reports progress through ``logging`` (logger ``penetration.fe``).
"""
from __future__ import annotations

import logging
import time
from collections import namedtuple
from dataclasses import dataclass

import numpy as np
from numba import njit

from .audit import Audit
from .contact import Projectile, contact
from .element_pass import element_pass
from .erosion_free.debris import InsideTarget
from .model import Model, body_of
from .nodes import external, guide, move, node_pass
from .state import (A_BOUNDARY, A_BOUNDARY_IMPULSE, A_CONTACT, A_ERODED, A_HOURGLASS, A_STEPS, AT_REST, B_ACTIVE,
                    B_EXIT, B_REST_VELOCITY, B_STOP_AT_REST, B_TIP, B_VELOCITY, C_DT, EROSION, FAILED, FAILURES,
                    H_CONTACTS, H_DEPTH, H_FORCE, H_MAX_FORCE, H_T, H_VELOCITY, HISTORY, HISTORY_FULL, INITIAL, N_ACC,
                    N_BODY, PAUSED, PERFORATED, REACHED, RF_ERO, RF_HG, RF_IMPULSE, RF_POWER, RI_FAIL, Record)
from .timestep import next_step

LOG = logging.getLogger("penetration.fe")
# the step's view of a model: read through the named tuples, written through the arrays (see ``state``)
State = namedtuple("State", "span nodes kind q bc loads body E F alive X V rf ri")
HISTORY_CHUNK = 200_000


@njit(cache=True)
def step(st, proj, ctl, acc, dt, dtv):
    """One explicit step of the state st by dt (velocities by dtv, the mean of the last step and this one);
    returns (contact impulse, contacts, largest nodal contact force)."""
    bc = st.bc
    node_pass(st.span, st.F, st.alive, st.nodes.mass, st.nodes.state, bc.fix, bc.dash, bc.rowdash, (bc.zp, bc.zs), dtv,
              st.V, st.rf)
    acc[A_BOUNDARY] += st.rf[RF_POWER].sum() * dtv
    acc[A_BOUNDARY_IMPULSE] += st.rf[RF_IMPULSE].sum() * dtv
    external(st.nodes, st.loads, dtv, acc)
    imp, nc, fmax = 0.0, 0, 0.0
    if proj[B_ACTIVE] > 0.5:
        V1, imp, loss, nc, fmax = contact(st.span, st.nodes, st.body, proj, dt)
        acc[A_CONTACT] += loss
        proj[B_VELOCITY] = V1
        proj[B_TIP] += dt * V1
    acc[A_CONTACT] += guide(st.span, st.nodes, bc.guide, dt)
    move(st.span, st.X, st.V, st.nodes.state, dt)
    ctl[C_DT] = dt
    element_pass(st.span, st.X, st.V, st.kind, st.q, ctl, st.E, st.F, st.alive, st.rf, st.ri)
    nz = st.span.nz
    acc[A_HOURGLASS] += st.rf[RF_HG, :nz].sum()
    acc[A_ERODED] += st.rf[RF_ERO, :nz].sum()
    return imp, nc, fmax


@njit(cache=True)
def advance(st, proj, ctl, rec, t, dt, t_stop, dt_factor, k, k_pause):
    """Steps from t (the last step dt) until t_stop, an erosion, the projectile at rest or out of the target, a
    failure, a full history (rec.hist from column k) or step k_pause. Returns (status, dt, t, k)."""
    hist, acc, ctrl = rec.hist, rec.acc, rec.ctrl
    while t < t_stop:
        dt_new, crit, element = next_step(st.rf, st.ri, st.span.nz, dt, t, dt_factor)
        dtv = 0.5 * (dt + dt_new) if t > 0.0 else dt_new
        dt = dt_new
        acc[A_STEPS + crit] += 1.0
        ctrl[0], ctrl[1] = crit, element
        imp, nc, fmax = step(st, proj, ctl, acc, dt, dtv)
        t += dt
        if k < hist.shape[1]:
            hist[H_T, k] = t
            hist[H_DEPTH, k] = proj[B_TIP]
            hist[H_VELOCITY, k] = proj[B_VELOCITY]
            hist[H_FORCE, k] = imp / dt
            hist[H_CONTACTS, k] = nc
            hist[H_MAX_FORCE, k] = fmax
            k += 1
        for jj in range(st.span.nz):
            if st.ri[RI_FAIL, jj] >= 0:
                return FAILED, dt, t, k
        for jj in range(st.span.nz):
            if st.rf[RF_ERO, jj] != 0.0:
                return EROSION, dt, t, k
        if proj[B_STOP_AT_REST] > 0.5 and proj[B_VELOCITY] <= proj[B_REST_VELOCITY]:
            return AT_REST, dt, t, k
        if proj[B_ACTIVE] > 0.5 and proj[B_TIP] - st.body.zeta[-1] > proj[B_EXIT]:
            return PERFORATED, dt, t, k
        if k >= hist.shape[1]:
            return HISTORY_FULL, dt, t, k
        if k >= k_pause:
            return PAUSED, dt, t, k
    return REACHED, dt, t, k


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
    dt_shares: dict | None = None       # share of the steps each time-step criterion controlled
    dt_control: str = ""                # the last step's criterion and element


def state_of(model, body):
    """The step's view of ``model`` and the projectile's kernel view ``body`` (``body_of``): its arrays as they are
    now (an erosion or a remap may replace them between calls of ``advance``)."""
    return State(model.span(), model.nodes(), model.kind, model.q, model.boundary(), model.loads(), body, model.E,
                 model.F, model.alive, model.X, model.V, model.rows.f, model.rows.i)


class Unstable(RuntimeError):
    """A run stopped early: names the quantity, where and when."""


def _projectile_state(model, projectile):
    p = np.zeros(N_BODY)
    if projectile is not None:
        p[:] = (projectile.Zt, projectile.V, projectile.mass, projectile.friction, 1.0, model.z.max(),
                float(projectile.V > 0), projectile.rest_velocity)
    else:
        p[2] = 1.0
    return p


def _failure(model):
    bad = np.flatnonzero(model.rows.fail >= 0)[0]
    code = int(model.rows.code[bad])
    return (f"{FAILURES.get(code, code)} at t = {model.t:.6g} s, step {model.steps}: "
            f"{model.where(int(model.rows.fail[bad]))}")


def run(model: Model, projectile: Projectile | None = None, callback=None):
    """Advance ``model`` (and ``projectile``) until rest, end_time or a failure.

    callback(model, t) at every output interval (e.g. to sample fields); progress every 2 s of wall time to the
    logger ``penetration.fe`` at INFO. Raises Unstable with a diagnostic when the run fails.
    """
    c = model.controls
    proj = _projectile_state(model, projectile)
    rec = Record(np.zeros((len(HISTORY), HISTORY_CHUNK)), np.zeros(N_ACC), np.array([INITIAL, -1], np.int64))
    audit = Audit(model, proj)
    t0 = time.perf_counter()
    status, diag, k, next_out, dt, last_log = "end_time", "", 0, model.t, model.dt, 0.0
    body = body_of(projectile, model.r.size)
    if projectile is not None:
        model.set_window(proj[B_TIP])
    audit.record(rec.acc, rec.ctrl, dt)
    while True:
        st = state_of(model, body)
        k_pause = k + c.erosion_free.rezone_every if c.erosion_free else np.iinfo(np.int64).max
        code, dt, model.t, k_new = advance(st, proj, model.ctl, rec, model.t, dt,
                                           min(next_out + c.output_interval, c.end_time), c.dt_factor, k, k_pause)
        model.steps += k_new - k
        k = k_new
        if code == EROSION:
            try:
                model.retire_eroded()
            except InsideTarget as err:
                status, diag = "failed", str(err)
                break
            if c.erosion_free:
                rec.acc[A_ERODED] = 0.0   # the guard's elements were ejecta (booked as the ledger's ejecta)
        if c.erosion_free and code in (REACHED, PAUSED):
            bad = model.rezone()
            if bad:
                status, diag = "failed", f"the remap would empty {model.where(bad)} at t = {model.t:.6g} s"
                break
        if projectile is not None and code in (REACHED, EROSION, PAUSED):
            model.set_window(proj[B_TIP])
        if code == FAILED:
            status, diag = "failed", _failure(model)
            break
        if code == HISTORY_FULL:
            rec = rec._replace(hist=np.concatenate([rec.hist, np.zeros((len(HISTORY), HISTORY_CHUNK))], axis=1))
        status = {AT_REST: "rest", PERFORATED: "perforated"}.get(code, status)
        if model.t >= next_out + c.output_interval - 1e-15 or code in (REACHED, AT_REST, PERFORATED):
            next_out = model.t
            row = audit.record(rec.acc, rec.ctrl, dt)
            if callback is not None:
                if projectile is not None:  # the callback sees the projectile's current state
                    projectile.Zt, projectile.V = float(proj[B_TIP]), float(proj[B_VELOCITY])
                callback(model, model.t)
            if abs(row["energy_error"]) > c.max_energy_error:
                status = "failed"
                diag = (f"energy error {row['energy_error']:.3g} exceeds {c.max_energy_error} at t = {model.t:.6g} s "
                        f"(hourglass {row['hourglass']:.4g} J, contact {row['contact']:.4g} J, internal {row['internal']:.4g} J)")
                break
            now = time.perf_counter()
            if now - last_log > 2.0 or code in (AT_REST, PERFORATED):
                last_log = now
                LOG.info("t %8.3f ms  steps %7d  depth %7.4f m  v %8.2f m/s  energy error %+.2e  eroded %8.2f kg  "
                         "dt by %s  wall %6.1f s", model.t * 1e3, model.steps, proj[B_TIP], proj[B_VELOCITY],
                         row["energy_error"], model.ledger.eroded_mass, row["dt_criterion"], now - t0)
        if code in (AT_REST, PERFORATED) or (code == REACHED and model.t >= c.end_time - 1e-15):
            break
    model.dt = dt
    history = {n: rec.hist[i, :k].copy() for i, n in enumerate(HISTORY)}
    if projectile is not None:
        projectile.Zt, projectile.V = float(proj[B_TIP]), float(proj[B_VELOCITY])
    shares, crit, where = audit.controlling()
    res = Result(status, model.t, model.steps, history, audit.rows, time.perf_counter() - t0, projectile, diag,
                 shares, f"{crit}: {where}")
    if status == "failed":
        raise Unstable(diag)
    return res
