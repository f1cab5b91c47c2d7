"""One shot at the finite-element level: the mesh, model and projectile of a run spec (``spec.RunSpec``), its run,
and its results (depth, filtered deceleration, audit, nose pressure, the share of the tunnel eroded).

``run_shot(spec)`` runs a spec built once (``fe.level.scene_spec`` for a scene
of the pipeline, ``shots.ladder.fe_spec`` for a user's shot); nothing is read from
elsewhere after that.
"""
from __future__ import annotations

import contextlib
import logging
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.signal import butter, filtfilt

from . import state as fe_state
from .contact import Projectile
from .erosion_free.controls import ErosionFree
from .mesh import MeshSpec, body_outline, build
from .model import Model
from .solver import LOG, run
from .spec import BLOCK_RADIUS, Controls, RunSpec, Settings, TargetSpec  # noqa: F401 (the level's names)

G0 = 9.80665


def mesh_spec(nose, settings: Settings, target: TargetSpec, expected_depth) -> MeshSpec:
    """The target's mesh for a shot: the block's depth, or the expected depth plus the margin (semi-infinite)."""
    if target.kind == "block":
        depth = target.depth or 5.4
    else:
        depth = target.depth or expected_depth + settings.depth_margin
    h = settings.element_size
    hole = target.pilot_hole * nose.radius if target.formulation == "erosion_free" else 0.0
    return MeshSpec(h, settings.core_calibers * nose.radius,
                    min(depth, expected_depth + 0.5 * settings.depth_margin), target.radius, depth, settings.grading,
                    pilot_hole=hole, opened_radius=nose.radius if hole else 0.0)


def model_for(nose, settings: Settings, target: TargetSpec, material, expected_depth):
    lateral, bottom = target.boundary("lateral"), target.boundary("bottom")
    spec = mesh_spec(nose, settings, target, expected_depth)
    behind = None if settings.window_tail is None else settings.body_length + settings.window_tail
    controls = replace(settings.controls, lateral=lateral, bottom=bottom, output_interval=settings.output_interval,
                       window_ahead=settings.window_ahead, window_behind=behind)
    if target.formulation == "erosion_free":
        # rezoned out to twice the core (the crater's heave reaches past the core); what flies farther than the shank
        # radius above the struck face, or loses its shape above it, is ejected (fe.erosion_free.rezone.eject, fe.erosion_free.debris); so is
        # what thins in the crater (down to four shank radii) once the whole projectile has passed below it; deeper,
        # an element of the tunnel's wall that loses its shape behind the projectile's tail is wall debris
        given = controls.erosion_free or ErosionFree()
        crater = 4.0 * nose.radius if given.crater_depth is None else given.crater_depth
        scale = target.ejection_scale   # > 1: the lip ejects more readily (thicker elements, nearer the face)
        free = replace(given, pilot_guide=target.pilot_guide, rezone_radius=2.0 * spec.core_radius,
                       eject_length=min(1.0, given.eject_length * scale),
                       eject_height=(nose.radius if given.eject_height is None else given.eject_height) / scale,
                       crater_depth=crater,
                       crater_thin_after=(crater + settings.body_length if given.crater_thin_after is None
                                          else given.crater_thin_after),
                       wall_debris_behind=(settings.body_length if given.wall_debris_behind is None
                                           else given.wall_debris_behind))
        controls = replace(controls, erosion_free=free, guard=True, drop_free_nodes=False)
    return Model(build(spec), material, controls)


def binned(t, force, mass, bin_width):
    """Deceleration (m/s^2) in bins of bin_width: each bin's contact impulse over mass times bin width."""
    if t.size == 0:
        return np.zeros(0), np.zeros(0)
    dt = np.diff(np.concatenate(([0.0], t)))
    n = max(1, int(math.ceil(t[-1] / bin_width)))
    idx = np.minimum((t / bin_width).astype(int), n - 1)
    decel = np.bincount(idx, weights=force * dt, minlength=n) / (mass * bin_width)
    return (np.arange(n) + 0.5) * bin_width, decel


