"""Benchmark: cost of the HJC sigma_n(v) table (cavity-expansion level).

Run: cd workflow/benchmarks && python cavity_speed.py
Prints the machine, then the wall time of the whole table (the velocities of
workflow/config.yaml, 2 threads) for Table 1 HJC at several zone counts, after
one warm-up run that compiles the kernels; then the median cost of one
cavity-level trajectory (DO1 at 835 m/s, the configured trajectory rtol of the
cavity scenes) with the crater law and with nose entry, for three noses.
"""
import statistics
import time
from pathlib import Path

from nstar_speed import machine, timed

from penetration.cavity.expansion import Controls, Mesh, expand, stress_table
from penetration.cavity.level import cavity_trajectory, sigma_table
from penetration.concrete.hjc import HJC
from penetration.nose.geometry import DoubleOgive, Ogive
from penetration.pipeline.config import read_yaml


def main():
    cfg = read_yaml(Path(__file__).resolve().parents[1] / "config.yaml")["cavity"]
    print(f"machine: {machine()}")
    expand(HJC(), 1000.0, mesh=Mesh(zones=40))  # compile
    v = cfg["velocities"]
    ctl = Controls(cycle_ratio=cfg["cycle_ratio"], tol=cfg["tol"], cfl=cfg["cfl"])
    print(f"{len(v)} velocities from {min(v):g} to {max(v):g} m/s")
    for zones in (50, cfg["zones"], 200):
        best = min(timed(lambda: stress_table(HJC(), v, 0.07, Mesh(zones=zones, cap=cfg["cap"]), ctl))
                   for _ in range(2))
        print(f"zones {zones:4d}: table in {best:.2f} s")
    table, _ = sigma_table(HJC(strength_scale=0.6), v, 0.07, Mesh(zones=cfg["zones"], cap=cfg["cap"]), ctl)
    noses = {"double ogive (DO1)": DoubleOgive(0.07, S1=0.8576, S2=0.42, a1=0.0397, a2=0.0638, alpha=0.245),
             "CRH 4.5": Ogive(4.5, 0.07), "CRH 3": Ogive(3.0, 0.07)}
    for label, nose in noses.items():
        for effects in (("crater", "cavity"), ("nose_entry", "cavity")):
            times = []
            for _ in range(7):
                t0 = time.perf_counter()
                cavity_trajectory(nose, 81.1, 835.0, table, effects, rtol=1e-7)
                times.append(time.perf_counter() - t0)
            print(f"{label:20s} {effects[0]:10s}: {1e3 * statistics.median(times):6.1f} ms per shot")


if __name__ == "__main__":
    main()
