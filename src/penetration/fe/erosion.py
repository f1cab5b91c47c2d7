"""Erosion: the one criterion that deletes an element, and the bookkeeping of what it removes.

An element erodes once its criterion's quantity reaches the erosion value: the equivalent plastic strain
(``plastic_strain``, LS-DYNA's *MAT_ADD_EROSION with the failure strain the paper calibrates), the accumulated
equivalent strain (``effective_strain``), the volumetric tension 1/mu_ratio - 1 (``volumetric_tension``) or the
damage (``damage``). The element pass marks it ERODING and books its internal energy; ``retire`` then removes it
and drops (or frees) the nodes it leaves without any element, booking their mass, kinetic energy and momentum. On
the erosion-free target nothing erodes: the guard's elements are debris (``erosion_free.debris``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .erosion_free import debris
from .state import ACTIVE, DAMAGE, EFFECTIVE_STRAIN, ERODED, ERODING, FREE, MASS, PLASTIC_STRAIN, VOLUMETRIC_TENSION


@njit(cache=True, inline="always", error_model="numpy")
def erodes(kind, value, eps_p, eps_eff, damage, vol_tension):
    """Whether an element with these state variables erodes under criterion ``kind`` at ``value`` (branch-free;
    the kinematics phase passes vol_tension = inf, which leaves every element of the volumetric criterion to the
    scalar phase: its division would cost every element)."""
    return (((kind == PLASTIC_STRAIN) & (eps_p >= value)) | ((kind == EFFECTIVE_STRAIN) & (eps_eff >= value))
            | ((kind == VOLUMETRIC_TENSION) & (vol_tension >= value)) | ((kind == DAMAGE) & (damage >= value)))


def retire(model):
    """Remove the elements eroded in the last pass; drop (or keep as free) the nodes left without an element.
    Returns how many elements were removed."""
    just = np.flatnonzero(model.alive == ERODING)
    if just.size == 0:
        return 0
    if model.controls.erosion_free:   # nothing is deleted: the guard's elements are debris (fe.erosion_free.debris)
        debris.eject(model, just)
    else:
        model.alive[just] = ERODED
        model.ledger.eroded_mass += float(model.E[MASS, just].sum())
    nodes = model.conn[just].ravel()
    np.subtract.at(model.count, nodes, 1)
    free = np.unique(nodes[model.count[nodes] == 0])
    free = free[model.nstate[free] == ACTIVE]
    if model.controls.drop_free_nodes and not model.controls.erosion_free:
        kinetic, mass = model.drop_nodes(free)
        model.ledger.eroded += kinetic
        model.ledger.dropped_mass += mass
    else:
        model.nstate[free] = FREE
    return just.size
