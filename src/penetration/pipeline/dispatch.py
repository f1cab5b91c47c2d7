"""What the Snakefile asks of the package: a rule's code inputs, the study grids, and the dispatch to its task.

Each rule names its task module (``task("tasks.cavity")``, ``task("figures.fig12")``);
its code inputs are that module and every package module it imports,
directly or not, so that editing a module re-runs exactly the rules whose
tasks use it. The rule's task is the function of the rule's name in that
module.
"""
from __future__ import annotations

import ast
import atexit
import functools
import hashlib
import importlib
import json
import os
from pathlib import Path

from . import config

PACKAGE = Path(__file__).resolve().parents[1]
NAME = PACKAGE.name


@functools.lru_cache(maxsize=None)
def _module_file(dotted: str) -> Path:
    """File of a package module given as 'tasks.cavity' (package directories give their __init__)."""
    base = PACKAGE.joinpath(*dotted.split(".")) if dotted else PACKAGE
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    raise FileNotFoundError(f"no module {NAME}.{dotted} under {PACKAGE}")


def _dotted(path: Path) -> str:
    rel = path.relative_to(PACKAGE).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _parsed_imports(path: Path, source: str) -> list[str]:
    """Dotted names (relative to the package) of the package modules that ``source``, the text of ``path``, imports,
    anywhere in it (modules that do not exist included: ``_imported`` filters them)."""
    here = _dotted(path).split(".") if _dotted(path) else []
    package = here if path.name == "__init__.py" else here[:-1]
    found = set()
    for node in ast.walk(ast.parse(source, str(path))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
            elif node.module and node.module.split(".")[0] == NAME:
                base = []
            else:
                continue
            mod = node.module or ""
            if not node.level:
                mod = mod.partition(".")[2]
            stem = base + (mod.split(".") if mod else [])
            found.add(".".join(stem))
            found.update(".".join(stem + [a.name]) for a in node.names)  # 'from . import x' imports module x
        elif isinstance(node, ast.Import):
            found.update(a.name.partition(".")[2] for a in node.names if a.name.split(".")[0] == NAME)
    return sorted(found)


# The parsed imports of each module by the digest of its text, kept between processes (every Snakemake run parses
# the Snakefile, which asks for the closures of its tasks: parsing some 150 modules costs seconds, reading their
# digests milliseconds). A derived file beside the compiled modules; a module whose text changed is parsed again.
IMPORTS_CACHE = PACKAGE / "__pycache__" / "pipeline_imports.json"


@functools.lru_cache(maxsize=None)
def _imports_cache() -> dict:
    try:
        data = json.loads(IMPORTS_CACHE.read_text())
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}


def _save_imports_cache() -> None:
    """Write the cache whole, through a temporary file (a reader never sees half of it; of two writers the last
    wins, and either's file is complete)."""
    try:
        IMPORTS_CACHE.parent.mkdir(exist_ok=True)
        tmp = IMPORTS_CACHE.with_name(f"{IMPORTS_CACHE.name}.{os.getpid()}.tmp")
        tmp.write_text(json.dumps(_imports_cache(), sort_keys=True))
        os.replace(tmp, IMPORTS_CACHE)
    except OSError:
        pass   # a read-only install: the closures are parsed each time, as without a cache


@functools.lru_cache(maxsize=None)
def _save_at_exit() -> None:
    """Write the cache once, whole, when the process ends (called at each module parsed anew; registers once)."""
    atexit.register(_save_imports_cache)


@functools.lru_cache(maxsize=None)
def _imported(path: Path) -> frozenset[str]:
    """Dotted names (relative to the package) of the package modules that ``path`` imports, anywhere in it.

    Cached per file for the life of the process (a Snakefile's parse asks for the closure of some 70 tasks,
    which share most of their modules), and between processes by the digest of the file's text (IMPORTS_CACHE)."""
    text = path.read_bytes()
    digest = hashlib.sha1(text).hexdigest()
    cache, key = _imports_cache(), _dotted(path) or "."
    entry = cache.get(key)
    if not (isinstance(entry, list) and len(entry) == 2 and entry[0] == digest):
        entry = cache[key] = [digest, _parsed_imports(path, text.decode())]
        _save_at_exit()
    return frozenset(m for m in entry[1] if _exists(m))


@functools.lru_cache(maxsize=None)
def _exists(dotted: str) -> bool:
    try:
        _module_file(dotted)
        return True
    except FileNotFoundError:
        return False


