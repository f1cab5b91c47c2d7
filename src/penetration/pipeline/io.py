"""File I/O shared by the task and figure modules: atomic writes, CSV/JSON, nose records.

Every write goes to a temporary sibling first and is renamed over the
target only when complete, so an interrupted job never leaves a
half-written output. New files get ordinary permissions (0666 minus the
umask), as any file the user creates would.

``task`` marks the functions that Snakemake rules call (one per rule, named
after it); ``penetration.pipeline.dispatch`` finds them by module and name.
"""
from __future__ import annotations

import csv
import dataclasses
import json
import os
import secrets
import stat
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pandas as pd

from ..nose.geometry import make_nose

TASKS = {}


def task(fn):
    """Mark ``fn`` as the task of the rule of the same name."""
    TASKS[fn.__name__] = fn
    return fn


# --------------------------------------------------------------- atomic I/O
class TargetError(OSError):
    """A write whose target exists and is not a regular file (a device, FIFO, socket or directory)."""


_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"))


def check_target(path):
    """Raise TargetError unless ``path`` is a regular file or does not exist yet (a symlink is judged by what it
    points to; a dangling one counts as a new path): renaming a finished file over a device, FIFO or socket would
    replace it with a regular file, and over a directory would fail only after the work is done."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        _check_folder(path)
        return
    except NotADirectoryError:
        return  # a parent is a file: the write fails with its own error
    if stat.S_ISREG(mode):
        if not _writable(path, mode):
            raise TargetError(f"{path} is read-only; allowed: a writable file or a new path (a finished run never "
                              "replaces a read-only file)")
        _check_folder(path)
        return
    kind = next((text for test, text in _KINDS if test(mode)), "not a regular file")
    via = f" (a symlink to {os.path.realpath(path)})" if os.path.islink(path) else ""
    raise TargetError(f"{path} is {kind}{via}; allowed: a regular file or a new path")


def _writable(path, mode) -> bool:
    """Whether ``path`` may be written: access allows it and its mode has a write bit (root may write anything, but
    a file or folder without any write bit was meant to be kept)."""
    return os.access(path, os.W_OK) and bool(mode & (stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH))


def _check_folder(path):
    """Raise TargetError where the nearest existing folder of ``path`` cannot take a new file (the result is written
    beside it, then renamed): checked before any computing, so that no finished run is lost."""
    folder = Path(os.path.abspath(path)).parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    if folder.is_dir() and not _writable(folder, os.stat(folder).st_mode):
        raise TargetError(f"{path}: its folder {folder} is read-only; allowed: a path in a writable folder")


@contextmanager
def atomic(path):
    """Yield a temporary sibling path; it replaces ``path`` only if the block succeeds. A target that exists and is
    not a regular file is refused before anything is written (check_target)."""
    path = Path(path)
    check_target(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp")
    os.close(os.open(tmp, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))  # mode 0666 minus the umask
    try:
        yield tmp
        check_target(path)  # again: the block may have run for minutes
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_text(path, text):
    with atomic(path) as tmp:
        tmp.write_text(text)


def write_csv(frame: pd.DataFrame, path):
    with atomic(path) as tmp:
        frame.to_csv(tmp, index=False, float_format="%.12g", lineterminator="\n")


def write_vtu(path, r, z, quads, cell_data: dict):
    """Write a 2-D axisymmetric mesh as VTK XML unstructured grid (readable by ParaView and meshio): points (r, z, 0)
    in metres, quadrilateral cells ``quads`` (corner node indices), one array per cell field."""
    import meshio
    points = np.column_stack([np.asarray(r, float), np.asarray(z, float), np.zeros(len(r))])
    mesh = meshio.Mesh(points, [("quad", np.asarray(quads, np.int64))],
                       cell_data={k: [np.asarray(v, float)] for k, v in cell_data.items()})
    with atomic(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")


def write_json(obj, path):
    write_text(path, json.dumps(obj, indent=2, default=_jsonable) + "\n")


def file_digest(path) -> str:
    """sha256 of a file's content, "missing" when there is no such file."""
    import hashlib

    p = Path(path)
    return hashlib.sha256(p.read_bytes()).hexdigest() if p.is_file() else "missing"


def committed_study(spec) -> pd.DataFrame:
    """The CSV of a committed study output passed by penetration.pipeline.dispatch.study_input ({path, sha256}), checked to be
    the content the rule was scheduled with."""
    path = Path(spec["path"])
    if not path.is_file():
        raise FileNotFoundError(f"{path}: a study's output this rule reads is missing; build it with `make studies`")
    digest = file_digest(path)
    if digest != spec["sha256"]:
        raise RuntimeError(f"{path} changed after the workflow was scheduled (sha256 {digest[:12]}, scheduled "
                           f"{spec['sha256'][:12]}); run again")
    return pd.read_csv(path)


def committed_studies(specs) -> pd.DataFrame | None:
    """The committed pieces of a study built so far (``specs``: study_input records, one per velocity or target, in
    order), their rows concatenated; None where none is built (a missing piece is left out: the study comes in
    pieces)."""
    frames = [committed_study(s) for s in specs if s["sha256"] != "missing"]
    return pd.concat(frames, ignore_index=True) if frames else None


def load_json(path):
    return json.loads(Path(path).read_text())


def _jsonable(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.bool_):
        return bool(x)
    raise TypeError(f"cannot serialise {type(x)}")


# -------------------------------------------------------------- nose records
def nose_record(nose) -> dict:
    """Kind and parameters of a nose, enough to rebuild it with make_nose."""
    return {"kind": nose.kind, "params": {f.name: getattr(nose, f.name) for f in dataclasses.fields(nose)}}


def nose_from_record(rec):
    return make_nose(rec["kind"], **rec["params"])


def read_inference(path):
    """An inference result file: the dict written by the infer_* tasks, with its nose rebuilt."""
    data = load_json(path)
    data["nose"] = nose_from_record(data["nose"])
    return data


def read_noses(path) -> dict:
    """Name -> nose from the noses table written by the ``geometry`` task."""
    table = pd.read_csv(path)
    return {r.name: nose_from_record({"kind": r.kind, "params": json.loads(r.params)}) for r in table.itertuples()}


# ------------------------------------------------------------------ CSV rows
def read_rows(path):
    """(header fields, rows as dicts) of a CSV file; fields beyond the header sit under the key None.

    Raises ValueError naming the file when it is not UTF-8 text, has no header or names a column twice (a
    dict row would keep the last of the two values silently). A UTF-8 byte-order mark is read as such.
    """
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            reader = csv.DictReader(fh)
            fields = list(reader.fieldnames or [])
            twice = next((f for i, f in enumerate(fields) if f in fields[:i]), None)
            if twice is not None:
                raise ValueError(f"{path}: column {twice!r} is given twice in the header; allowed: each column once")
            rows = list(reader)
    except UnicodeDecodeError:
        raise ValueError(f"{path} is not a UTF-8 text CSV file") from None
    except csv.Error as err:
        raise ValueError(f"{path} is not a readable CSV file: {err}") from None
    if not fields:
        raise ValueError(f"{path} is empty: a header row and at least one shot are needed")
    return fields, rows


def write_rows(path, fields, rows):
    """Write dict rows under the header ``fields`` (atomically)."""
    with atomic(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
