"""Tables 1, 2 and 4: the paper's values beside ours (or beside their SI form)."""
from __future__ import annotations

import pandas as pd

from ..reference import load_reference
from ..tasks import task, write_csv

TABLE4 = (("cone", "cone"), ("jones", "minimum_nstar"), ("double_ogive", "double_ogive"), ("crh45", "crh45"))


def _transcription(refs, item):
    return pd.DataFrame([{"quantity": r.quantity, "case": r.case, "paper": r.value, "unit": r.unit, "si": r.si,
                          "source": r.source, "note": r.note} for r in refs.values() if r.item == item])


@task
def table1(inputs, outputs, params):
    write_csv(_transcription(load_reference(inputs.reference), "table1"), outputs.csv)


@task
def table2(inputs, outputs, params):
    write_csv(_transcription(load_reference(inputs.reference), "table2"), outputs.csv)


@task
def table4(inputs, outputs, params):
    refs = load_reference(inputs.reference)
    ours = pd.read_csv(inputs.noses).set_index("name")
    m45 = ours.loc["crh45", "mass"]
    rows = []
    for short, name in TABLE4:
        rows.append({"nose": name, "nstar_paper": refs[f"table4.nstar.{short}"].value,
                     "nstar_fig16_legend": refs[f"fig16.nstar.{short}"].value, "nstar_ours": ours.loc[name, "nstar"],
                     "mass_paper_kg": refs[f"table4.mass.{short}"].value, "mass_ours_kg": ours.loc[name, "mass"],
                     "ratio_paper": refs[f"table4.ratio.{short}"].value, "ratio_ours": ours.loc[name, "mass"] / m45,
                     "ours_is": "inferred from the paper's N* and mass" if name == "double_ogive" else "computed"})
    write_csv(pd.DataFrame(rows), outputs.csv)


@task
def table3(inputs, outputs, params):
    """Table 3: paper's simulation and calculation beside our model levels."""
    from ..reference import TABLE3_NOSES, VELOCITIES
    import json
    refs = load_reference(inputs.reference)
    key = lambda frame: frame.set_index(["velocity", "nose"]).dop
    cal = key(pd.read_csv(inputs.analytic))
    stated = key(pd.read_csv(inputs.stated))
    cavity = pd.read_csv(inputs.cavity).set_index(["velocity", "nose"]).cavity_dop
    fit = json.load(open(inputs.fit))
    fitted = {(c["velocity"], c["nose"]): c["depth"] * (1 + c["relative_residual"]) for c in fit["cells"]}
    rows = []
    for v in VELOCITIES:
        for n in TABLE3_NOSES:
            rows.append({"velocity_ms": v, "nose": n, "paper_sim_m": refs[f"table3.sim.{v}.{n}"].value,
                         "paper_calc_m": refs[f"table3.calc.{v}.{n}"].value, "analytic_m": cal[(v, n)],
                         "cavity_m": cavity[(v, n)],
                         "analytic_stated_S_m": stated[(v, n)], "analytic_fit_to_calc_m": fitted[(v, n)]})
    t = pd.DataFrame(rows)
    t["rel_dev_analytic_vs_paper_calc_pct"] = 100 * (t.analytic_m / t.paper_calc_m - 1)
    t["rel_dev_analytic_vs_paper_sim_pct"] = 100 * (t.analytic_m / t.paper_sim_m - 1)
    t["rel_dev_cavity_vs_paper_sim_pct"] = 100 * (t.cavity_m / t.paper_sim_m - 1)
    base = t.set_index(["velocity_ms", "nose"]).analytic_m
    t["analytic_increment_vs_crh3_pct"] = [100 * (base[(v, n)] / base[(v, "crh3")] - 1) for v, n in zip(t.velocity_ms, t.nose)]
    t["analytic_increment_vs_crh45_pct"] = [100 * (base[(v, n)] / base[(v, "crh45")] - 1) for v, n in zip(t.velocity_ms, t.nose)]
    write_csv(t, outputs.csv)
