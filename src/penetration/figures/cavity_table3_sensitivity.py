"""Table 3 at the cavity level under each calibration variant, against the paper's simulation column."""
from __future__ import annotations

import pandas as pd

from ..pipeline.io import task, write_csv
from .common import figure, save

NOSE_LABELS = {"double_ogive": "DO", "crh45": "CRH 4.5", "crh3": "CRH 3"}


@task
def cavity_table3_sensitivity(inputs, outputs, params):
    data = pd.read_csv(inputs.csv)
    write_csv(data, outputs.csv)
    cells = data[["velocity", "nose"]].drop_duplicates().reset_index(drop=True)
    labels = [f"{v:g}\n{NOSE_LABELS.get(n, n)}" for v, n in zip(cells.velocity, cells.nose)]
    x = {(v, n): i for i, (v, n) in enumerate(zip(cells.velocity, cells.nose))}
    fig, (ax,) = figure(1, 8.0, 4.4)
    ax.axhspan(-params.goal_pct, params.goal_pct, color="tab:green", alpha=0.08,
               label=f"within {params.goal_pct:g} % of the paper")
    ax.axhline(0.0, color="k", lw=1, label="paper's simulation column (Table 3)")
    variants = data.groupby("variant", sort=False)
    for k, (label, g) in enumerate(variants):
        shift = (k - (len(variants) - 1) / 2) * 0.09
        xs = [x[(v, n)] + shift for v, n in zip(g.velocity, g.nose)]
        inside = (g.rel_dev_pct.abs() <= params.goal_pct).sum()
        # ten colours, then the same colours with another marker: every variant its own symbol
        ax.plot(xs, g.rel_dev_pct, "os^D"[k // 10 % 4], ms=4, color=f"C{k % 10}",
                label=f"{label}: {g.calibrated.iloc[0]} = {g.value.iloc[0]:.3g} ({inside}/{len(g)} inside)")
    ax.set_xticks(range(len(labels)), labels, fontsize=7)
    ax.set(xlabel="striking velocity (m/s) and nose", ylabel="cavity level vs paper simulation (%)",
           title="Table 3 at the cavity level: one parameter calibrated on DO1 per variant")
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save(fig, outputs.png, params.dpi)
