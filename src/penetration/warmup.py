"""Compile the package's numba kernels once, at install: ``python -m penetration.warmup``.

The cavity and finite-element kernels are compiled on their first call and cached on disk next to their modules
(``numba_cache``); a fresh install would otherwise spend a user's first FE shot compiling (1-3 min on 2 cores). This
runs one tiny shot at the cavity and FE levels (a CRH 3 ogive of 1 cm radius at 300 m/s, 3 elements across the
radius), which compiles and caches every kernel those levels call, and prints what it did and how long it took.

Compiling is one core's work, and the FE step's kernels are two nearly equal halves: the element pass, which the
model's first stable step already calls, and the node-side kernels (node pass, loads, contact, guide, move, next
step). A helper process (``--helper``) compiles the second half on a tiny model of its own, then the erosion-free
target's remap and the cavity level's kernels, while this one compiles the first; the step and the cavity shot then
find the helper's kernels in the cache.
If the helper fails, this process compiles them itself: the same kernels, only later (on one core the two processes
take turns: no faster, no slower than one).
"""
from __future__ import annotations

import dataclasses
import subprocess
import sys
import tempfile
import time


def _context():
    from .fe.shot import Settings
    from .nose.geometry import Ogive
    from .shots.ladder import Context, UserShot
    ctx = Context(strength_scale=1.0, strength_scale_source="warm-up", failure_strain=1.0,
                  failure_strain_source="warm-up", fe_settings=Settings(element_size=0.07 / 3),
                  cavity_velocities=(100.0, 200.0, 400.0), cavity_rtol=1e-6)
    return UserShot(Ogive(3.0, 0.01), 0.05, 300.0, 48e6, 2440.0, 0.1), ctx


def step_state(measure_first_step=True, formulation="eroding"):
    """The tiny shot's model as ``fe.solver.run`` hands it to the step: (model, State, the projectile's state array).
    Without ``measure_first_step`` the model's first stable step is not measured (a stand-in of 1 ns): measuring it
    calls, hence compiles, the element pass. ``formulation``: the target's (fe.spec.FORMULATIONS)."""
    from .fe import model as fe_model
    from .fe import solver
    from .fe.contact import Projectile
    from .fe.mesh import body_outline
    from .fe.shot import model_for
    from .shots.ladder import fe_spec
    shot, ctx = _context()
    spec, _ = fe_spec(shot, ctx)
    measured = fe_model.Model._initial_dt
    if not measure_first_step:
        fe_model.Model._initial_dt = lambda self: 1e-9   # this throwaway model only
    try:
        settings = spec.settings
        if formulation == "erosion_free":   # no erosion criterion on that target
            settings = dataclasses.replace(settings, controls=dataclasses.replace(settings.controls, erosion="none"))
        model = model_for(spec.nose, settings, dataclasses.replace(spec.target, formulation=formulation),
                          spec.material, spec.expected_depth)
    finally:
        fe_model.Model._initial_dt = measured
    zeta, rho = body_outline(spec.nose, spec.settings.body_length)
    projectile = Projectile(zeta, rho, spec.mass, 0.0, spec.velocity, spec.friction)
    return (model, solver.state_of(model, fe_model.body_of(projectile, model.r.size)),
            solver._projectile_state(model, projectile))


def node_kernels() -> None:
    """Call each node-side kernel of ``fe.solver.step`` once, with the arguments the step passes it (the same
    types, hence the same compiled signature), on a tiny model whose first stable step is not measured (measuring
    it would compile the element pass, which the main process is compiling meanwhile). The calls' results are
    thrown away."""
    import numpy as np

    from .fe.contact import contact
    from .fe.nodes import external, guide, move, node_pass
    from .fe.state import N_ACC
    from .fe.timestep import next_step
    model, st, proj = step_state(measure_first_step=False)
    bc, acc, dt = st.bc, np.zeros(N_ACC), 1e-9
    next_step(st.rf, st.ri, st.span.nz, dt, 0.0, model.controls.dt_factor)
    node_pass(st.span, st.F, st.alive, st.nodes.mass, st.nodes.state, bc.fix, bc.dash, bc.rowdash, (bc.zp, bc.zs), dt,
              st.V, st.rf)
    external(st.nodes, st.loads, dt, acc)
    contact(st.span, st.nodes, st.body, proj, dt)
    guide(st.span, st.nodes, bc.guide, dt)
    move(st.span, st.X, st.V, st.nodes.state, dt)
    free, _, _ = step_state(measure_first_step=False, formulation="erosion_free")
    free.rezone()   # the erosion-free target's ejection and remap, as its time loop calls them


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv == ["--helper"]:
        node_kernels()
        from .shots.ladder import run
        shot, ctx = _context()
        run(shot, "cavity", ctx)
        return 0
    if argv:
        print(f"usage: python -m penetration.warmup (unknown arguments {argv})", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    print("compiling the cavity and finite-element kernels (once per install; 1-3 min on 2 cores)...",
          file=sys.stderr, flush=True)
    err = tempfile.TemporaryFile("w+")    # not a pipe: a helper that writes much would block on a full one
    helper = subprocess.Popen([sys.executable, "-m", "penetration.warmup", "--helper"], stdout=subprocess.DEVNULL,
                              stderr=err)
    from .shots.ladder import run
    shot, ctx = _context()
    for level in ("fe", "cavity"):   # the element pass first: the longest compile
        t = time.perf_counter()
        r = run(shot, level, ctx)
        print(f"  {level:6s} kernels ready ({time.perf_counter() - t:.1f} s; tiny shot {r.depth_m:.3g} m)",
              file=sys.stderr, flush=True)
    if helper.wait():   # harmless: the shots above compiled the helper's kernels themselves
        err.seek(0)
        lines = err.read().strip().splitlines()
        print(f"  (the helper compiling the node-side and cavity kernels failed, code {helper.returncode}; "
              f"this process compiled them instead: {lines[-1] if lines else 'no message'})",
              file=sys.stderr, flush=True)
    err.close()
    print(f"kernels compiled and cached in {time.perf_counter() - t0:.1f} s", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
