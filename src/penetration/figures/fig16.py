"""Fig 16: outlines of four noses of equal length with their N*."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv
from .common import color, figure, save

NOSES = (("cone", "cone", "cone"), ("minimum_nstar", "Jones (minimum N*)", "jones"),
         ("double_ogive", "double ogive (inferred)", "double_ogive"), ("crh45", "CRH 4.5 ogive", "crh45"))


@task
def fig16(inputs, outputs, params):
    curves = pd.read_csv(inputs.curves)
    table = pd.read_csv(inputs.noses).set_index("name")
    refs = load_reference(inputs.reference)
    parts = []
    for name, label, ref in NOSES:
        g = curves[curves.name == name]
        parts.append(pd.DataFrame({"nose": name, "x_over_b": g.x / g.x.max(), "y_over_a": g.y / g.y.max(),
                                   "nstar_ours": table.loc[name, "nstar"],
                                   "nstar_paper_legend": refs[f"fig16.nstar.{ref}"].value}))
    data = pd.concat(parts, ignore_index=True)
    write_csv(data, outputs.csv)
    fig, (ax,) = figure(1, 6.0, 4.0)
    for name, label, ref in NOSES:
        g = data[data.nose == name]
        ax.plot(g.x_over_b, g.y_over_a, color=color(name),
                label=f"{label}: N* {g.nstar_ours.iloc[0]:.4f} (paper {g.nstar_paper_legend.iloc[0]:.4f})")
    ax.set(xlabel="x/b", ylabel="y/a", xlim=(0, 1), ylim=(0, 1.02), title="Fig 16: four noses of the CRH 4.5 length")
    ax.legend(loc="lower right", fontsize=7)
    save(fig, outputs.png, params.dpi)
