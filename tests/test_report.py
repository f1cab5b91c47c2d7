"""The replication report: its source computes nothing, and the rendered HTML embeds every figure, as it is."""
import ast
import base64
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "workflow/report.py"
HTML = ROOT / "figures/report.html"


def test_report_source_reads_outputs_only():
    """No module of the package (physics or tasks) is imported: the report reads figures and results."""
    imported = set()
    for node in ast.walk(ast.parse(SOURCE.read_text())):
        if isinstance(node, ast.Import):
            imported |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add((node.module or "").split(".")[0])
    assert imported <= {"base64", "json", "os", "pathlib", "pandas", "IPython"}, imported


def shown_images():
    """alt (the figure's path) -> base64 data of every embedded PNG (attributes in any order)."""
    shown = {}
    for tag in re.findall(r"<img\b[^>]*>", HTML.read_text()):
        alt = re.search(r'alt="([^"]+)"', tag)
        src = re.search(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', tag)
        if alt and src:
            shown[alt.group(1)] = src.group(1)
    return shown


def test_report_embeds_every_figure_as_built():
    shown = shown_images()
    expected = {str(p.relative_to(ROOT)) for d in ("figures", "figures/fe", "figures/fe/full", "figures/timing")
                for p in (ROOT / d).glob("*.png") if not p.name.startswith("sweep")}  # the sweep target is on demand
    assert expected <= set(shown), sorted(expected - set(shown))
    for path, data in shown.items():
        assert base64.b64decode(data) == (ROOT / path).read_bytes(), f"{path} in the report is not the file"


def test_report_has_no_error_output():
    html = HTML.read_text()
    assert "Traceback" not in html and 'data-mime-type="application/vnd.jupyter.stderr"' not in html
    for section in ("At a glance", "The paper's conclusions", "internal contradictions", "Every figure and table",
                    "Inferred and calibrated inputs", "Users' shots at every level"):
        assert section in html, section
