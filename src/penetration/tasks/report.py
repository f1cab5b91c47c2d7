"""The replication report: workflow/report.py (jupytext percent format) executed and rendered to one HTML file.

Executed in a Python kernel (nbclient; no notebook server) in the pipeline's directory, with the FE mesh
profile of the build in the environment (PENETRATION_FE_PROFILE); a cell that raises fails the rule.
Rendered without the code (a reader's document), every figure embedded, so the file stands alone.
"""
from __future__ import annotations

import os

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
    write_text(outputs.html, html)
    print(f"{len(nb.cells)} cells executed; {len(html) / 1e6:.1f} MB of HTML")
