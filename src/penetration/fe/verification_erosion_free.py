"""Verification problems of the erosion-free target (registered in ``verification.PROBLEMS``): what is new in it, the
nose opening the tunnel by pushing the concrete aside, with an audit that has no eroded term. (Its remap is checked
on Blake's cavity, rezoned: ``verification_mechanics``.)"""
from __future__ import annotations

from ..checks import Check, below as _below
from ..hjc import HJC
from .quasi_static import driven_ogive
from .solver import run
from .verification import problem


@problem("erosion-free penetration audit")
def erosion_free_audit(v=40.0, across=4, hole=0.25):
    """A CRH 3 ogive (20 mm shank radius) driven at a constant 40 m/s into the erosion-free HJC target (pilot hole
    1/4 of the radius, 4 elements across it) to 14 radii: the drive holds the speed, and the audit closes with no
    eroded term (the eroded mass and energy exactly 0; the remap's and the ejecta's terms booked)."""
    name = f"erosion-free penetration audit (CRH 3, a = 20 mm, {v:g} m/s driven, hole {hole:g} a)"
    m, p = driven_ogive(across, hole, v, HJC(), outputs=50, crater_depth=None)   # the quasi-static check's set-up
    res = run(m, p)
    audit = res.audit[-1]
    # the audit's error over the work done on the target (the 1e6 kg projectile's energy would hide it)
    work = audit["internal"] + audit["ke_target"] + audit["hourglass"] + audit["contact"] + audit["boundary"]
    error = audit["energy_error"] * _scale(res) / work
    return [Check(name, "projectile speed at the end / v", p.V / v, 1.0, 1.0 - 1e-3, 1.0 + 1e-3, "1",
                  "1: driven at a constant speed (1e6 kg; within 1e-3)"),
            _below(name, "eroded mass + |eroded energy| (no element deleted)", m.eroded_mass + abs(audit["eroded"]),
                   1e-300, "kg + J", "0 exactly: the erosion-free target deletes nothing (exact)"),
            _below(name, "|energy error| / work done on the target (no eroded term)", abs(error), 0.01, "1",
                   "conservation (the audit with the remap's and the ejecta's terms)")]


def _scale(res):
    """The audit's scale of the relative energy error: the energy at the start plus |external work|."""
    first, last = res.audit[0], res.audit[-1]
    return first["total"] + abs(last["external"])
