"""Fig 15: Pd/d against striking velocity, calculated (Eq 9) and simulated (cavity level).

The paper's Table 3 cells and the DO1 experiment are overlaid.
"""
from __future__ import annotations

import pandas as pd

from ..paper.reference import TABLE3_NOSES, VELOCITIES, load_reference
from ..pipeline.io import task, write_csv
from .common import color, figure, save

LABELS = {"crh3": "CRH 3", "crh45": "CRH 4.5", "double_ogive": "double ogive", "minimum_nstar": "minimum N* (Jones)"}


@task
def fig15(inputs, outputs, params):
    dop = pd.read_csv(inputs.dop)
    cav = pd.read_csv(inputs.cavity).rename(columns={"cavity_dop": "dop"})
    refs = load_reference(inputs.reference)
    d = 2 * dop.radius.iloc[0]
    data = dop[["nose", "velocity", "nstar", "dop", "dop_over_d"]].assign(source="ours (Eq 9, S calibrated on DO1)")
    sim = cav[["nose", "velocity", "nstar", "dop", "dop_over_d"]].assign(source="ours (cavity level, HJC)")
    paper = [{"nose": n, "velocity": v, "dop": refs[f"table3.{col}.{v}.{n}"].value,
              "dop_over_d": refs[f"table3.{col}.{v}.{n}"].value / d, "source": f"paper Table 3 {name}"}
             for v in VELOCITIES for n in TABLE3_NOSES for col, name in (("calc", "calculation"), ("sim", "simulation"))]
    exp = refs["fig15.do1_experiment"]
    paper.append({"nose": "double_ogive", "velocity": refs["table2.velocity"].value, "dop": refs["table2.dop"].value,
                  "dop_over_d": exp.value, "source": "paper DO1 experiment"})
    table = pd.concat([data, sim, pd.DataFrame(paper)], ignore_index=True)
    write_csv(table, outputs.csv)
    fig, (ax,) = figure(1, 6.4, 4.4)
    for n, g in data.groupby("nose", sort=False):
        ax.plot(g.velocity, g.dop_over_d, color=color(n), label=f"{LABELS[n]}, N* {g.nstar.iloc[0]:.4f}")
    ax.plot([], [], "k-", label="solid: ours, Eq 9 with S calibrated on DO1")
    for n, g in sim.groupby("nose", sort=False):
        ax.plot(g.velocity, g.dop_over_d, color=color(n), ls="--", lw=1)
    ax.plot([], [], "k--", lw=1, label="dashed: ours, cavity level (HJC, strength scale calibrated on DO1)")
    for row in paper:
        filled = "calculation" in row["source"]
        marker = "*" if "experiment" in row["source"] else "o"
        ax.plot(row["velocity"], row["dop_over_d"], marker, ms=10 if marker == "*" else 5, color=color(row["nose"]),
                mfc=color(row["nose"]) if filled or marker == "*" else "none")
    ax.plot([], [], "ko", label="paper calculation (Table 3)")
    ax.plot([], [], "ko", mfc="none", label="paper simulation (Table 3)")
    ax.plot([], [], "k*", ms=10, label="DO1 experiment")
    ax.set(xlabel="striking velocity (m/s)", ylabel="Pd/d", xlim=(400, 1400), ylim=(0, 90), title="Fig 15")
    ax.legend(fontsize=7, loc="upper left")
    save(fig, outputs.png, params.dpi)