def lowpass(x, bin_width, cutoff):
    """Zero-phase fourth-order Butterworth low-pass at ``cutoff`` (Hz) of a series sampled every bin_width."""
    if cutoff is None or x.size < 20 or cutoff >= 0.5 / bin_width:
        return x
    b, a_ = butter(4, cutoff * 2 * bin_width)
    return filtfilt(b, a_, x, padlen=min(3 * max(len(a_), len(b)), x.size - 1))


def filtered(t, force, mass, bin_width, cutoff):
    """Binned deceleration, low-passed at cutoff (None: the raw bins)."""
    tb, decel = binned(t, force, mass, bin_width)
    return tb, lowpass(decel, bin_width, cutoff)


def nose_pressure(model, projectile, nose, h):
    """Largest normal pressure (Pa) on the nose now: -sigma_nn of live elements whose centre lies within one
    element of the nose surface, with the surface normal at the same distance behind the tip."""
    rc, zc = model.centroids()
    zeta = projectile.Zt - zc
    near = (model.alive == fe_state.LIVE) & (zeta > -h) & (zeta < nose.length)
    if not near.any():
        return 0.0
    zn = np.clip(zeta[near], 0.0, nose.length)
    y = nose.radius_at(zn)
    near_idx = np.flatnonzero(near)
    keep = rc[near] < y + 2.5 * h
    if not keep.any():
        return 0.0
    e = near_idx[keep]
    beta = nose.angle(zn[keep])
    nr_, nz_ = np.cos(beta), np.sin(beta)
    E = model.E
    srr, szz, srz = E[fe_state.SRR, e] - E[fe_state.P, e], E[fe_state.SZZ, e] - E[fe_state.P, e], E[fe_state.SRZ, e]
    return float(np.max(-(srr * nr_ ** 2 + szz * nz_ ** 2 + 2 * srz * nr_ * nz_)))


def tunnel_eroded_share(model, radius, depth):
    """Share of the tunnel's initial volume (elements whose initial centre lies within ``radius`` of the axis and
    between the surface and ``depth``) that erosion deleted: 1 when the tunnel was all deleted, 0 when all of
    it was pushed aside. Volumes 2 pi r0 A0 from the initial tensor grid."""
    g = model.grid
    r, z = g.r, g.z
    rc, zc = 0.5 * (r[1:] + r[:-1]), 0.5 * (z[1:] + z[:-1])
    vol = 2 * np.pi * np.outer(np.diff(z), rc * np.diff(r))  # [row j, column i], as the elements are numbered
    inside = (zc[:, None] < depth) & (zc[:, None] > 0) & (rc[None, :] < radius)
    eroded = np.isin(model.alive.reshape(g.nz, g.nr), (fe_state.ERODED, fe_state.ERODING))
    total = vol[inside].sum()
    return float(vol[inside & eroded].sum() / total) if total > 0 else math.nan


@dataclass
class ShotResult:
    depth: float
    time: float
    status: str
    peak_deceleration: float
    histories: dict
    audit: list
    wall_time: float
    steps: int
    elements: int
    eroded_mass: float
    max_nose_pressure: float
    model: Model | None = None
    attempts: int = 1
    tunnel_eroded_share: float = math.nan
    dt_shares: dict = field(default_factory=dict)   # share of the steps each time-step criterion controlled
    dt_control: str = ""                             # the last step's criterion and element
    snapshots: list = field(default_factory=list)    # the target's state at the requested times and at the end
    conn: object = None                              # the elements' corner nodes (the snapshots' cells)

    def summary(self):
        last = self.audit[-1]
        worst = max(abs(r["energy_error"]) for r in self.audit)
        ie = last["internal"] + last["eroded"]
        return {"depth_m": self.depth, "time_to_rest_s": self.time, "status": self.status,
                "peak_deceleration_m_s2": self.peak_deceleration, "wall_time_s": self.wall_time, "steps": self.steps,
                "elements": self.elements, "element_steps": self.steps * self.elements,
                "eroded_mass_kg": self.eroded_mass, "max_nose_pressure_pa": self.max_nose_pressure,
                "energy_error_max": worst, "energy_error_final": last["energy_error"],
                "momentum_error_final": last["momentum_error"], "hourglass_over_internal": last["hourglass"] / max(ie, 1e-300),
                "contact_loss_fraction": last["contact"] / max(last["total"], 1e-300), "attempts": self.attempts,
                "tunnel_eroded_share": self.tunnel_eroded_share, "ejected_mass_kg": last.get("ejected_mass", 0.0),
                "crater_debris_mass_kg": last.get("crater_debris_mass", 0.0),
                "wall_debris_mass_kg": last.get("wall_debris_mass", 0.0),
                "remap_energy_j": last.get("remap", 0.0),
                **{f"dt_share_{k}": v for k, v in self.dt_shares.items()}, "dt_control": self.dt_control}


