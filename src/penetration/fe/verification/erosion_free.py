"""Verification problems of the erosion-free target (registered in ``PROBLEMS``, which ``fe.verification`` joins): what is new in it, the
nose opening the tunnel by pushing the concrete aside, with an audit that has no eroded term. (Its remap is checked
on Blake's cavity, rezoned: ``verification_mechanics``.)"""
from __future__ import annotations

import functools

import numpy as np

from ...checks import Check, below as _below
from ...concrete.hjc import HJC
from ..solver import run
from .common import problems
from .quasi_static import driven_ogive

PROBLEMS, problem = problems()


@functools.lru_cache(maxsize=4)
def _driven(v, across, hole, guide):
    """The driven check's run (the quasi-static check's set-up, 50 outputs, no crater debris), once per set-up and
    process: (model, projectile, result, the smallest radius of the hole's wall over the run / its radius, the
    audit's energy error over the work done on the target, whose 1e6 kg projectile's energy would hide it)."""
    m, p = driven_ogive(across, hole, v, HJC(), outputs=50, crater_depth=None, guide=guide)
    wall = np.arange(m.nz + 1) * (m.nr + 1)   # node column 0: the hole's wall
    r0, inner = float(m.r[0]), [np.inf]
    res = run(m, p, callback=lambda mm, t: inner.append(float(mm.r[wall].min())))
    audit = res.audit[-1]
    work = audit["internal"] + audit["ke_target"] + audit["hourglass"] + audit["contact"] + audit["boundary"]
    return m, p, res, min(inner) / r0, audit["energy_error"] * _scale(res) / work


@problem("erosion-free penetration audit")
def erosion_free_audit(v=40.0, across=4, hole=0.25):
    """A CRH 3 ogive (20 mm shank radius) driven at a constant 40 m/s into the erosion-free HJC target (pilot hole
    1/4 of the radius, 4 elements across it) to 14 radii: the drive holds the speed, and the audit closes with no
    eroded term (the eroded mass and energy exactly 0; the remap's and the ejecta's terms booked)."""
    name = f"erosion-free penetration audit (CRH 3, a = 20 mm, {v:g} m/s driven, hole {hole:g} a)"
    m, p, res, _, error = _driven(v, across, hole, False)
    return [Check(name, "projectile speed at the end / v", p.V / v, 1.0, 1.0 - 1e-3, 1.0 + 1e-3, "1",
                  "1: driven at a constant speed (1e6 kg; within 1e-3)"),
            _below(name, "eroded mass + |eroded energy| (no element deleted)",
                   m.ledger.eroded_mass + abs(res.audit[-1]["eroded"]), 1e-300, "kg + J",
                   "0 exactly: the erosion-free target deletes nothing (exact)"),
            _below(name, "|energy error| / work done on the target (no eroded term)", abs(error), 0.01, "1",
                   "conservation (the audit with the remap's and the ejecta's terms)")]


@problem("erosion-free pilot guide")
def erosion_free_guide(v=40.0, across=4, hole=0.25):
    """The driven check of the erosion-free penetration audit with a rigid frictionless guide filling the pilot hole
    (TargetSpec.pilot_guide): without it the hole's wall moves inside its radius ahead of the nose (the check says
    by how much; the audit problem's run); with it no wall node does, and the guide's radial impulses, booked with
    the contact's, keep the audit closed."""
    name = f"erosion-free pilot guide (CRH 3, a = 20 mm, {v:g} m/s driven, hole {hole:g} a)"
    without, with_guide = _driven(v, across, hole, False), _driven(v, across, hole, True)
    return [_below(name, "smallest radius of the hole's wall / its radius, without the guide", without[3],
                   1.0 - 1e-3, "1", "< 1: the wall moves into the hole ahead of the nose (what the guide is for)"),
            Check(name, "smallest radius of the hole's wall / its radius, with the guide", with_guide[3], 1.0,
                  1.0 - 1e-9, 1.0 + 1e-9, "1", "1: no wall node inside the guide (exact up to round-off)"),
            _below(name, "|energy error| / work done on the target, with the guide", abs(with_guide[4]), 0.01, "1",
                   "conservation (the guide's impulses booked with the contact's)")]


def _scale(res):
    """The audit's scale of the relative energy error: the energy at the start plus |external work|."""
    first, last = res.audit[0], res.audit[-1]
    return first["total"] + abs(last["external"])
