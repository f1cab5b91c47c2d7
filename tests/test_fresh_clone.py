"""workflow/benchmarks/fresh_clone.py's record: a new column joins the file without losing or shifting a row."""
import csv
import importlib.util
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "workflow/benchmarks/fresh_clone.py"


def _module():
    spec = importlib.util.spec_from_file_location("fresh_clone", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_row_with_a_new_column_rewrites_the_record_whole(tmp_path):
    fc = _module()
    record = tmp_path / "fresh_clone.csv"
    record.write_text("date,target,total_s,machine\n2026-01-01,ci,900.0,\"M1, 2 CPUs\"\n")
    fc.append(record, {"date": "2026-01-02", "target": "reproduce", "total_s": 60.5, "machine": "M2",
                       "install_cache": "warm"})
    with open(record, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["date"] for r in rows] == ["2026-01-01", "2026-01-02"]
    assert rows[0]["machine"] == "M1, 2 CPUs" and rows[0]["install_cache"] == ""    # the old row kept, the column empty
    assert rows[1]["install_cache"] == "warm" and rows[1]["total_s"] == "60.5"
    assert not list(tmp_path.glob("*.tmp"))


def test_the_cache_is_cold_where_the_folder_is_missing_or_empty(tmp_path):
    fc = _module()
    assert fc.install_cache({"UV_CACHE_DIR": str(tmp_path / "none")}) == "cold"
    (tmp_path / "empty").mkdir()
    assert fc.install_cache({"UV_CACHE_DIR": str(tmp_path / "empty")}) == "cold"
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "wheel").write_text("x")
    assert fc.install_cache({"UV_CACHE_DIR": str(tmp_path / "full")}) == "warm"
    assert fc.install_cache({"XDG_CACHE_HOME": str(tmp_path / "xdg")}) == "cold"
