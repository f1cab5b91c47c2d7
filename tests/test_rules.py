"""Rules and tasks correspond one to one, and a rule's code inputs are exactly what its task imports.

The oracle for "what a task imports" is the interpreter itself: each task
module is imported in a fresh child process and the package modules that
end up in ``sys.modules`` are its closure (the rules compute theirs by
reading the source). Editing a module must then re-run exactly the rules
whose task imports it (and, through their outputs, what depends on them):
checked with dry runs in a copy of the workflow whose outputs all exist.
"""
import importlib
import json
import os
import pkgutil
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "penetration"
SNAKEMAKE = [sys.executable, "-m", "snakemake"]


def task_modules():
    """Every task and figure module of the package, by dotted name."""
    import penetration.figures
    import penetration.tasks
    names = []
    for pkg in (penetration.tasks, penetration.figures):
        names += [f"{pkg.__name__}.{m.name}" for m in pkgutil.iter_modules(pkg.__path__)]
    return names


def registered_tasks():
    """Rule name -> dotted module of the function marked with @task."""
    from penetration.pipeline.io import TASKS
    for m in task_modules():
        importlib.import_module(m)
    return {name: fn.__module__ for name, fn in TASKS.items()}


CLOSURE_SCRIPT = """
import importlib, json, os, sys


def in_child(work):
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(r)
        os.write(w, json.dumps(work()).encode())
        os._exit(0)
    os.close(w)
    data = b""
    while chunk := os.read(r, 65536):
        data += chunk
    os.waitpid(pid, 0)
    return json.loads(data)


def others():
    for name in sys.argv[1:]:
        importlib.import_module(name)
    return sorted(k for k in sys.modules if k.split(".")[0] != "penetration")


# every other library the tasks load, loaded here once (what each child then imports of the package is unchanged:
# a library never imports the package)
for lib in in_child(others):
    try:
        importlib.import_module(lib)
    except Exception:
        pass


def loaded(name):
    importlib.import_module(name)
    return sorted(k for k in sys.modules if k == "penetration" or k.startswith("penetration."))


print(json.dumps({name: in_child(lambda: loaded(name)) for name in sys.argv[1:]}))
"""


@pytest.fixture(scope="module")
def closures():
    """Task module -> package modules (as src-relative files) in sys.modules after importing it alone."""
    mods = sorted(set(registered_tasks().values()))
    res = subprocess.run([sys.executable, "-c", CLOSURE_SCRIPT, *mods], capture_output=True, text=True, check=True)
    files = {}
    for mod, loaded in json.loads(res.stdout).items():
        files[mod] = {str(Path(sys.modules["penetration"].__file__).parent.joinpath(*m.split(".")[1:])) for m in loaded}
    return {mod: {_as_file(p) for p in paths} for mod, paths in files.items()}


def _as_file(path):
    p = Path(path)
    return p.with_suffix(".py") if p.with_suffix(".py").is_file() else p / "__init__.py"


def rule_names():
    res = subprocess.run(SNAKEMAKE + ["--list-rules"], capture_output=True, text=True, cwd=ROOT, check=True)
    # Snakemake writes part of the list to stderr
    # all, studies, sweep and compare are targets (inputs only, no task)
    return {line for line in (res.stdout + res.stderr).splitlines() if line.isidentifier()} - {"all", "studies", "sweep",
                                                                                                "compare"}


