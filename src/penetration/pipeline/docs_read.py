"""Reading the committed outputs that the docs' generated blocks quote (pipeline.docs and its block modules)."""
from __future__ import annotations

import csv
import io


def rows(read, path):
    """The rows of a CSV output as dicts (``read(path)``: its text)."""
    return list(csv.DictReader(io.StringIO(read(path))))


def rows_if_any(read, path):
    """The rows of an output that a study may not have built yet (none then)."""
    try:
        return rows(read, path)
    except FileNotFoundError:
        return []


def number(text) -> float:
    """A CSV cell as a float (an empty cell: nan)."""
    return float(text) if text not in ("", None) else float("nan")
