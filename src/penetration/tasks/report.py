"""The replication report: workflow/report.py (jupytext percent format) executed and rendered to one HTML file.

Executed in a Python kernel (nbclient; no notebook server) in the pipeline's directory, with the FE mesh
profile of the build in the environment (PENETRATION_FE_PROFILE); a cell that raises fails the rule.
Rendered without the code (a reader's document), every figure embedded, so the file stands alone.
"""
from __future__ import annotations

import base64
import os
import re
from pathlib import Path

import jupytext
from nbclient import NotebookClient
from nbconvert import HTMLExporter

from ..io import task, write_text


@task
def report(inputs, outputs, params):
    nb = jupytext.read(inputs.source)
    for k, cell in enumerate(nb.cells):  # ids by position (jupytext draws random ones): the same source renders the same HTML
        cell.id = f"cell-{k}"
    os.environ["PENETRATION_FE_PROFILE"] = params.profile
    NotebookClient(nb, timeout=params.timeout_s, kernel_name="python3",
                   resources={"metadata": {"path": os.getcwd()}}).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", []) if o.get("output_type") == "error"]
    if errors:
        raise RuntimeError(f"{len(errors)} cells of {inputs.source} raised: {errors[0].get('ename')}: {errors[0].get('evalue')}")
    html, _ = HTMLExporter(exclude_input=True, exclude_input_prompt=True, exclude_output_prompt=True).from_notebook_node(nb)
    problems = embedding_problems(html, Path("."), params.profile)
    if problems:
        raise RuntimeError(f"{inputs.source} renders a report that does not show the figures as built: {problems}")
    write_text(outputs.html, html)
    print(f"{len(nb.cells)} cells executed; {len(html) / 1e6:.1f} MB of HTML")


# sections the report must have (a cell that lost one fails the build)
SECTIONS = ("At a glance", "The paper's conclusions", "internal contradictions", "Every figure and table",
            "Inferred and calibrated inputs", "Users' shots at every level")


def shown_images(html):
    """alt (the figure's path) -> bytes of every embedded PNG (attributes in any order)."""
    shown = {}
    for tag in re.findall(r"<img\b[^>]*>", html):
        alt = re.search(r'alt="([^"]+)"', tag)
        src = re.search(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', tag)
        if alt and src:
            shown[alt.group(1)] = base64.b64decode(src.group(1))
    return shown


def embedding_problems(html, root: Path, profile):
    """What is wrong with a rendered report: a PNG of the build's folders (figures, figures/fe, the profile's,
    figures/timing; the on-demand sweep aside) not shown, a shown PNG that is not the file on disk, a missing
    section, error output. An empty list when none."""
    shown = shown_images(html)
    expected = {p.relative_to(root).as_posix() for d in ("figures", "figures/fe", f"figures/fe/{profile}", "figures/timing")
                for p in (root / d).glob("*.png") if not p.name.startswith("sweep")}
    problems = [f"{p} not shown" for p in sorted(expected - set(shown))]
    problems += [f"{p} shown is not the file on disk" for p, data in shown.items()
                 if not (root / p).is_file() or (root / p).read_bytes() != data]
    problems += [f"section {s!r} missing" for s in SECTIONS if s not in html]
    if "Traceback" in html or 'data-mime-type="application/vnd.jupyter.stderr"' in html:
        problems.append("error output in the report")
    return problems
