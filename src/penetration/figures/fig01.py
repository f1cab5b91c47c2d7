"""Fig 1: shares of the static and inertial terms of the resistance (Eq 7).

Panel (a), 2024-O aluminium, needs the parameters of the authors' earlier
aluminium law, which the paper does not give: it is drawn empty with that
note and its diff row is ``not-derivable``.
"""
from __future__ import annotations

import pandas as pd

from ..pipeline.io import task, write_csv
from ..units import MPA
from .common import figure, save


@task
def fig01(inputs, outputs, params):
    data = pd.read_csv(inputs.shares)
    write_csv(data, outputs.csv)
    fig, (ax1, ax2) = figure(2, 5.0, 3.8)
    ax1.text(0.5, 0.5, "2024-O aluminium:\nparameters not given in the paper\n(not derivable)", ha="center",
             va="center", transform=ax1.transAxes)
    ax1.set(title="(a) 2024-O aluminium", xticks=[], yticks=[])
    for i, (fc, g) in enumerate(data.groupby("fc")):
        ax2.plot(g.velocity, g.static_share, color=f"C{i}", label=f"static, fc = {fc / MPA:.0f} MPa")
        ax2.plot(g.velocity, g.inertial_share, color=f"C{i}", ls="--")
    ax2.set(xlabel="striking velocity (m/s)", ylabel="share of the resistance",
            title=f"(b) concrete, CRH 3 (N* = {data.nstar.iloc[0]:.4f}); dashed: inertial", ylim=(0, 1))
    ax2.legend(fontsize=7)
    save(fig, outputs.png, params.dpi)