def _with_parents(dotted: str) -> set[str]:
    """A module and the packages above it (importing a module runs their __init__ first)."""
    parts = dotted.split(".") if dotted else []
    return {".".join(parts[:i]) for i in range(len(parts) + 1)}


def code_closure(module: str) -> list[Path]:
    """Files of ``module`` and of every package module it imports, transitively (sorted)."""
    seen, todo = set(), list(_with_parents(module))
    while todo:
        m = todo.pop()
        if m in seen:
            continue
        seen.add(m)
        for dep in _imported(_module_file(m)):
            todo.extend(_with_parents(dep) - seen)
    return sorted(_module_file(m) for m in seen)


def task(module: str, root: str = "src") -> dict:
    """Named Snakemake inputs of a rule whose task lives in ``module``: ``task`` (its file) and ``code``.

    Paths are relative to the working directory, as ``root/penetration/...``.
    """
    rel = lambda p: f"{root}/{NAME}/{p.relative_to(PACKAGE).as_posix()}"
    return {"task": rel(_module_file(module)), "code": [rel(p) for p in code_closure(module)]}


def study_input(path: str) -> dict:
    """A committed study output that a rule of the paper reads (never a Snakemake input, so that rebuilding the paper
    never reruns a study): its path and the digest of its content, passed as a param so that a changed study reruns
    the rule (Snakemake's params trigger). The digest is "missing" when the file is not there (the task then says
    how to build it)."""
    from .io import file_digest

    return {"path": path, "sha256": file_digest(path)}


def uncommitted(paths):
    """A rule's input function over committed pieces of a study (``paths``, which may name the rule's wildcards):
    those not on disk yet. A committed piece is a record, read through the rule's params (``study_input``), never a
    job of the DAG, so that no rerun trigger (a newer source file, the input set it was first built from) asks to
    rebuild a record whose runs are gone; a missing one is built first."""
    return lambda w: [p for p in (q.format(**w) for q in paths) if not Path(p).exists()]


def run(rule, task_file, inputs, outputs, params):
    """Call the task of ``rule`` in the module whose file is ``task_file`` (used by workflow/scripts/run_task.py)."""
    parts = Path(task_file).with_suffix("").parts
    dotted = ".".join(parts[max(i for i, p in enumerate(parts) if p == NAME) + 1:])
    module = importlib.import_module(f"{NAME}.{dotted}")
    fn = getattr(module, rule, None)
    if fn is None:
        raise KeyError(f"rule {rule!r}: no task of that name in {NAME}.{dotted}")
    return fn(inputs, outputs, params)


def scene_input(path) -> dict:
    """A rule's scene inputs: ``scene``, the scene file, and ``scene_bases``, the files it extends (scenes.scene_files),
    so that a change to the paper's case reruns every level's scene of it. ``path`` may hold wildcards
    (``workflow/scenes/fe/{scene}.yaml``) or be a function of them."""
    from .scenes import scene_files
    if callable(path) or "{" in path:
        get = path if callable(path) else (lambda w: path.format(**dict(w.items())))
        return {"scene": get, "scene_bases": lambda w: scene_files(get(w))[1:]}
    return {"scene": path, "scene_bases": scene_files(path)[1:]}


def size_params(path, config):
    """A scene rule's ``size`` param (``path``: the scene file, with wildcards): None for a scene without the scale
    effect, so that its job never depends on the study; else what scenes.sized needs, the config's variants and S law,
    the study's fe mesh profile and its calibration at the scene's level as a committed study output (study_input: a
    changed calibration reruns the job)."""
    from .scenes import SIZE, SIZE_LEVEL, scene_data

    def params(w):
        data = scene_data(path.format(**dict(w.items())))
        if SIZE not in data.get("effects", []):
            return None
        study = config["scale_effect"]
        return {"variants": study["variants"], "law": config["validation"]["strength_law"],
                "fe_profile": study["fe_profile"],
                "calibration": study_input(f"figures/scale/calibration_{SIZE_LEVEL[data['level']]}.csv")}
    return params


def load_studies(folder, schema_path) -> dict:
    """Study grids by name: every ``folder/NAME.yaml``, each checked against the schema's definition NAME."""
    schema = json.loads(Path(schema_path).read_text())
    studies = {}
    for path in sorted(Path(folder).glob("*.yaml")):
        name = path.stem
        if name not in schema["$defs"]:
            raise config.ConfigError(f"{path}: no study named {name!r}; known: {sorted(schema['$defs'])}")
        studies[name] = config.load_with(path, {**schema["$defs"][name], "$defs": schema["$defs"]})
    return studies


