"""Fig 12: DO1 velocity and Pd/d against time (cavity level) with the experiment."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv
from .common import do1_histories, save


@task
def fig12(inputs, outputs, params):
    hist = pd.read_csv(inputs.histories)
    refs = load_reference(inputs.reference)
    d = refs["table2.diameter"].si
    data = hist.assign(t_ms=hist.t * 1e3, pd_over_d=hist.z / d)[["nose", "velocity", "t_ms", "v", "pd_over_d"]]
    write_csv(data, outputs.csv)
    fig = do1_histories(data.t_ms, data.pd_over_d, data.v, refs, "cavity level",
                        "Fig 12: DO1, strength scale calibrated on this shot", (0, 18))
    save(fig, outputs.png, params.dpi)
