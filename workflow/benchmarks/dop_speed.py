"""Benchmark: closed-form DOP throughput and trajectory cost per shot.

Run: python workflow/benchmarks/dop_speed.py
Prints the machine, the vectorised Eq 9 throughput (shots per second) for
1e6 shots, and the median wall time of one trajectory integration (DOP853)
with its DOP error against Eq 9 at several tolerances.
"""
import time

import numpy as np
from nstar_speed import machine, timed

from penetration.analytic.dop import penetration_depth
from penetration.analytic.resistance import Target
from penetration.analytic.trajectory import assemble, integrate
from penetration.nose.geometry import DoubleOgive
from penetration.nose.nstar import nstar


def main():
    print(f"machine: {machine()}")
    tg = Target(2440.0, 48e6, 6.69)
    rng = np.random.default_rng(1)
    n = 1_000_000
    v = rng.uniform(100, 2000, n)
    m = rng.uniform(10, 500, n)
    ns = rng.uniform(0.04, 0.5, n)
    best = min(timed(lambda: penetration_depth(m, 0.07, ns, tg, v)) for _ in range(5))
    print(f"Eq 9 vectorised: {n / best:.3g} shots/s ({1e3 * best:.1f} ms for {n} shots)")
    nose = DoubleOgive(0.07, S1=0.8576, S2=0.42, a1=0.0397, a2=0.0638, alpha=0.245)
    nn = nstar(nose)
    exact = float(penetration_depth(81.1, 0.07, nn, tg, 835.0))
    print(f"{'rtol':>8s} {'median ms/shot':>15s} {'rel. DOP error':>15s}")
    for rtol in (1e-4, 1e-6, 1e-8, 1e-10):
        times, depth = [], None
        for _ in range(20):
            t0 = time.perf_counter()
            tr = integrate(assemble(("crater", "static", "inertial"), nose, nn, 81.1, tg, 835.0), 81.1, 835.0,
                           rtol=rtol)
            times.append(time.perf_counter() - t0)
            depth = tr.depth
        print(f"{rtol:8.0e} {1e3 * np.median(times):15.2f} {abs(depth - exact) / exact:15.2e}")


if __name__ == "__main__":
    main()
