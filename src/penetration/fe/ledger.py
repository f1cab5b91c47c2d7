"""The ledger: what leaves the model's mechanical state during a run and where it goes, one named entry each.

The kernels keep their own accumulators in the run's record (``state.A_*``: hourglass work, boundary work and
impulse, contact losses, eroded elements' internal energy, external work); everything booked outside the kernels is
an entry here, and the audit (``audit.Audit``) balances the two together:

- ``eroded`` (J): kinetic energy of the nodes dropped with eroded elements; ``eroded_mass`` (kg) the elements'
  mass, ``dropped_mass`` (kg) and ``dropped_momentum_z`` (N s) the dropped nodes' (erosion and the moving window);
- ``window`` (J), ``window_mass`` (kg): what the moving window retired behind the projectile;
- ``ejecta`` (J): internal energy of the erosion-free target's ejected elements (their mass and momentum stay in
  the model), ``ejected_mass`` (kg) of which ``crater_debris_mass`` and ``wall_debris_mass`` (kg) were debris
  below the struck face (``erosion_free.debris``);
- ``remapped``: the erosion-free rezones' report (``erosion_free.rezone``: the kinetic energy and axial momentum
  the velocity remap changed, the node moves).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .erosion_free.rezone import R_COUNT, R_ENERGY, R_MOMENTUM


@dataclass
class Ledger:
    eroded: float = 0.0
    eroded_mass: float = 0.0
    dropped_mass: float = 0.0
    dropped_momentum_z: float = 0.0
    window: float = 0.0
    window_mass: float = 0.0
    ejecta: float = 0.0
    ejected_mass: float = 0.0
    crater_debris_mass: float = 0.0
    wall_debris_mass: float = 0.0
    remapped: np.ndarray = field(default_factory=lambda: np.zeros(R_COUNT + 1))

    @property
    def remap(self):
        """Kinetic energy the rezones' remap removed (J)."""
        return float(self.remapped[R_ENERGY])

    @property
    def remap_momentum_z(self):
        return float(self.remapped[R_MOMENTUM])
