"""Committed records read through one checked reader (pipeline.records): a truncated, empty, binary or hand-edited
record, or one of the wrong kind, is refused naming the file, the row and the column -- at the reader and through
the command line, which never ends in a traceback or loses an answer over it."""
import shutil
from pathlib import Path

import pytest

from penetration.pipeline.records import RecordError, read_record

ROOT = Path(__file__).resolve().parents[1]


def cli(*args):
    from conftest import run_cli
    return run_cli(*args)


def _write(tmp_path, text, name="r.csv", binary=False):
    p = tmp_path / name
    (p.write_bytes if binary else p.write_text)(text)
    return p


@pytest.mark.parametrize("text,needle", [
    ("", "header"),
    ("parameter,value\n", "at least 1 row"),
    ("parameter,value\nfs,1.2,9\n", "row 2"),
    ("parameter,value\nfs,abc\n", "row 2 column value"),
    ("parameter,value\nfs,nan\n", "a finite number"),
    ("parameter\nfs\n", "column value"),
    ("parameter,value,value\nfs,1,2\n", "each column once"),
])
def test_the_reader_names_file_row_and_column(tmp_path, text, needle):
    path = _write(tmp_path, text)
    with pytest.raises(RecordError) as err:
        read_record(path, {"parameter": "text", "value": "number"})
    assert needle in str(err.value) and str(path) in str(err.value) and "not allowed" in str(err.value)


def test_binary_and_missing_records(tmp_path):
    with pytest.raises(RecordError, match="UTF-8"):
        read_record(_write(tmp_path, b"\x89PNG\r\n\x1a\n\0\0\xff", binary=True), {"a": "text"})
    with pytest.raises(RecordError, match="missing"):
        read_record(tmp_path / "none.csv", {"a": "text"})


def test_kinds_and_optional_columns(tmp_path):
    path = _write(tmp_path, "\ufeffa,n,c,f,o\nx,1.5,25.0,True,\n")
    rows = read_record(path, {"a": "text", "n": "number", "c": "count", "f": "flag"}, {"o": "number", "z": "number"})
    assert rows == [{"a": "x", "n": 1.5, "c": 25, "f": True, "o": None}]
    with pytest.raises(RecordError, match="whole number"):
        read_record(_write(tmp_path, "c\n2.5\n"), {"c": "count"})


def _pipeline_copy(tmp_path):
    """A pipeline directory with the config, reference, data and the committed records the command line reads."""
    for rel in ("workflow/config.yaml", "workflow/schemas", "workflow/reference", "workflow/data", "figures/fe/full",
                "figures/calibration_cavity_laboratory.csv", "figures/calibration_cavity_do1.csv", "figures/scale"):
        src, dst = ROOT / rel, tmp_path / rel
        dst.parent.mkdir(parents=True, exist_ok=True)
        (shutil.copytree if src.is_dir() else shutil.copy)(src, dst)
    return tmp_path


SHOT = ("ogive", "crh=3", "mass_kg=0.9", "diameter_m=0.0269", "fc_MPa=35", "velocity_ms=500")


@pytest.mark.parametrize("record,text", [
    ("figures/calibration_cavity_laboratory.csv", "fold,parameter,value\nall,strength_scale,"),   # truncated
    ("figures/calibration_cavity_laboratory.csv", ""),                                              # empty
    ("figures/calibration_cavity_laboratory.csv", "fold,parameter,value\nall,strength_scale,big\n"),
    ("figures/calibration_cavity_laboratory.csv", "parameter,value,element_size_m,elements_across_radius\nfs,1.1,0.01,7\n"),
])
def test_a_bad_calibration_record_is_refused_before_the_run(tmp_path, record, text):
    root = _pipeline_copy(tmp_path)
    (root / record).write_text(text)
    res = cli("dop", *SHOT, "--model", "cavity", "--root", str(root))
    assert res.returncode == 2 and "Traceback" not in res.stderr and record in res.stderr, res.stderr


def test_a_record_of_the_wrong_kind_passed_to_calibration(tmp_path):
    res = cli("dop", *SHOT, "--model", "cavity", "--calibration", str(ROOT / "figures/fe/full/calibration_fe_do1.csv"))
    assert res.returncode == 2 and "a calibration of strength_scale, not of fs" in res.stderr


@pytest.mark.parametrize("text", ["", "level,shots\nanalytic,x\n", b"\0\1\2"])
def test_a_bad_validation_record_leaves_the_answer_standing(tmp_path, text):
    root = _pipeline_copy(tmp_path)
    p = root / "figures/fe/full/validation_levels_summary.csv"
    (p.write_bytes if isinstance(text, bytes) else p.write_text)(text)
    res = cli("dop", *SHOT, "--root", str(root))
    assert res.returncode == 0 and "depth" in res.stdout and "Traceback" not in res.stderr
    assert "validation_levels_summary.csv" in res.stderr and "not known" in res.stderr
