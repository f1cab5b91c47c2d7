"""Table 4: N* and masses of the equal-length noses, the paper's beside ours."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv

TABLE4 = (("cone", "cone"), ("jones", "minimum_nstar"), ("double_ogive", "double_ogive"), ("crh45", "crh45"))


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