def test_every_rule_has_a_task_and_every_task_a_rule():
    assert rule_names() == set(registered_tasks())


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    """A copy of the workflow where every output exists and is newer than every source file."""
    root = tmp_path_factory.mktemp("workflow")
    for name in ("Snakefile", "workflow", "src"):
        (shutil.copytree if (ROOT / name).is_dir() else shutil.copy)(ROOT / name, root / name)
    # the rule graph does not depend on the files' times: it is computed meanwhile, on the other core
    graph = subprocess.Popen(SNAKEMAKE + ["--rulegraph"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, cwd=root)
    try:
        dry = subprocess.run(SNAKEMAKE + ["-n", "-c1", "--forceall"], capture_output=True, text=True, cwd=root,
                             check=True)
    except BaseException:
        graph.kill()
        raise
    # a job's benchmark record is one of its products too (accuracy_cost and sweep_figures read records)
    outputs = {f.strip() for line in (dry.stdout + dry.stderr).splitlines()
               if line.strip().startswith(("output:", "benchmark:")) for f in line.split(":", 1)[1].split(",")}
    now = time.time()
    for p in root.rglob("*"):
        if p.is_file():
            os.utime(p, (now - 1000, now - 1000))
    for f in outputs:
        (root / f).parent.mkdir(parents=True, exist_ok=True)
        (root / f).touch()
        os.utime(root / f, (now, now))
    dot, err = graph.communicate()
    assert graph.returncode == 0, f"snakemake --rulegraph failed: {err[-2000:]}"
    return root, now, _descendants(dot)


def _descendants(dot):
    """Rule -> every rule downstream of it, from Snakemake's --rulegraph (dot)."""
    import re
    label = dict(re.findall(r"^\s*(\d+)\[label = \"(\w+)\"", dot, re.M))
    edges = [(label[a], label[b]) for a, b in re.findall(r"^\s*(\d+) -> (\d+)", dot, re.M)]
    down = {}
    for rule in label.values():
        seen, todo = set(), [rule]
        while todo:
            r = todo.pop()
            for a, b in edges:
                if a == r and b not in seen:
                    seen.add(b)
                    todo.append(b)
        down[rule] = seen
    return down


def rerun(tree, module):
    """(rules re-run because ``module`` changed, all rules re-run) in a dry run after editing it."""
    root, now, _ = tree
    path = root / "src" / "penetration" / module
    os.utime(path, (now + 100, now + 100))
    try:
        res = subprocess.run(SNAKEMAKE + ["-n", "-c1"], capture_output=True, text=True, cwd=root, check=True)
        out = res.stdout + res.stderr
    finally:
        os.utime(path, (now - 1000, now - 1000))
    direct, every, rule = set(), set(), None
    for line in out.splitlines():
        if line.startswith(("rule ", "localrule ")):
            rule = line.split()[1].rstrip(":")
            every.add(rule)
        elif line.strip().startswith("reason:") and "Updated input files:" in line and f"penetration/{module}" in line:
            direct.add(rule)
    return direct, every - {"all"}


# one module per layer, bottom to top (a dry run each, about 7 s): the shared base, physics, the pipeline's I/O, a
# stage's geometry, the tasks' helpers, a figure
@pytest.mark.parametrize("module", ["units.py", "concrete/hjc.py", "pipeline/io.py", "nose/geometry.py",
                                    "tasks/common.py", "figures/fig04.py"])
@pytest.mark.slow
def test_editing_a_module_reruns_exactly_its_users(tree, closures, module):
    in_dag = tree[2]  # the default target's rules (reproduce_check runs only when asked for)
    users = {rule for rule, mod in registered_tasks().items() if SRC / module in closures[mod] and rule in in_dag}
    direct, every = rerun(tree, module)
    downstream = set().union(*(tree[2][r] for r in users)) - {"all"}
    assert direct <= users  # Snakemake names only one reason per job: the others re-run for their inputs
    assert every == users | downstream


def test_every_rule_declares_threads_resources_benchmark_and_log():
    """What a cluster profile and the cost figures use: threads, memory and runtime, a benchmark record named after
    the rule, a log; and the task convention (the task module and its code as inputs, the one script). Read from the
    workflow as Snakemake loads it: a rule may inherit these from its kind's first rule (use rule ... with:)."""
    from workflow_rules import loaded_rules
    rules = {name: r for name, r in loaded_rules().items() if r.output}  # not the targets (all, studies, sweep)
    assert set(rules) == rule_names()
    for name, r in rules.items():
        assert {"_cores", "mem_mb", "runtime"} <= set(r.resources), f"rule {name} lacks threads or resources"
        assert str(r.benchmark).startswith(f"results/benchmarks/{name}"), f"rule {name}: benchmark {r.benchmark}"
        assert len(r.log) == 1, f"rule {name} lacks its log"
        assert r.input.get("task") and r.input.get("code"), f"rule {name} lacks **task(...)"
        assert r.script == "../scripts/run_task.py", f"rule {name}: script {r.script}"


def test_a_rule_whose_task_resolves_its_scene_declares_the_inferred_noses():
    """A task that resolves its scene (tasks.common.scene_from_inputs, through scene_shot or window_study too)
    reads both inferred noses: its rule must declare them (`do1` and `fig4`, Snakefile's GEOMETRY_RESULTS), or the
    job fails at its start. A rule that reads its scene file alone (its noses' names) is listed, and its task must
    not resolve the scene."""
    import inspect

    from workflow_rules import loaded_rules

    from penetration.pipeline.io import TASKS
    registered_tasks()
    reads_file_only = {"fe_table3"}
    for name, r in loaded_rules().items():
        if "scene" not in r.input.keys():
            continue
        if name in reads_file_only:
            source = inspect.getsource(TASKS[name])
            assert not any(f in source for f in ("scene_from_inputs(", "scene_shot(", "window_study(")), name
            continue
        assert {"do1", "fig4"} <= set(r.input.keys()), f"rule {name} resolves its scene without both inferred noses"


def test_no_rule_takes_the_whole_config_as_a_param():
    """Snakemake re-runs a job whose params changed: a rule holding the whole config would re-run (validation_fe:
    minutes) after any edit of it, a figure's dpi included. Rules take the sections their tasks read
    (workflow/rules/common.smk's cfg_slice)."""
    import re
    text = "\n".join(p.read_text() for p in sorted((ROOT / "workflow/rules").glob("*.smk")))
    text += (ROOT / "Snakefile").read_text()
    whole = re.findall(r"^\s*(?:params:)?.*\b\w+=(?:config\s*[,)\n]|lambda \w+: \{\*\*config\b)", text, re.M)
    assert whole == []


def test_a_modules_parsed_imports_are_kept_until_its_text_changes(tmp_path, monkeypatch):
    """The imports each module's text gives are kept between processes (the cache file) by the text's digest: a
    second process reads them without parsing, and a module edited since is parsed again, never served stale."""
    from penetration.pipeline import dispatch
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    for name, text in {"__init__.py": "", "a.py": "from . import b\n", "b.py": "", "c.py": ""}.items():
        (pkg / name).write_text(text)
    monkeypatch.setattr(dispatch, "PACKAGE", pkg)
    monkeypatch.setattr(dispatch, "NAME", "pkg")
    monkeypatch.setattr(dispatch, "IMPORTS_CACHE", tmp_path / "imports.json")
    parsed = []
    real = dispatch._parsed_imports
    monkeypatch.setattr(dispatch, "_parsed_imports", lambda path, text: parsed.append(path.name) or real(path, text))

    def new_process():
        for f in (dispatch._imported, dispatch._imports_cache, dispatch._module_file, dispatch._exists):
            f.cache_clear()

    new_process()
    assert dispatch._imported(pkg / "a.py") == {"", "b"} and parsed == ["a.py"]
    dispatch._save_imports_cache()
    new_process()
    assert dispatch._imported(pkg / "a.py") == {"", "b"} and parsed == ["a.py"]      # from the file, not parsed
    (pkg / "a.py").write_text("from . import c\n")
    new_process()
    assert dispatch._imported(pkg / "a.py") == {"", "c"} and parsed == ["a.py", "a.py"]
    for f in (dispatch._imported, dispatch._imports_cache, dispatch._module_file, dispatch._exists):
        f.cache_clear()   # the real package's caches again for the other tests
