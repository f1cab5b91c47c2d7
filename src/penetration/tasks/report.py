"""The replication report: workflow/report.py (jupytext percent format) executed and rendered to one HTML file.

Executed in a Python kernel (nbclient; no notebook server) in the pipeline's directory, with the FE mesh
profile of the build, the levels' labels and the studies' outputs (workflow/studies.yaml) in the environment
(PENETRATION_FE_PROFILE, PENETRATION_LEVELS, PENETRATION_STUDIES) and the diff's statuses with their meanings
(PENETRATION_STATUSES); a cell that raises fails the rule.
Rendered without the code (a reader's document), every figure embedded and no script, stylesheet or font fetched
from the network (nbconvert's lab template less its require.js, MathJax and mermaid loaders), so the file stands alone
and reads the same offline. Its few equations are HTML text (sub- and superscripts, Unicode), which needs no
typesetting script; its page title is the notebook's `title` metadata (the paper's).
"""
from __future__ import annotations

import base64
import html as htmllib
import json
import os
import re
from pathlib import Path

import jupytext
from jinja2 import DictLoader
from nbclient import NotebookClient
from nbconvert import HTMLExporter

from ..levels import LABELS
from ..paper.diff import STATUS_MEANINGS
from ..pipeline.io import task, write_text


@task
def report(inputs, outputs, params):
    nb = jupytext.read(inputs.source)
    for k, cell in enumerate(nb.cells):  # ids by position (jupytext draws random ones): the same source renders the same HTML
        cell.id = f"cell-{k}"
    os.environ["PENETRATION_FE_PROFILE"] = params.profile
    os.environ["PENETRATION_LEVELS"] = json.dumps(LABELS)
    os.environ["PENETRATION_STUDIES"] = json.dumps(list(params.studies))
    os.environ["PENETRATION_STATUSES"] = json.dumps(STATUS_MEANINGS)
    NotebookClient(nb, timeout=params.timeout_s, kernel_name="python3",
                   resources={"metadata": {"path": os.getcwd()}}).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", []) if o.get("output_type") == "error"]
    if errors:
        raise RuntimeError(f"{len(errors)} cells of {inputs.source} raised: {errors[0].get('ename')}: {errors[0].get('evalue')}")
    html = rendered_html(nb)
    problems = embedding_problems(html, Path("."), params.profile)
    if problems:
        raise RuntimeError(f"{inputs.source} renders a report that is not the build's, whole and offline: {problems}")
    read = [inputs.source, inputs.reference, inputs.findings, *inputs.outputs, *params.studies]
    write_text(outputs.html, html + input_manifest(read))
    print(f"{len(nb.cells)} cells executed; {len(html) / 1e6:.1f} MB of HTML")


MANIFEST = "report inputs (git blob SHA-1, path)"


def blob_sha1(data: bytes) -> str:
    """Git's object name of a file's content: what `git ls-tree` lists for it at a commit."""
    import hashlib
    return hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()


def input_manifest(paths) -> str:
    """An HTML comment naming every committed file the report was rendered from with its content's git object
    name (results/, which is not committed, and the machine's timing under figures/timing/ left out), so that a
    check can tell a committed report from one whose inputs have moved on (tests/test_report.py)."""
    lines = []
    for p in sorted({Path(x).as_posix() for x in paths}):
        if p.startswith(("results/", "figures/timing/")) or not Path(p).is_file():
            continue
        lines.append(f"{blob_sha1(Path(p).read_bytes())} {p}")
    return f"\n<!-- {MANIFEST}:\n" + "\n".join(lines) + "\n-->\n"


def read_manifest(html) -> dict:
    """path -> git object name from a report's input manifest ({} when it has none)."""
    m = re.search(r"<!-- " + re.escape(MANIFEST) + r":\n(.*?)\n-->", html, re.S)
    if not m:
        return {}
    return {line.split(" ", 1)[1]: line.split(" ", 1)[0] for line in m.group(1).splitlines() if " " in line}


