"""Fig 4: the modified (double-ogive) nose against CRH 3 (ODG) and CRH 5 (ABG)."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd

from ..pipeline.io import read_inference, task, write_csv
from .common import color, figure, save

LABELS = {"fig4_crh3": "CRH 3 (ODG)", "fig4_crh5": "CRH 5 (ABG)", "fig4_double_ogive": "double ogive (ACDG, inferred)"}


def fig5_axis(curves):
    """Shift and scale to the paper's Fig 4/5 axis: x/b of CRH 3, shanks aligned."""
    b3 = curves.loc[curves.name == "fig4_crh3", "x"].max()
    ends = curves.groupby("name").x.max()
    return lambda name, x: (x - (ends[name] - b3)) / b3


@task
def fig04(inputs, outputs, params):
    curves = pd.read_csv(inputs.curves)
    to_axis = fig5_axis(curves)
    design = read_inference(inputs.fig4)
    rows = [pd.DataFrame({"nose": n, "x_over_b": to_axis(n, g.x), "y_over_a": g.y})
            for n, g in curves[curves.name.isin(LABELS)].groupby("name", sort=False)]
    data = pd.concat(rows, ignore_index=True)
    write_csv(data, outputs.csv)

    fig, (ax,) = figure(1, 7.0, 3.4)
    for n, g in data.groupby("nose", sort=False):
        ax.plot(g.x_over_b, g.y_over_a, color=color(n), lw=2 if "double" in n else 1.2, label=LABELS[n])
    nose = design["nose"]
    xC, xD = nose.joints
    pts = {"A": (0.0, 0.0), "C": (xC, nose.a1), "D": (xD, nose.a2), "G": (nose.length, 1.0)}
    for lab, (x, y) in pts.items():
        xa = to_axis("fig4_double_ogive", x)
        ax.plot(xa, y, "ko", ms=3)
        ax.annotate(lab, (xa, y), textcoords="offset points", xytext=(-8, 5))
    ax.annotate("O", (0, 0), textcoords="offset points", xytext=(2, 5))
    for i, (x0, x1) in enumerate(((0, xC), (xC, xD), (xD, nose.length)), start=1):
        xs = np.linspace(x0, x1, 50)
        ax.fill_between(to_axis("fig4_double_ogive", xs), 0, nose.radius_at(xs), alpha=0.12, color=f"C{i + 2}")
        ax.text(to_axis("fig4_double_ogive", 0.5 * (x0 + x1)), 0.08, f"region {i}", ha="center", fontsize=7)
    band = design["band"]
    ax.set(xlabel="x/b (b: CRH 3 nose length)", ylabel="y/a", xlim=(-0.4, 1.05), ylim=(0, 1.05),
           title=f"Fig 4 design: cone over k > 0.027 of CRH 3 (x/b {band['xi_c']:.3f}-{band['xi_d']:.3f}); "
                 f"N* = {json.dumps(round(design['described']['nstar'], 4))}")
    ax.legend(loc="upper left", fontsize=7)
    save(fig, outputs.png, params.dpi)
