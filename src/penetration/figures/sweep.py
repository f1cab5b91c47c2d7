"""The sweep target: depth against velocity for nose families at every level, and how the cost grows with shots."""
from __future__ import annotations

import pandas as pd

from ..levels import LEVELS
from ..pipeline.io import task, write_csv
from .common import figure, save

STYLE = {"analytic": ("-", None), "trajectory": (":", None), "cavity": ("--", None), "fe": ("none", "D")}


@task
def sweep_figures(inputs, outputs, params):
    runs = [pd.read_csv(f).assign(level=lv, n=int(n)) for f, lv, n in zip(inputs.csvs, params.levels, params.sizes)]
    marks = [pd.read_csv(f, sep="\t") for f in inputs.benchmarks]
    cost = pd.DataFrame({"level": params.levels, "shots": params.sizes, "wall_time_s": [float(b.s.iloc[0]) for b in marks],
                         "max_rss_mb": [float(b.max_rss.iloc[0]) for b in marks]})
    cost["wall_time_per_shot_s"] = cost.wall_time_s / cost.shots
    write_csv(cost, outputs.cost_csv)
    largest = pd.concat([g[g.n == g.n.max()] for _, g in pd.concat(runs).groupby("level", sort=False)])
    depth = largest[["level", "nose", "nstar", "velocity_ms", "depth_m", "time_to_rest_s", "peak_deceleration_m_s2",
                     "status"]].sort_values(["level", "nose", "velocity_ms"], kind="stable").reset_index(drop=True)
    write_csv(depth, outputs.csv)

    fig, (ax,) = figure(1, 6.4, 4.6)
    colors = dict(zip(depth.nose.unique(), ["tab:red", "tab:blue", "tab:purple", "tab:gray", "tab:orange", "tab:green"]))
    for (level, nose), g in depth.groupby(["level", "nose"], sort=False):  # sorted by velocity within
        ls, mk = STYLE[level]
        ax.plot(g.velocity_ms, g.depth_m, linestyle=ls, marker=mk, color=colors[nose], ms=5,
                label=nose if level == "analytic" else None)
    for level in LEVELS:
        ls, mk = STYLE[level]
        ax.plot([], [], linestyle=ls, marker=mk, color="k", label=f"level {level}")
    ax.set(xlabel="striking velocity (m/s)", ylabel="depth of penetration (m)",
           title="Sweep: nose families on the DO1 projectile into Table 1's concrete (no paper values exist)\n"
                 f"analytic and trajectory: S from {params.law} (stated); cavity and fe: the DO1 calibrations")
    ax.title.set_fontsize(8)
    ax.legend(fontsize=6, ncol=2)
    save(fig, outputs.png, params.dpi)

    fig, (ax,) = figure(1, 5.0, 4.0)
    for level, g in cost.groupby("level", sort=False):
        ax.plot(g.shots, g.wall_time_s, "o-", label=level)
    ax.set(xscale="log", yscale="log", xlabel="shots in one job", ylabel="wall time of the job (s)",
           title="Sweep cost against the number of shots (benchmark records)")
    ax.legend(fontsize=7)
    save(fig, outputs.cost_png, params.dpi)