# nbconvert's lab page without the loaders it fetches from a CDN (require.js, MathJax, mermaid): nothing in the
# report needs them (no widgets, no diagrams; equations are HTML text)
OFFLINE_TEMPLATE = """{%- extends 'index.html.j2' -%}
{%- block html_head_js -%}{%- endblock html_head_js -%}
{%- block html_head_js_mathjax -%}{%- endblock html_head_js_mathjax -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
"""


def rendered_html(nb):
    """The notebook as one HTML page without its code, prompts or any resource loaded from the network."""
    exporter = HTMLExporter(template_name="lab", template_file="offline.html.j2",
                            extra_loaders=[DictLoader({"offline.html.j2": OFFLINE_TEMPLATE})],
                            exclude_input=True, exclude_input_prompt=True, exclude_output_prompt=True)
    return exporter.from_notebook_node(nb)[0]


# the page title: the paper's (the notebook's `title` metadata, in the header of workflow/report.py)
TITLE = "Replication of Liu, Pi & Huang (2015), Penetration performance of double-ogive-nose projectiles"
# sections the report must have (a cell that lost one fails the build)
SECTIONS = ("The bottom line", "At a glance", "The paper's conclusions", "internal contradictions", "Every figure and table",
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


_REMOTE = r"(?:https?:)?//[^\s\"'()<>]+"
# what a browser fetches on opening the page: src/href/data of loading tags, CSS url() and @import, JS import()
_LOADS = (rf"<(?:script|link|img|iframe|source|embed|audio|video|track|object)\b[^>]*?\b(?:src|href|data|srcset)\s*=\s*[\"']?({_REMOTE})",
          rf"url\(\s*[\"']?({_REMOTE})", rf"@import\s+[\"']({_REMOTE})", rf"\bimport\s*\(\s*[\"'`]({_REMOTE})")


def network_resources(html):
    """Every URL the page would fetch from the network when opened (an <a href> is a link, not a load)."""
    return sorted({m for pattern in _LOADS for m in re.findall(pattern, html, flags=re.IGNORECASE)})


def page_title(html):
    title = re.search(r"<title>(.*?)</title>", html, flags=re.DOTALL)
    return htmllib.unescape(title.group(1)).strip() if title else None


def unset_tex(html):
    """LaTeX left in the page's text, which no script typesets offline ($...\\cmd...$, $$, \\( or \\[)."""
    text = re.sub(r"<(script|style)\b.*?</\1>", "", html, flags=re.DOTALL | re.IGNORECASE)
    return re.findall(r"\$\$|\\\(|\\\[|\$[^$<>\n]*\\[A-Za-z]+[^$<>\n]*\$", text)


def embedding_problems(html, root: Path, profile):
    """What is wrong with a rendered report: a PNG of the build's folders (figures, figures/fe, the profile's,
    figures/timing; the on-demand sweep aside) not shown, a shown PNG that is not the file on disk, a missing
    section, error output, a resource fetched from the network, LaTeX left for a script, a title not the paper's.
    An empty list when none."""
    shown = shown_images(html)
    expected = {p.relative_to(root).as_posix() for d in ("figures", "figures/fe", f"figures/fe/{profile}", "figures/timing")
                for p in (root / d).glob("*.png") if not p.name.startswith("sweep")}
    problems = [f"{p} not shown" for p in sorted(expected - set(shown))]
    problems += [f"{p} shown is not the file on disk" for p, data in shown.items()
                 if not (root / p).is_file() or (root / p).read_bytes() != data]
    problems += [f"section {s!r} missing" for s in SECTIONS if s not in html]
    if "Traceback" in html or 'data-mime-type="application/vnd.jupyter.stderr"' in html:
        problems.append("error output in the report")
    problems += [f"{url} loaded from the network" for url in network_resources(html)]
    problems += [f"LaTeX {tex!r} needs a typesetting script" for tex in unset_tex(html)]
    if page_title(html) != TITLE:
        problems.append(f"page title {page_title(html)!r} is not the paper's")
    return problems
