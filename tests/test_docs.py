"""The numbers the README and docs/ quote are their outputs' (penetration.docs): every generated block equals what
the outputs committed at git HEAD give. This test checks the committed documents against the committed outputs."""
from pathlib import Path

import pytest

from conftest import ROOT, committed, committed_files
from penetration.docs import BLOCK, BLOCKS, render

DOCUMENTS = ["README.md"] + [p for p in committed_files("docs") if p.endswith(".md")]


@pytest.mark.parametrize("path", DOCUMENTS)
def test_generated_blocks_equal_what_the_committed_outputs_give(path):
    text = committed(path)
    assert render(text, committed) == text, f"python -m penetration.docs {path}"


def test_the_readme_quotes_its_results_through_generated_blocks():
    names = [m.group("name") for m in BLOCK.finditer(committed("README.md"))]
    assert {"levels", "answer", "rebuild"} <= set(names) and len(names) == len(set(names))


def test_a_stale_block_is_found(tmp_path):
    text = "x\n<!-- generated: answer -->\nDO/CRH 4.5 1.000-1.001\n<!-- end generated -->\n"
    assert render(text, committed) != text
    with pytest.raises(KeyError, match="known"):
        render("<!-- generated: nothing -->\n<!-- end generated -->", committed)
