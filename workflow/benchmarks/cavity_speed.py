"""Benchmark: cost of the HJC sigma_n(v) table (cavity-expansion level).

Run: cd workflow/benchmarks && python cavity_speed.py
Prints the machine, then the wall time of the whole table (the velocities of
workflow/config.yaml, 2 threads) for Table 1 HJC at several zone counts, after
one warm-up run that compiles the kernels.
"""
from pathlib import Path

import yaml

from nstar_speed import machine, timed
from penetration.cavity import Controls, Mesh, expand, stress_table
from penetration.hjc import HJC


def main():
    cfg = yaml.safe_load((Path(__file__).resolve().parents[1] / "config.yaml").read_text())["cavity"]
    print(f"machine: {machine()}")
    expand(HJC(), 1000.0, mesh=Mesh(zones=40))  # compile
    v = cfg["velocities"]
    ctl = Controls(cycle_ratio=cfg["cycle_ratio"], tol=cfg["tol"], cfl=cfg["cfl"])
    print(f"{len(v)} velocities from {min(v):g} to {max(v):g} m/s")
    for zones in (50, cfg["zones"], 200):
        best = min(timed(lambda: stress_table(HJC(), v, 0.07, Mesh(zones=zones, cap=cfg["cap"]), ctl))
                   for _ in range(2))
        print(f"zones {zones:4d}: table in {best:.2f} s")


if __name__ == "__main__":
    main()
