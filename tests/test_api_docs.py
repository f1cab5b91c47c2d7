"""docs/api.md stays true: every Python example runs from the checkout and prints what its comments say (each
`print(...)  # text` line, and each comment line standing alone, is one expected line of output, in order)."""
import contextlib
import io
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BLOCKS = re.findall(r"```python\n(.*?)```", (ROOT / "docs/api.md").read_text(), re.S)


def expected_lines(code):
    out = []
    for line in code.splitlines():
        if line.startswith("# "):
            out.append(line[2:])
        elif "print(" in line and "  # " in line:
            out.append(line.split("  # ", 1)[1])
    return out


def test_the_page_has_examples_that_print():
    assert len(BLOCKS) >= 5 and all(expected_lines(b) for b in BLOCKS)


@pytest.mark.parametrize("code", BLOCKS, ids=[f"example{i + 1}" for i in range(len(BLOCKS))])
def test_each_example_runs_and_prints_what_it_says(code):
    here = os.getcwd()
    out = io.StringIO()
    os.chdir(ROOT)
    try:
        with contextlib.redirect_stdout(out):
            exec(compile(code, "docs/api.md", "exec"), {"__name__": "__docs__"})
    finally:
        os.chdir(here)
    assert out.getvalue().splitlines() == expected_lines(code)