@contextlib.contextmanager
def progress_to(log):
    """Progress of the solver's logger also to the callable ``log`` (a line at a time) while the block runs (None:
    nothing added)."""
    if log is None:
        yield
        return

    class Forward(logging.Handler):
        def emit(self, record):
            log(record.getMessage())

    handler = Forward(logging.INFO)
    level = LOG.level
    LOG.addHandler(handler)
    LOG.setLevel(logging.INFO)
    try:
        yield
    finally:
        LOG.removeHandler(handler)
        LOG.setLevel(level)


def snapshot(model, t, depth) -> dict:
    """The target's state now: node positions (m), and per element its damage, plastic strain, pressure (Pa) and
    state code (fe.state: LIVE 1; eroded, ejected and the others carry no stress)."""
    return {"t": float(t), "depth": float(depth), "r": model.r.copy(), "z": model.z.copy(),
            "damage": model.E[fe_state.DMG].copy(), "eps_p": model.E[fe_state.EPSP].copy(),
            "pressure": model.E[fe_state.P].copy(), "state": np.asarray(model.alive).copy()}


def run_shot(spec: RunSpec, keep_model=False, max_attempts=3, snapshot_times=()) -> ShotResult:
    """Penetration of the spec's rigid projectile into its FE target; progress through the solver's logger.
    ``snapshot_times`` (s): the target's state is kept at the first output at or after each (and at the end)."""
    settings, target, nose = spec.settings, spec.target, spec.nose
    expected = spec.expected_depth
    zeta, rho = body_outline(nose, settings.body_length)
    for attempt in range(1, max_attempts + 1):
        model = model_for(nose, settings, target, spec.material, expected)
        proj = Projectile(zeta, rho, spec.mass, 0.0, spec.velocity, spec.friction)
        pmax = [0.0]
        pending, shots = sorted(float(x) for x in snapshot_times), []

        def sample(m, t):
            pmax[0] = max(pmax[0], nose_pressure(m, proj, nose, settings.element_size))
            if pending and t >= pending[0] - 1e-15:   # one snapshot for every requested time up to now
                while pending and t >= pending[0] - 1e-15:
                    pending.pop(0)
                shots.append(snapshot(m, t, proj.Zt))

        t0 = time.perf_counter()
        res = run(model, proj, callback=sample)
        wall = time.perf_counter() - t0
        if (res.status == "perforated" and target.kind == "semi_infinite" and target.depth is None
                and attempt < max_attempts):
            expected *= 2.0
            LOG.info("reached the bottom of a %.2f m domain: repeating 2 times deeper", model.z.max())
            continue
        break
    if snapshot_times:
        shots.append(snapshot(model, res.time, proj.Zt))
    h = res.history
    tb, dec = filtered(h["t"], h["contact_force"], spec.mass, settings.bin_width, settings.cutoff_hz)
    return ShotResult(float(proj.Zt), float(res.time), res.status, float(dec.max()) if dec.size else 0.0,
                      {"t": h["t"], "depth": h["depth"], "velocity": h["velocity"], "contact_force": h["contact_force"],
                       "t_bins": tb, "deceleration": dec}, res.audit, wall, res.steps, model.grid.elements,
                      model.ledger.eroded_mass, pmax[0], model if keep_model else None, attempt,
                      tunnel_eroded_share(model, nose.radius, float(proj.Zt)), res.dt_shares, res.dt_control,
                      shots, model.conn.copy() if snapshot_times else None)
