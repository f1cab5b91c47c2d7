"""The replication report: its source computes nothing, and the report task refuses a rendering that does not show
every figure as built (checked on a small tree made here, not on the working tree's outputs)."""
import ast
import base64
from pathlib import Path

from penetration.tasks.report import SECTIONS, embedding_problems

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "workflow/report.py"


def test_report_source_reads_outputs_only():
    """No module of the package (physics or tasks) is imported: the report reads figures and results."""
    imported = set()
    for node in ast.walk(ast.parse(SOURCE.read_text())):
        if isinstance(node, ast.Import):
            imported |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add((node.module or "").split(".")[0])
    assert imported <= {"base64", "json", "os", "pathlib", "pandas", "IPython"}, imported


def test_report_source_names_every_required_section():
    text = SOURCE.read_text()
    assert all(s in text for s in SECTIONS)


def _tree(tmp_path):
    for rel, data in {"figures/a.png": b"A", "figures/fe/full/b.png": b"B", "figures/timing/c.png": b"C",
                      "figures/sweep_x.png": b"S", "figures/fe/ci/d.png": b"D"}.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_bytes(data)


def _img(path, data):
    return f'<img alt="{path}" src="data:image/png;base64,{base64.b64encode(data).decode()}">'


def test_a_report_showing_every_figure_as_built_passes(tmp_path):
    _tree(tmp_path)
    html = " ".join(SECTIONS) + _img("figures/a.png", b"A") + _img("figures/fe/full/b.png", b"B") \
        + _img("figures/timing/c.png", b"C")
    assert embedding_problems(html, tmp_path, "full") == []


def test_a_stale_missing_or_broken_report_is_refused(tmp_path):
    _tree(tmp_path)
    stale = " ".join(SECTIONS) + _img("figures/a.png", b"old") + _img("figures/timing/c.png", b"C")
    problems = embedding_problems(stale, tmp_path, "full")
    assert "figures/a.png shown is not the file on disk" in problems
    assert "figures/fe/full/b.png not shown" in problems
    broken = _img("figures/a.png", b"A") + "Traceback"
    problems = embedding_problems(broken, tmp_path, "ci")
    assert "error output in the report" in problems and any("section" in p for p in problems)
    assert "figures/fe/ci/d.png not shown" in problems and not any("sweep" in p for p in problems)
