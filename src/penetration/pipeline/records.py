"""Committed records read through one checked reader.

A record is a CSV whose header names its columns (UTF-8, a byte-order mark read as such). Each column a reader
needs has a kind: ``number`` (a finite number), ``count`` (an integer >= 0, written as 25 or 25.0), ``text`` (not
empty), ``flag`` (True or False) or ``any``. An error names the file, the row (numbered as a spreadsheet does: the
header is row 1), the column and what is allowed, so that a truncated, empty, binary or hand-edited record never
ends in a raw traceback and never answers silently.
"""
from __future__ import annotations

import csv
import io
import math

from ..errors import ParameterError

KINDS = {"number": "a finite number", "count": "a whole number >= 0", "text": "a non-empty text",
         "flag": "True or False", "any": "any text"}


class RecordError(ParameterError):
    """A committed record that cannot be read as its reader needs: names the file, the row, the column and what is
    allowed."""


def _value(kind, text):
    if kind == "number":
        v = float(text)
        if not math.isfinite(v):
            raise ValueError
        return v
    if kind == "count":
        v = float(text)
        if not (math.isfinite(v) and v >= 0 and v == int(v)):
            raise ValueError
        return int(v)
    if kind == "text":
        if not text.strip():
            raise ValueError
        return text
    if kind == "flag":
        if text not in ("True", "False"):
            raise ValueError
        return text == "True"
    return text


def read_record(path, columns: dict, optional: dict | None = None, min_rows: int = 1, what: str = "") -> list:
    """The rows of the record at ``path`` as dicts: ``columns`` (name -> kind of KINDS) must be there and hold their
    kind in every row; ``optional`` columns are checked where present (an empty cell is None); other columns are
    kept as text. ``what`` says what the record is (named in errors, e.g. the rule that builds it)."""
    optional = optional or {}
    where = f"record {path}" + (f" ({what})" if what else "")
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            text = fh.read()
    except FileNotFoundError:
        raise RecordError(where, "file", "missing", "an existing file" + (f": build it ({what})" if what else "")) from None
    except UnicodeDecodeError:
        raise RecordError(where, "file", "binary or not UTF-8", "a UTF-8 text CSV") from None
    if "\0" in text:
        raise RecordError(where, "file", "binary (NUL bytes)", "a UTF-8 text CSV")
    try:
        reader = csv.reader(io.StringIO(text, newline=""))
        header = next(reader, [])
        rows = list(reader)
    except csv.Error as err:
        raise RecordError(where, "file", str(err), "a CSV file") from None
    if not header:
        raise RecordError(where, "header", "empty", f"a header row naming the columns {', '.join(columns)}")
    twice = sorted({c for c in header if header.count(c) > 1})
    if twice:
        raise RecordError(where, "header", twice[0], "each column once")
    missing = [c for c in columns if c not in header]
    if missing:
        raise RecordError(where, f"column {missing[0]}", "missing", f"a header with the columns {', '.join(columns)} "
                          f"(it has {', '.join(header)})")
    kinds = {**{c: k for c, k in optional.items() if c in header}, **columns}
    out = []
    for number, row in enumerate(rows, start=2):
        if not row:
            continue
        if len(row) != len(header):
            raise RecordError(where, f"row {number}", f"{len(row)} fields", f"{len(header)} fields, as the header "
                              "(a truncated or hand-edited record)")
        rec = dict(zip(header, row))
        for col, kind in kinds.items():
            cell = rec[col]
            if col in optional and col not in columns and cell == "":
                rec[col] = None
                continue
            try:
                rec[col] = _value(kind, cell)
            except ValueError:
                raise RecordError(where, f"row {number} column {col}", cell, KINDS[kind]) from None
        out.append(rec)
    if len(out) < min_rows:
        raise RecordError(where, "rows", len(out), f"at least {min_rows} row{'s' if min_rows > 1 else ''} below the "
                          "header (a truncated record)")
    return out

