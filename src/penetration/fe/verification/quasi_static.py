"""The erosion-free target's quasi-static check: a rigid CRH 3 ogive driven at a low constant speed into the HJC
target opens its pilot hole; once the nose is buried its steady axial force over the shank area, F / (pi a^2), is
set against the stresses of cavity expansion in the same material (a study, ``tasks.fe_erosion_free``).

At low speed the normal stress on a slender nose is close to the static cavity stress, so F / (pi a^2) ~ sigma_n(V)
of the cavity level (a spherical cavity opened from zero radius, self-similar; ``cavity.stress_table``). The FE
target opens its tunnel from a pilot hole of radius r0 instead, and its elements are finite: the 1-D references
expanded from r0 to a in ``fe.cavity_reference`` (spherical and cylindrical in plane strain) show what the hole alone
changes, and the mesh refinement (``mesh_convergence.grid_refinement``) what the elements change.
"""
from __future__ import annotations

import math
import time

import numpy as np

from ...concrete.hjc import HJC
from ...nose.geometry import Ogive
from ..contact import Projectile
from ..erosion_free.controls import ErosionFree
from ..mesh import MeshSpec, body_outline, build
from ..model import Controls, Model
from ..solver import Unstable, run

RADIUS = 0.02          # m, shank radius of the driven ogive
PSI = 3.0              # CRH of the ogive
TRAVEL = 14.0          # shank radii driven
STEADY_FROM = 8.0      # shank radii of depth after which the force is steady (the nose, 3.3 a long, well buried)
# shank radii: the target's radius and depth. Its lateral and bottom boundaries are dashpots, which carry no static
# load: a 15 x 20 target resisted 380 MPa at 6 across, a 30 x 40 one 465 and a 60 x 80 one 476 MPa (+2 %)
DOMAIN = (60.0, 80.0)


def driven_ogive(across: float, hole: float, v: float, material: HJC | None = None, outputs: int = 200,
                 crater_depth: float | None = 4 * RADIUS, guide: bool = False,
                 domain: tuple[float, float] = DOMAIN) -> tuple[Model, Projectile]:
    """The model and projectile of the driven check: the CRH 3 ogive (RADIUS) as a 1e6 kg body at ``v`` (its speed
    stays within 1e-4 of v), the erosion-free target with ``across`` elements across the shank radius and a pilot
    hole of ``hole`` shank radii, to TRAVEL radii of travel with ``outputs`` output samples; ``crater_depth``: the
    guard's crater-debris depth (None: a lost shape anywhere below the face stops the run); ``guide``: a rigid guide
    fills the pilot hole (Controls.pilot_guide); ``domain``: the target's radius and depth in shank radii (its
    lateral and bottom surfaces non-reflecting, which carry no static load: at a driven speed a target of finite
    size)."""
    a = RADIUS
    zeta, rho = body_outline(Ogive(PSI, a), 20 * a)
    end = TRAVEL * a / v
    g = build(MeshSpec(a / across, 3 * a, 16 * a, domain[0] * a, domain[1] * a, 1.15, pilot_hole=hole * a, opened_radius=a))
    free = ErosionFree(rezone_radius=8 * a, eject_height=a, crater_depth=crater_depth, pilot_guide=guide)
    m = Model(g, material or HJC(), Controls(erosion_free=free, guard=True, drop_free_nodes=False,
                                            lateral="non_reflecting", bottom="non_reflecting", end_time=end,
                                            output_interval=end / outputs))
    return m, Projectile(zeta, rho, 1e6, 0.0, v)


def driven_force(across: float, hole: float = 0.25, v: float = 40.0, material: HJC | None = None,
                 guide: bool = False, domain: tuple[float, float] = DOMAIN) -> dict:
    """The steady axial force over pi a^2 (Pa, compression positive: mean and standard deviation over the output
    samples beyond STEADY_FROM radii of depth) of the ogive driven at ``v`` (m/s) into the erosion-free target with
    ``across`` elements across its shank radius and a pilot hole of ``hole`` shank radii, the hole filled by the rigid
    guide if ``guide`` (as the study's scenes have it), in a target of ``domain`` (radius, depth in shank radii);
    with what the run cost. A run that stops (solver.Unstable)
    gives status "stopped", its diagnostic and no force."""
    if not (math.isfinite(across) and across >= 2):
        raise ValueError(f"quasi-static force: across = {across}; allowed: >= 2 elements across the shank radius")
    if not 0.0 < hole < 1.0:
        raise ValueError(f"quasi-static force: hole = {hole}; allowed: 0 < hole < 1 (a fraction of the shank radius)")
    if not (math.isfinite(v) and 0.0 < v <= 200.0):
        raise ValueError(f"quasi-static force: v = {v} m/s; allowed: 0 < v <= 200 m/s (a low, driven speed)")
    a = RADIUS
    t0 = time.perf_counter()
    m, p = driven_ogive(across, hole, v, material, guide=guide, domain=domain)
    base = {"elements_across": float(across), "pilot_hole": float(hole), "pilot_guide": bool(guide),
            "velocity_ms": float(v), "domain_radius_over_a": float(domain[0]), "domain_depth_over_a": float(domain[1])}
    try:
        res = run(m, p)
    except Unstable as stop:   # a stopped run is a result of the check: where and when, no force
        return {**base, "force_over_area_pa": float("nan"), "force_std_pa": float("nan"), "samples": 0,
                "eroded_mass_kg": float(m.ledger.eroded_mass), "steps": int(m.steps), "elements": int(m.alive.size),
                "status": "stopped", "diagnostic": str(stop), "wall_time_s": time.perf_counter() - t0}
    depth = np.asarray(res.history["depth"])
    force = np.abs(np.asarray(res.history["contact_force"]))
    steady = depth > STEADY_FROM * a
    area = math.pi * a * a
    return {**base, "force_over_area_pa": float(force[steady].mean() / area), "force_std_pa": float(force[steady].std() / area),
            "samples": int(steady.sum()), "eroded_mass_kg": float(m.ledger.eroded_mass), "steps": int(res.steps),
            "elements": int(m.alive.size), "status": res.status, "diagnostic": "", "wall_time_s": time.perf_counter() - t0}


def references(hole: float, v: float = 40.0, material: HJC | None = None) -> dict:
    """The cavity stresses the force is set against (Pa): the cavity level's sigma_n(v) (spherical, from zero
    radius) and the 1-D driven cavities opened at v from the hole's radius to the shank radius, spherical and
    cylindrical (their wall stress averaged over the last quarter of that opening)."""
    from ...cavity.expansion import stress_table
    from .cavity_reference import wall_stress

    material = material or HJC()
    a, r0 = RADIUS, hole * RADIUS
    s, _ = stress_table(material, [v], radius=a, workers=1)
    t_end = (a - r0) / v
    return {"cavity_level_sigma_n_pa": float(s[0]),
            "sphere_from_hole_pa": wall_stress(material, v, r0, t_end, 0.75 * t_end, r_out=50 * a),
            "cylinder_from_hole_pa": wall_stress(material, v, r0, t_end, 0.75 * t_end, r_out=50 * a, sphere=False)}
