"""Table 2: the DO1 experiment as the paper states it, beside its SI form."""
from __future__ import annotations

from ..paper.reference import load_reference
from ..pipeline.io import task, write_csv
from .table1 import transcription


@task
def table2(inputs, outputs, params):
    write_csv(transcription(load_reference(inputs.reference), "table2"), outputs.csv)
