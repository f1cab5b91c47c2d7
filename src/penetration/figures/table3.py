"""Table 3: the paper's simulated and calculated depths beside every model level."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import TABLE3_NOSES, VELOCITIES, load_reference
from ..pipeline.io import load_json, task, write_csv


@task
def table3(inputs, outputs, params):
    """Table 3: paper's simulation and calculation beside our model levels."""
    refs = load_reference(inputs.reference)
    key = lambda frame: frame.set_index(["velocity", "nose"]).dop
    cal = key(pd.read_csv(inputs.analytic))
    stated = key(pd.read_csv(inputs.stated))
    cavity = pd.read_csv(inputs.cavity).set_index(["velocity", "nose"]).cavity_dop
    fit = load_json(inputs.fit)
    fitted = {(c["velocity"], c["nose"]): c["depth"] * (1 + c["relative_residual"]) for c in fit["cells"]}
    cell_S = {(c["velocity"], c["nose"]): c["S_fitting_this_cell"] for c in fit["cells"]}
    row_fit = {r["nose"]: r for r in fit["row_fits"]["rows"]}
    rows = []
    for v in VELOCITIES:
        for n in TABLE3_NOSES:
            rows.append({"velocity_ms": v, "nose": n, "paper_sim_m": refs[f"table3.sim.{v}.{n}"].value,
                         "paper_calc_m": refs[f"table3.calc.{v}.{n}"].value, "analytic_m": cal[(v, n)],
                         "cavity_m": cavity[(v, n)],
                         "analytic_stated_S_m": stated[(v, n)], "analytic_fit_to_calc_m": fitted[(v, n)],
                         # inferences: S fitting this calculated cell alone; (N*, S) fitting the nose's row alone
                         "S_fitting_calc_cell": cell_S[(v, n)], "row_fit_nstar": row_fit[n]["nstar"],
                         "row_fit_S": row_fit[n]["S"], "row_fit_max_abs_residual_m": row_fit[n]["max_abs_residual_m"]})
    t = pd.DataFrame(rows)
    t["rel_dev_analytic_vs_paper_calc_pct"] = 100 * (t.analytic_m / t.paper_calc_m - 1)
    t["rel_dev_analytic_vs_paper_sim_pct"] = 100 * (t.analytic_m / t.paper_sim_m - 1)
    t["rel_dev_cavity_vs_paper_sim_pct"] = 100 * (t.cavity_m / t.paper_sim_m - 1)
    base = t.set_index(["velocity_ms", "nose"]).analytic_m
    t["analytic_increment_vs_crh3_pct"] = [100 * (base[(v, n)] / base[(v, "crh3")] - 1) for v, n in zip(t.velocity_ms, t.nose)]
    t["analytic_increment_vs_crh45_pct"] = [100 * (base[(v, n)] / base[(v, "crh45")] - 1) for v, n in zip(t.velocity_ms, t.nose)]
    write_csv(t, outputs.csv)
