"""Fig 12: DO1 velocity and Pd/d against time (cavity level) with the experiment."""
from __future__ import annotations

import pandas as pd

from ..reference import load_reference
from ..io import task, write_csv
from .common import PAPER_STYLE, figure, save


@task
def fig12(inputs, outputs, params):
    hist = pd.read_csv(inputs.histories)
    refs = load_reference(inputs.reference)
    d = refs["table2.diameter"].si
    data = hist.assign(t_ms=hist.t * 1e3, pd_over_d=hist.z / d)[["nose", "velocity", "t_ms", "v", "pd_over_d"]]
    write_csv(data, outputs.csv)
    fig, (ax,) = figure(1, 6.2, 4.2)
    ax.plot(data.t_ms, data.pd_over_d, color="tab:green", label="Pd/d (ours, cavity level)")
    exp = refs["table2.dop"].si / d
    ax.axhline(exp, **{k: v for k, v in PAPER_STYLE.items() if k == "color"}, ls="--", lw=1,
               label=f"experiment DO1: {refs['table2.dop'].value} m (Pd/d = {exp:.1f})")
    ax.set(xlabel="t (ms)", ylabel="Pd/d", ylim=(0, 40), xlim=(0, 18),
           title="Fig 12: DO1, strength scale calibrated on this shot")
    ax2 = ax.twinx()
    ax2.plot(data.t_ms, data.v, color="tab:blue", label="velocity (ours)")
    ax2.set(ylabel="velocity (m/s)", ylim=(0, 900))
    ax.legend(loc="lower center", fontsize=7)
    ax2.legend(loc="lower right", fontsize=7)
    save(fig, outputs.png, params.dpi)
