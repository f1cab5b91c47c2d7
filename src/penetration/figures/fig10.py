"""Fig 10: HJC pressure against volumetric strain, with unloading paths."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv
from .common import PAPER_STYLE, figure, save


@task
def fig10(inputs, outputs, params):
    data = pd.read_csv(inputs.paths)
    refs = load_reference(inputs.reference)
    write_csv(data, outputs.csv)
    fig, (ax,) = figure(1, 6.0, 4.4)
    unloads = sorted({p for p in data.path if p != "loading"})
    styles = {"offset": ("-", 1.6), "literal": (":", 0.9), "extended": ("--", 0.9)}
    for (lock, path), g in data.groupby(["lock", "path"], sort=False):
        ls, lw = styles[lock]
        first_unload = path == unloads[0]
        label = (f"loading ({lock} lock)" if path == "loading"
                 else f"unloading from mu_max = {', '.join(u.split()[-1] for u in unloads)} ({lock} lock)"
                 if first_unload else None)
        ax.plot(g.mu, g.p / 1e9, color="tab:blue" if path == "loading" else "tab:orange", lw=lw, ls=ls, label=label)
    pts = [(refs["table1.muc"].value, refs["table1.pc"].value), (refs["table1.mul"].value, refs["table1.pl"].value)]
    ax.plot(*zip(*pts), **PAPER_STYLE, label="paper: (muc, pc), (mul, pl)")
    ax.axhline(-refs["table1.T"].value, color="k", lw=0.6, ls="--", label="tension cut-off -T")
    ax.set(xlabel="volumetric strain mu", ylabel="pressure p (GPa)", title="Fig 10: HJC equation of state",
           xlim=(-0.005, data.mu.max() * 1.02))
    ax.legend(fontsize=7, loc="upper left")
    save(fig, outputs.png, params.dpi)
