"""Compile the package's numba kernels once, at install: ``python -m penetration.warmup``.

The cavity and finite-element kernels are compiled on their first call and cached on disk next to their modules
(``numba_cache``); a fresh install would otherwise spend a user's first FE shot compiling (1-4 min on 2 cores). This
runs one tiny shot at the cavity and FE levels (a CRH 3 ogive of 1 cm radius at 300 m/s, 3 elements across the
radius), which compiles and caches every kernel those levels call, and prints what it did and how long it took.
"""
from __future__ import annotations

import sys
import time


def main() -> int:
    t0 = time.perf_counter()
    print("compiling the cavity and finite-element kernels (once per install; 1-4 min on 2 cores)...",
          file=sys.stderr, flush=True)
    from .fe.shot import Settings
    from .nose.geometry import Ogive
    from .shots.ladder import Context, UserShot, run
    ctx = Context(strength_scale=1.0, strength_scale_source="warm-up", failure_strain=1.0,
                  failure_strain_source="warm-up", fe_settings=Settings(element_size=0.07 / 3),
                  cavity_velocities=(100.0, 200.0, 400.0), cavity_rtol=1e-6)
    shot = UserShot(Ogive(3.0, 0.01), 0.05, 300.0, 48e6, 2440.0, 0.1)
    for level in ("cavity", "fe"):
        t = time.perf_counter()
        r = run(shot, level, ctx)
        print(f"  {level:6s} kernels ready ({time.perf_counter() - t:.1f} s; tiny shot {r.depth_m:.3g} m)",
              file=sys.stderr, flush=True)
    print(f"kernels compiled and cached in {time.perf_counter() - t0:.1f} s", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
