"""Fig 7: outlines and dimensions of the CRH 3, double-ogive and CRH 5 projectiles.

The paper's millimetre values are lost with the figure and the diameter of
the 450 kg projectiles is not stated, so lengths are given in calibers (d).
"""
from __future__ import annotations

import pandas as pd

from ..pipeline.io import read_noses, task, write_csv
from .common import color, figure, save

ORDER = (("fig4_crh3", "CRH 3"), ("fig4_double_ogive", "double ogive (inferred)"), ("fig4_crh5", "CRH 5"))
SHANK_CALIBERS = 1.0  # shank drawn behind each nose, for the picture only


@task
def fig07(inputs, outputs, params):
    noses = read_noses(inputs.noses)
    rows, dims = [], []
    for name, _ in ORDER:
        nose = noses[name]
        d = 2 * nose.radius
        x, y = nose.outline(params.points)
        rows.append(pd.DataFrame({"nose": name, "x_over_d": x / d, "y_over_d": y / d}))
        dims.append({"nose": name, "nose_length_over_d": nose.length / d})
        if hasattr(nose, "joints"):
            xC, xD = nose.joints
            dims[-1].update(region1_over_d=xC / d, region2_over_d=(xD - xC) / d,
                            region3_over_d=(nose.length - xD) / d, a1_over_d=nose.a1 / d, a2_over_d=nose.a2 / d,
                            S1_over_d=nose.S1 / d, S2_over_d=nose.S2 / d)
    data = pd.concat(rows, ignore_index=True)
    write_csv(data.merge(pd.DataFrame(dims), on="nose"), outputs.csv)

    fig, axes = figure(1, 8.0, 5.0)
    ax = axes[0]
    for i, ((name, label), dim) in enumerate(zip(ORDER, dims)):
        g = data[data.nose == name]
        off = -1.4 * i
        L = dim["nose_length_over_d"]
        xs = list(g.x_over_d - L) + [SHANK_CALIBERS]
        ys = list(g.y_over_d) + [0.5]
        ax.plot(xs, [off + v for v in ys], color=color(name), lw=1.6)
        ax.plot(xs, [off - v for v in ys], color=color(name), lw=1.6)
        ax.plot([SHANK_CALIBERS] * 2, [off - 0.5, off + 0.5], color=color(name), lw=1.6)
        text = f"{label}: nose length {L:.3f} d"
        if "region1_over_d" in dim:
            text += (f"\nregions {dim['region1_over_d']:.3f} / {dim['region2_over_d']:.3f} / {dim['region3_over_d']:.3f} d;"
                     f" S1 = {dim['S1_over_d']:.2f} d, S2 = {dim['S2_over_d']:.2f} d")
        ax.text(-L, off + 0.6, text, fontsize=7)
    ax.set_aspect("equal")
    ax.set(xlabel="x / d (shanks aligned at 0)", yticks=[], title="Fig 7: projectiles in calibers (mm values not in the paper)")
    save(fig, outputs.png, params.dpi)
