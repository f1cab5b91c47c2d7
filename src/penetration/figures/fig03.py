"""Fig 3: cumulative N* (a) and its rate k (b) along a CRH 3 ogive."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv
from .common import PAPER_STYLE, figure, save


@task
def fig03(inputs, outputs, params):
    curves = pd.read_csv(inputs.curves)
    bands = pd.read_csv(inputs.bands).set_index("convention")
    refs = load_reference(inputs.reference)
    c = curves[curves.name == "fig4_crh3"].drop_duplicates("x")
    b, a = c.x.max(), c.y.max()
    adopted = bands.index[bands.adopted][0]
    scale = {"integrand_no_factor2": 0.5 * a, "dN/d(x/b)": b, "dN/d(x/a)": a, "dN/d(x/d)": 2 * a, "dN/dx_m": 1.0}
    data = pd.DataFrame({"x_over_b": c.x / b, "nstar_cum": c.nstar_cum, "k_adopted": c.k * scale[adopted],
                         "k_dN_dxb": c.k * b})
    write_csv(data, outputs.csv)

    fig, (ax1, ax2) = figure(2, 5.0, 3.8)
    ax1.plot(data.x_over_b, data.nstar_cum, color="tab:red", label="CRH 3 (ours, Eq 5)")
    ax1.axhline(refs["fig03.nstar_axis_max"].value, color="k", ls=":", lw=1, label="paper axis top 0.11")
    ax1.set(xlabel="x/b", ylabel="cumulative N*", xlim=(0, 1), ylim=(0, 0.115), title="(a) N* from the tip")
    ax1.legend(loc="lower right")
    band = bands.loc[adopted]
    ax2.plot(data.x_over_b, data.k_adopted, color="tab:red", label=f"k = {adopted} (ours, adopted)")
    ax2.axvspan(band.lo, band.hi, color="tab:green", alpha=0.15, label=f"k > 0.027: x/b {band.lo:.3f}-{band.hi:.3f}")
    ax2.axhline(refs["fig03.k_threshold"].value, color="k", ls="--", lw=1, label="paper threshold 0.027")
    ax2.plot([refs["fig03.k_peak_x"].value], [band.peak_k], **PAPER_STYLE, label="paper: peak at x/b = 0.208")
    ax2.set(xlabel="x/b", ylabel="k", xlim=(0, 1), ylim=(0, refs["fig03.k_axis_max"].value),
            title="(b) rate k; the label's dN*/d(x/b) peaks at %.3f" % bands.loc["dN/d(x/b)", "peak_k"])
    ax2.legend(loc="upper right", fontsize=7)
    save(fig, outputs.png, params.dpi)
