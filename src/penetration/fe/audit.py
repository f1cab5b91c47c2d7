"""The audit: energy and momentum balance of a run, and what controlled its time step, one record per output.

Energy balance:

    KE_target + KE_projectile + IE + W_hourglass + E_eroded + W_contact + W_boundary + E_window + E_remap
        + E_ejecta - W_external = E_0

(the entries of the run's record, ``state.A_*``, and of the model's ledger, ``ledger.Ledger``) with E_eroded the
internal energy of eroded elements plus the kinetic energy of dropped free nodes, W_contact the
kinetic energy the kinematic contact removes (its impulses are perfectly inelastic), W_boundary the work absorbed
by non-reflecting boundaries, E_window what the moving window retired, W_external the work of loads and
prescribed velocities, E_remap the kinetic energy the erosion-free target's remap removed (``fe.erosion_free.rezone``) and
E_ejecta the internal energy of its ejected elements (their mass and kinetic energy stay in the model). The error
is reported relative to E_0 (plus |W_external|). The axial momentum balances likewise with the dropped nodes'
momentum, the remap's and the dashpots' impulse.

Each record also gives, for the steps since the previous record, the share each time-step criterion
(``state.CRITERIA``) controlled, and the element that controlled the last of them.
"""
from __future__ import annotations

import numpy as np

from .state import (A_BOUNDARY, A_BOUNDARY_IMPULSE, A_CONTACT, A_ERODED, A_EXTERNAL, A_HOURGLASS, A_STEPS, B_ACTIVE,
                    B_MASS, B_TIP, B_VELOCITY, CRITERIA, LIVE)


class Audit:
    """The records of a run; ``E0``, ``P0``: the energy and axial momentum at its start."""

    def __init__(self, model, proj):
        self.model, self.proj = model, proj
        self.E0 = model.kinetic_energy() + model.internal_energy() + self._ke_projectile()
        self.P0 = model.momentum_z() + proj[B_MASS] * proj[B_VELOCITY] * proj[B_ACTIVE]
        self.rows = []

    def _ke_projectile(self):
        p = self.proj
        return 0.5 * p[B_MASS] * p[B_VELOCITY] ** 2 * p[B_ACTIVE]

    def record(self, acc, ctrl, dt):
        """Append the record of now (acc: the run's accumulators; ctrl: the last step's criterion and element); the
        step counts per criterion in acc are reset."""
        m, p = self.model, self.proj
        ke_t, ke_p, ie = m.kinetic_energy(), self._ke_projectile(), m.internal_energy()
        L = m.ledger
        total = (ke_t + ke_p + ie + acc[A_HOURGLASS] + acc[A_BOUNDARY] + acc[A_CONTACT] + acc[A_ERODED] + L.eroded
                 + L.window + L.remap + L.ejecta - acc[A_EXTERNAL])
        pz = (m.momentum_z() + p[B_MASS] * p[B_VELOCITY] * p[B_ACTIVE] + L.dropped_momentum_z + L.remap_momentum_z
              - acc[A_BOUNDARY_IMPULSE])
        scale = self.E0 + abs(acc[A_EXTERNAL])
        steps = acc[A_STEPS:A_STEPS + len(CRITERIA)]
        n = steps.sum()
        row = dict(t=m.t, steps=m.steps, ke_target=ke_t, ke_projectile=ke_p, internal=ie, hourglass=acc[A_HOURGLASS],
                   boundary=acc[A_BOUNDARY], contact=acc[A_CONTACT], eroded=acc[A_ERODED] + L.eroded,
                   window=L.window, remap=L.remap, ejecta=L.ejecta, external=acc[A_EXTERNAL], total=total,
                   energy_error=(total - self.E0) / scale if scale > 0 else 0.0, momentum_z=pz,
                   momentum_error=(pz - self.P0) / abs(self.P0) if self.P0 != 0 else pz, eroded_mass=L.eroded_mass,
                   ejected_mass=L.ejected_mass, crater_debris_mass=L.crater_debris_mass,
                   wall_debris_mass=L.wall_debris_mass,
                   dropped_mass=L.dropped_mass, window_mass=L.window_mass, depth=p[B_TIP], velocity=p[B_VELOCITY], dt=dt,
                   alive=int((m.alive == LIVE).sum()),
                   **{f"dt_share_{name}": (steps[c] / n if n else 0.0) for c, name in CRITERIA.items()},
                   dt_criterion=CRITERIA[int(ctrl[0])], dt_element=int(ctrl[1]))
        steps[:] = 0.0
        self.rows.append(row)
        return row

    def controlling(self):
        """The time-step criteria's shares over the whole run (weighted by each record's steps) and the element that
        controlled the last step, with its place."""
        steps = np.diff([0] + [r["steps"] for r in self.rows])
        total = max(int(steps.sum()), 1)
        share = {name: float(sum(s * r[f"dt_share_{name}"] for s, r in zip(steps, self.rows)) / total)
                 for name in CRITERIA.values()}
        last = self.rows[-1]
        where = self.model.where(last["dt_element"]) if last["dt_element"] >= 0 else "none (not an element's step)"
        return share, last["dt_criterion"], where
