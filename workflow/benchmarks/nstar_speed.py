"""Benchmark: time to compute N* of one profile, and its error against closed forms.

Run: python workflow/benchmarks/nstar_speed.py
Prints the machine, then per nose kind the median wall time of nstar() on a
freshly built nose (construction included) and the relative error where a
closed form exists.
"""
import os
import platform
import time

import numpy as np

from penetration.nose.geometry import Cone, DoubleOgive, Flat, MinimumNstar, Ogive, TabulatedNose
from penetration.nose.nstar import nstar


def machine():
    cpu = platform.processor() or "unknown"
    try:
        with open("/proc/cpuinfo") as fh:
            cpu = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{platform.platform()}, Python {platform.python_version()}, {os.cpu_count()} cores, {cpu}"


def timed(fn):
    """Wall time of one call of fn (s)."""
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def median_time(build, repeat=400):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        nstar(build())
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def main():
    a = 0.07
    L = Ogive(4.5, a).length
    x = np.linspace(0, L, 201)
    y = Ogive(4.5, a).y(x)
    cases = [
        ("ogive CRH 3", lambda: Ogive(3.0, a), 23 / 216),
        ("ogive CRH 0.5 (hemisphere)", lambda: Ogive(0.5, a), 0.5),
        ("blunted ogive CRH 3", lambda: Ogive(3.0, a, 0.01), None),
        ("cone", lambda: Cone(a, L), 1 / 18),
        ("flat", lambda: Flat(a), 1.0),
        ("double ogive", lambda: DoubleOgive(a, S1=0.8576, S2=0.42, a1=0.0397, a2=0.0638, alpha=0.245), None),
        ("minimum N* (Newton body)", lambda: MinimumNstar(a, L), None),
        ("table, 201 points", lambda: TabulatedNose(tuple(x), tuple(y)), None),
    ]
    print(f"machine: {machine()}")
    print(f"{'nose':32s} {'median time (ms)':>18s} {'rel. error vs closed form':>27s}")
    for name, build, exact in cases:
        t = median_time(build)
        err = "" if exact is None else f"{abs(nstar(build()) - exact) / exact:.1e}"
        print(f"{name:32s} {1e3 * t:18.4f} {err:>27s}")


if __name__ == "__main__":
    main()
