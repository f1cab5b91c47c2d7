"""The cavity-expansion law sigma_n(v) of HJC concrete, with the Eq 7 forms beside it."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..pipeline.io import load_json, task, write_csv
from .common import figure, save


def static_resistance(table, S_stated, S_calibrated, fc):
    """Quasi-static resistances side by side: HJC's cavity stress at v = 0 against S fc of Eq 7.

    ``hjc_table1_over_this``: the laboratory HJC set's quasi-static cavity
    stress divided by each row's stress.
    """
    at0 = table[table.velocity == 0].set_index("material")
    rows = [{"quantity": f"HJC quasi-static cavity stress ({m}; strength scale {at0.strength_scale[m]:.4g})",
             "stress_pa": at0.sigma_n[m]} for m in at0.index]
    rows += [{"quantity": "S fc with S = 72 fc^-0.5 (Li & Chen; paper Eq 7)", "stress_pa": S_stated * fc},
             {"quantity": f"S fc with S = {S_calibrated:.4g} (calibrated on DO1 with Eq 9)", "stress_pa": S_calibrated * fc}]
    out = pd.DataFrame(rows)
    out["over_fc"] = out.stress_pa / fc
    out["hjc_table1_over_this"] = at0.sigma_n["table1"] / out.stress_pa
    return out


@task
def cavity_sigma_n(inputs, outputs, params):
    table = pd.read_csv(inputs.sigma)
    cal = load_json(inputs.cal_do1)
    write_csv(table, outputs.csv)
    write_csv(static_resistance(table, 72 * (params.fc / 1e6) ** -0.5, cal["S"], params.fc), outputs.static)
    fig, (ax,) = figure(1, 6.0, 4.2)
    for (label, g), c in zip(table.groupby("material", sort=False), ("tab:green", "tab:gray")):
        ax.plot(g.velocity, g.sigma_n / 1e6, "o-", color=c, ms=3,
                label=f"HJC cavity expansion, {label} (strength scale {g.strength_scale.iloc[0]:.3f})")
    v = np.linspace(0, table.velocity.max(), 200)
    rho, fc = params.rho, params.fc
    for S, lab, ls in ((72 * (fc / 1e6) ** -0.5, "S fc + rho v^2, S = 72 fc^-0.5 (paper Eq 7)", "--"),
                       (cal["S"], f"S fc + rho v^2, S = {cal['S']:.3f} (calibrated on DO1)", ":")):
        ax.plot(v, (S * fc + rho * v * v) / 1e6, "k", ls=ls, lw=1, label=lab)
    shots = pd.read_csv(inputs.shots)
    top = shots.peak_normal_velocity.max()
    ax.axvspan(0, top, color="tab:blue", alpha=0.07,
               label=f"v_n the Table 3 noses sample (up to {top:.0f} m/s = "
                     f"{top / shots.velocity.max():.2f} x {shots.velocity.max():.0f} m/s)")
    ax.set(xlabel="cavity-wall (normal) velocity (m/s)", ylabel="sigma_n (MPa)", title="Normal stress law on the nose")
    ax.legend(fontsize=7)
    save(fig, outputs.png, params.dpi)
