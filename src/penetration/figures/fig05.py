"""Fig 5: cumulative N* along CRH 3, CRH 5 and the double ogive (Fig 4 axis)."""
from __future__ import annotations

import pandas as pd

from ..pipeline.io import task, write_csv
from .common import color, figure, save
from .fig04 import LABELS, fig5_axis


@task
def fig05(inputs, outputs, params):
    curves = pd.read_csv(inputs.curves)
    to_axis = fig5_axis(curves)
    data = pd.concat([pd.DataFrame({"nose": n, "x_over_b": to_axis(n, g.x), "nstar_cum": g.nstar_cum})
                      for n, g in curves[curves.name.isin(LABELS)].groupby("name", sort=False)], ignore_index=True)
    write_csv(data, outputs.csv)
    fig, (ax,) = figure(1, 6.0, 4.0)
    for n, g in data.groupby("nose", sort=False):
        ax.plot(g.x_over_b, g.nstar_cum, color=color(n), label=f"{LABELS[n]}: N* = {g.nstar_cum.iloc[-1]:.4f}")
    ax.set(xlabel="x/b (b: CRH 3 nose length)", ylabel="cumulative N*", xlim=(-0.4, 1.0), ylim=(0, 0.11),
           title="Fig 5 (paper: double ogive smallest at equal length)")
    ax.legend(loc="upper left", fontsize=8)
    save(fig, outputs.png, params.dpi)