def study_outputs(path, schema_path, values, checked=()) -> dict:
    """The research studies' committed outputs by study (``path``: workflow/studies.yaml, checked against its schema),
    each pattern expanded over the ``values`` of its placeholders (name -> list of values); a placeholder without
    values is refused, naming the study and the pattern, and so is an output of ``checked`` (the reproduction check's
    studies) that no study lists."""
    import itertools
    import string

    studies = config.load(path, schema_path)
    out = {}
    for name, study in studies.items():
        paths = []
        for pattern in study["outputs"]:
            keys = [k for _, k, _, _ in string.Formatter().parse(pattern) if k]
            unknown = sorted(set(keys) - set(values))
            if unknown:
                raise config.ConfigError(f"{path}: {name}.outputs: {pattern!r} names {unknown}; allowed placeholders: "
                                         f"{sorted(values)}")
            paths += [pattern.format(**dict(zip(keys, combo))) for combo in itertools.product(*(values[k] for k in keys))]
        out[name] = paths
    listed = {p for paths in out.values() for p in paths}
    unlisted = sorted(set(checked) - listed)
    if unlisted:
        raise config.ConfigError(f"{path}: the reproduction check's studies name outputs no study lists: {unlisted}; "
                                 f"allowed: the outputs of a study in {path}")
    return out


def fe_shot_owners(folder, schema_path) -> dict:
    """(scene, nose, velocity tag) -> the scene whose job computes that shot: the first scene, in name order, with
    the same shot of the same physics (everything of the scene file but its description, velocities and other
    noses equal, the nose's definition too). Fig 15's sweep and Table 3 share nine shots: each runs once."""
    from .scenes import read_scene, velocities
    scenes = {p.stem: read_scene(p, schema_path, ("fe",)) for p in sorted(Path(folder).glob("*.yaml"))}
    physics = {name: {k: v for k, v in d.items() if k not in ("description", "velocities", "noses")}
               for name, d in scenes.items()}
    owners, seen = {}, {}
    for name in sorted(scenes, key=lambda n: (n != "table3", n)):   # Table 3's own jobs first
        d = scenes[name]
        for v in velocities(d["velocities"]):
            for nose, spec in d["noses"].items():
                key = (nose, f"{v:g}", repr(spec), repr(physics[name]))
                owners[(name, nose, f"{v:g}")] = seen.setdefault(key, name)
    return owners


def fe_calibrated_scenes(folder, schema_path, parameter="erosion_strain") -> set:
    """The finite-element scenes whose ``parameter`` (fe.erosion_strain of an eroding target, fe.strength_scale of an
    erosion-free one) is calibrated on DO1 (their shots need the calibration)."""
    from .scenes import read_scene
    return {p.stem for p in sorted(Path(folder).glob("*.yaml"))
            if read_scene(p, schema_path, ("fe",)).get("fe", {}).get(parameter) == "calibrated"}


def fe_scene_shots(folder, schema_path) -> dict:
    """Shots of the finite-element scenes: scene name -> [(nose, velocity tag)], every scene validated (level fe)."""
    from .scenes import read_scene, velocities
    shots = {}
    for path in sorted(Path(folder).glob("*.yaml")):
        data = read_scene(path, schema_path, ("fe",))
        shots[path.stem] = [(nose, f"{v:g}") for v in velocities(data["velocities"]) for nose in data["noses"]]
    return shots


def end_with_parent(poll_s=1.0, grace_s=5.0):
    """End this process when the process that started it ends (a Snakemake job whose Snakemake was killed, even by
    SIGKILL, which it cannot pass on): a daemon thread polls the parent; once it is gone, SIGTERM to this process
    (the default action ends it at once; the writes of the package are atomic, so no half-written output stays),
    and SIGKILL after ``grace_s`` if that did not end it."""
    import os
    import signal
    import threading
    import time

    parent = os.getppid()

    def watch():
        while os.getppid() == parent:
            time.sleep(poll_s)
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(grace_s)
        os.kill(os.getpid(), signal.SIGKILL)

    threading.Thread(target=watch, name="end-with-parent", daemon=True).start()
