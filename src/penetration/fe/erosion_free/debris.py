"""Debris of the erosion-free target: where an element that lost its shape (marked by the guard, or by the lip's
ejection before a rezone) may be, and how it is booked. Nothing is deleted: a debris element is ejected (no stress
from then on, its mass and momentum kept on its nodes).

- above the struck face: ejecta (the lip thrown up along the nose);
- down to ``crater_depth`` below it: crater debris (concrete spalls from the free surface);
- deeper, with every node more than ``wall_debris_behind`` above the tip (behind the projectile's tail, out of its
  reach): wall debris of the tunnel;
- anywhere else inside the target: the run stops (``InsideTarget``), naming the element.
"""
from __future__ import annotations

from ..state import EJECTED, IE, MASS


class InsideTarget(RuntimeError):
    """An element of the erosion-free target lost its shape below the struck face (it may not be removed)."""


def eject(model, just):
    """Eject the elements ``just`` of an erosion-free model (their controls: ``model.controls.erosion_free``), booking
    their mass as ejected, crater or wall debris and their internal energy as ejecta; raise InsideTarget for one
    that may not go."""
    c = model.controls.erosion_free
    zc = model.z[model.conn[just]].mean(axis=1)
    crater = c.crater_depth or 0.0
    deep = just[zc >= crater]
    behind = c.wall_debris_behind
    wall = deep[:0]
    if deep.size and behind is not None:
        reach = model.z[model.conn[deep]].max(axis=1) < model.tip - behind
        wall, deep = deep[reach], deep[~reach]
    if deep.size:
        raise InsideTarget(f"{model.where(int(deep[0]))} lost its shape inside the target at t = {model.t:.6g} s")
    ledger = model.ledger
    ledger.wall_debris_mass += float(model.E[MASS, wall].sum())
    model.alive[just] = EJECTED
    ledger.ejected_mass += float(model.E[MASS, just].sum())
    ledger.crater_debris_mass += float(model.E[MASS, just[(zc >= 0.0) & (zc < crater)]].sum())
    ledger.ejecta += float(model.E[IE, just].sum())
