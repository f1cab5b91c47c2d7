"""The replication report: its source computes nothing, and the report task refuses a rendering that does not show
every figure as built, fetches anything from the network or is not titled after the paper (checked on a small tree
and small pages made here, not on the working tree's outputs)."""
import ast
import base64
from pathlib import Path

import jupytext

from penetration.tasks.report import SECTIONS, TITLE, embedding_problems, network_resources, page_title, rendered_html

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


HEAD = f"<html><head><title>{TITLE.replace('&', '&amp;')}</title></head><body>"


def _img(path, data):
    return f'<img alt="{path}" src="data:image/png;base64,{base64.b64encode(data).decode()}">'


def test_a_report_showing_every_figure_as_built_passes(tmp_path):
    _tree(tmp_path)
    html = HEAD + " ".join(SECTIONS) + _img("figures/a.png", b"A") + _img("figures/fe/full/b.png", b"B") \
        + _img("figures/timing/c.png", b"C")
    assert embedding_problems(html, tmp_path, "full") == []


def test_a_stale_missing_or_broken_report_is_refused(tmp_path):
    _tree(tmp_path)
    stale = HEAD + " ".join(SECTIONS) + _img("figures/a.png", b"old") + _img("figures/timing/c.png", b"C")
    problems = embedding_problems(stale, tmp_path, "full")
    assert "figures/a.png shown is not the file on disk" in problems
    assert "figures/fe/full/b.png not shown" in problems
    broken = _img("figures/a.png", b"A") + "Traceback"
    problems = embedding_problems(broken, tmp_path, "ci")
    assert "error output in the report" in problems and any("section" in p for p in problems)
    assert "figures/fe/ci/d.png not shown" in problems and not any("sweep" in p for p in problems)


def test_a_report_loading_from_the_network_is_refused(tmp_path):
    """A CDN script (MathJax, require.js), stylesheet, font or module import is flagged; links and inline data are not."""
    _tree(tmp_path)
    clean = HEAD + " ".join(SECTIONS) + _img("figures/a.png", b"A") + _img("figures/fe/full/b.png", b"B") \
        + _img("figures/timing/c.png", b"C") + '<a href="https://doi.org/10.1016/j.ijimpeng.2015.05.003">paper</a>' \
        + "<style>/* see https://example.org */ body {background: url(data:image/png;base64,AAAA)}</style>" \
        + "<p>P<sub>d</sub> = m / (2π a<sup>2</sup> ρ N*)</p>"
    assert network_resources(clean) == [] and embedding_problems(clean, tmp_path, "full") == []
    mathjax = "https://cdnjs.cloudflare.com/ajax/libs/mathjax/2.7.7/latest.js?config=TeX-AMS_CHTML-full,Safe"
    for loader, url in ((f'<script src="{mathjax}"></script>', mathjax),
                        ('<link rel="stylesheet" href="//cdn.example.org/x.css">', "//cdn.example.org/x.css"),
                        ("<style>@font-face {src: url('https://fonts.example.org/f.woff2')}</style>", "https://fonts.example.org/f.woff2"),
                        ('<script type="module">const m = await import("https://cdn.example.org/m.mjs");</script>', "https://cdn.example.org/m.mjs")):
        assert network_resources(clean + loader) == [url]
        assert f"{url} loaded from the network" in embedding_problems(clean + loader, tmp_path, "full")
    assert any("LaTeX" in p for p in embedding_problems(clean + r"<p>$\frac{m}{2\pi a^2}$</p>", tmp_path, "full"))


def test_the_report_is_titled_after_the_paper_and_loads_nothing():
    """The source rendered as the task renders it (unexecuted): the paper's title, and no script, stylesheet or font
    fetched from a CDN (nbconvert's default page loads require.js and MathJax from one)."""
    assert "Liu, Pi & Huang (2015)" in TITLE and "Penetration performance of double-ogive-nose projectiles" in TITLE
    html = rendered_html(jupytext.read(SOURCE))
    assert page_title(html) == TITLE
    assert network_resources(html) == []
    assert page_title(HEAD.replace(TITLE.replace("&", "&amp;"), "Notebook")) == "Notebook"
    assert any("title" in p for p in embedding_problems("<title>Notebook</title>" + " ".join(SECTIONS), Path("/nonexistent"), "full"))


def test_the_committed_report_is_rendered_from_the_committed_inputs():
    """The report at git HEAD names the files it was rendered from with their content's object names; each must be
    the file committed at HEAD (a report older than an input it shows is stale: rebuild it, `snakemake -c2
    figures/report.html`, and commit it). The machine's timing files are left out."""
    import subprocess

    from conftest import committed
    from penetration.tasks.report import read_manifest
    listed = subprocess.run(["git", "ls-tree", "-r", "HEAD"], capture_output=True, text=True, cwd=ROOT)
    if listed.returncode != 0:
        import pytest
        pytest.skip("not a git checkout")
    head = {line.split("\t", 1)[1]: line.split()[2] for line in listed.stdout.splitlines()}
    manifest = read_manifest(committed("figures/report.html"))
    assert manifest, "figures/report.html has no input manifest: it predates it; rebuild and commit it"
    stale = sorted(p for p, sha in manifest.items() if head.get(p) != sha)
    assert not stale, f"figures/report.html is stale: {len(stale)} of its inputs changed since, e.g. {stale[:8]}"
    assert len(manifest) > 100 and "figures/diff.csv" in manifest


def test_the_manifest_names_each_input_by_its_git_object(tmp_path):
    import subprocess

    from penetration.tasks.report import blob_sha1, input_manifest, read_manifest
    f = tmp_path / "figures/a.csv"
    f.parent.mkdir(parents=True)
    f.write_bytes(b"x,y\n1,2\n")
    git = subprocess.run(["git", "hash-object", str(f)], capture_output=True, text=True)
    assert blob_sha1(f.read_bytes()) == git.stdout.strip()
    import os
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        html = "<html></html>" + input_manifest(["figures/a.csv", "results/r.json", "figures/timing/t.csv"])
    finally:
        os.chdir(here)
    assert read_manifest(html) == {"figures/a.csv": git.stdout.strip()}
