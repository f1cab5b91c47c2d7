"""Fig 6: dimensioned drawing of the inferred DO1 double ogive (Table 4)."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..pipeline.io import read_inference, task, write_csv
from ..units import MM
from .common import figure, save


def _dimensions(nose):
    tip, base = nose.segments[0], nose.segments[-1]
    xC, xD = nose.joints
    deg = math.degrees
    return [("S1", "tip ogive radius", nose.S1 / MM, "mm"), ("S2", "base ogive radius", nose.S2 / MM, "mm"),
            ("a1", "radius at C", nose.a1 / MM, "mm"), ("a2", "radius at D", nose.a2 / MM, "mm"),
            ("a", "shank radius", nose.radius / MM, "mm"), ("b", "nose length", nose.length / MM, "mm"),
            ("x_C", "end of region 1", xC / MM, "mm"), ("x_D", "end of region 2", xD / MM, "mm"),
            ("phi0", "normal angle at the tip", deg(tip.phi0), "deg"),
            ("phi1", "normal angle at C", deg(tip.phi1), "deg"),
            ("alpha", "cone half-angle", deg(nose.cone_angle), "deg"),
            ("theta1", "normal angle of the base ogive at D", deg(base.phi0), "deg"),
            ("theta2", "virtual tip angle of the base ogive", deg(math.asin(1 - nose.radius / nose.S2)), "deg")]


@task
def fig06(inputs, outputs, params):
    result = read_inference(inputs.do1)
    nose = result["nose"]
    dims = _dimensions(nose)
    x, y = nose.outline(params.points)
    data = pd.concat([pd.DataFrame({"what": "outline", "name": "", "x": x / MM, "y": y / MM, "value": np.nan, "unit": "mm"}),
                      pd.DataFrame([{"what": "dimension", "name": n, "x": np.nan, "y": np.nan, "value": v, "unit": u}
                                    for n, _, v, u in dims])], ignore_index=True)
    write_csv(data, outputs.csv)

    fig, (ax,) = figure(1, 8.0, 4.0)
    ax.plot(x / MM, y / MM, "k", lw=2)
    ax.plot(x / MM, -y / MM, "k", lw=0.6, alpha=0.4)
    xC, xD = nose.joints
    for xv, yv, lab in ((xC, nose.a1, "C"), (xD, nose.a2, "D")):
        ax.plot([xv / MM] * 2, [0, yv / MM], "k:", lw=0.8)
        ax.annotate(f"{lab}: {'a1' if lab == 'C' else 'a2'} = {yv / MM:.1f} mm", (xv / MM, yv / MM),
                    textcoords="offset points", xytext=(-30, 10), fontsize=7)
    for seg, lab in ((nose.segments[0], "S1"), (nose.segments[-1], "S2")):
        for t in (seg.t0, seg.t1):
            px, py = seg.point(t)
            ax.plot([seg.xc / MM, px / MM], [seg.yc / MM, py / MM], color="tab:blue", lw=0.5, alpha=0.6)
        ax.annotate(f"{lab} = {seg.S / MM:.0f} mm (centre off-axis)", (seg.point(seg.t1)[0] / MM, seg.point(seg.t1)[1] / MM),
                    textcoords="offset points", xytext=(-60, -28), fontsize=7, color="tab:blue")
    text = "\n".join(f"{n} = {v:.2f} {u}" for n, _, v, u in dims if u == "deg")
    ax.text(0.01, 0.98, text, transform=ax.transAxes, va="top", fontsize=7, family="monospace")
    ax.set_aspect("equal")
    ax.set(xlim=(-10, nose.length / MM + 10), ylim=(-nose.radius / MM * 1.1, nose.radius / MM * 1.6),
           xlabel="x (mm)", ylabel="y (mm)",
           title=f"Fig 6: inferred DO1 double ogive (N* = {result['described']['nstar']:.4f}, "
                 f"nose mass {result['described']['mass']:.2f} kg); dimensions not stated in the paper")
    save(fig, outputs.png, params.dpi)
