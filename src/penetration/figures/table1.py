"""Table 1: the paper's material parameters beside their SI form."""
from __future__ import annotations

import pandas as pd

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv


def transcription(refs, item):
    """The reference rows of one table of the paper: value, unit, SI value, source and note."""
    return pd.DataFrame([{"quantity": r.quantity, "case": r.case, "paper": r.value, "unit": r.unit, "si": r.si,
                          "source": r.source, "note": r.note} for r in refs.values() if r.item == item])


@task
def table1(inputs, outputs, params):
    write_csv(transcription(load_reference(inputs.reference), "table1"), outputs.csv)
