"""The package is laid out by stage: a handful of modules at the top, every other module in a stage folder; folders
import one way, nothing imports in a cycle; physics does no I/O, plotting or printing; figures only draw.

Every entry at the top of the package (a module or a folder, found on the file system) has its place in LAYERS, so
a new module or folder cannot slip past these tests.
"""
import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[1] / "src/penetration"
# the layers, in the direction of imports: an entry imports only entries before it
LAYERS = ["errors", "units", "checks",      # the ground floor: error types, unit constants, a verification check
          "levels",     # the ladder of fidelity: the one list of its levels
          "studies",    # statistics and pure functions of result tables: intervals, regressions, Richardson and the
                        # GCI, mesh convergence, the grid study, the laboratory protocol (no physics: every level's
                        # verification and study may use them)
          "nose",       # geometry of the noses, N* (Eq 5), inference of the paper's unstated noses
          "analytic",   # resistance (Eqs 1-8, 11), the closed-form DOP (Eq 9), its fits, the rigid trajectory
          "concrete",   # HJC (Eqs 12-18), its effects, the target's material as a scene or shot states it
          "cavity",     # the cavity-expansion level, its oracles and verification
          "fe",         # the finite-element level, its verification problems
          "paper",      # the paper's reference values and the diff against them
          "pipeline",   # config, scenes, file I/O, the Snakefile's dispatch, numba caches, the docs' numbers
          "shots",      # a user's shot: its fields, the ladder of levels, how far to trust an answer, the committed
                        # records (calibrations, validation) it reads from a pipeline directory
          "figures",    # one module per figure or table: read results and draw
          "tasks",      # the pipeline's I/O layer, one module per stage
          "warmup", "build", "cli", "__main__"]  # entry points
FOLDERS = ["studies", "nose", "analytic", "concrete", "cavity", "fe", "paper", "pipeline", "shots", "figures", "tasks"]
# pure: no file I/O, plotting or printing
PHYSICS = ["errors", "units", "checks", "levels", "nose", "analytic", "concrete", "cavity", "fe", "shots.fields", "shots.ladder",
           "shots.trust"]
# pure functions on result tables (frames in, frames out): no file I/O, plotting or printing
TABLES = ["studies"]
# the closed form, which the simulation levels check and which never imports them (nor they it)
CLOSED_FORM = "analytic.dop"
SIMULATION = ["analytic.trajectory", "cavity", "fe"]


def top_entries():
    """The package's top-level modules and folders by name (a folder is one entry), from the file system."""
    return {p.stem for p in PKG.glob("*.py") if p.stem != "__init__"} | {
        p.name for p in PKG.iterdir() if p.is_dir() and (p / "__init__.py").is_file()}


def _dotted(path):
    parts = list(path.relative_to(PKG).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_dotted(p): p for p in sorted(PKG.rglob("*.py"))}


def _files(entry):
    """The files of a dotted module or folder."""
    return [p for name, p in MODULES.items() if name == entry or name.startswith(entry + ".")]


def module_imports(path):
    """(package modules, other top-level packages) that the file at ``path`` imports anywhere in it: ``from A import
    b`` names module A.b when that is a module, else A (running A's parents' __init__ is not a dependency)."""
    here = _dotted(path).split(".") if _dotted(path) else []
    package = here if path.name == "__init__.py" else here[:-1]
    inside, outside = set(), set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1] + (node.module.split(".") if node.module else [])
            elif node.module and node.module.split(".")[0] == "penetration":
                base = node.module.split(".")[1:]
            else:
                outside.add(node.module.split(".")[0])
                continue
            for a in node.names:
                sub = ".".join(base + [a.name])
                inside.add(sub if sub in MODULES else ".".join(base))
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = a.name.split(".")
                if parts[0] == "penetration":
                    inside.add(".".join(parts[1:]))
                else:
                    outside.add(parts[0])
    return inside, outside


def imports(entry):
    """Top-level entries (of this package) and other packages that a module or folder imports, its own modules left
    out."""
    names = set()
    for f in _files(entry):
        inside, outside = module_imports(f)
        names |= outside | {m.split(".")[0] for m in inside if m and m.split(".")[0] != entry}
    return names


def dotted_imports(entry):
    return {m for f in _files(entry) for m in module_imports(f)[0]}


def test_every_entry_has_its_place():
    """An entry in no layer fails here: LAYERS holds every top-level module and folder once."""
    assert len(LAYERS) == len(set(LAYERS))
    assert set(LAYERS) == top_entries()
    assert set(FOLDERS) | {e.split(".")[0] for e in PHYSICS} | set(TABLES) <= set(LAYERS)
    assert all(e in MODULES for e in PHYSICS)
    assert {e for e in top_entries() if (PKG / e).is_dir()} == set(FOLDERS)


def test_a_handful_of_modules_at_the_top():
    """The entry points and the ground floor; everything else lives in a stage folder."""
    top = sorted(p.stem for p in PKG.glob("*.py") if p.stem not in ("__init__", "__main__"))
    assert len(top) <= 10, top


@pytest.mark.parametrize("entry", LAYERS[:-1])
def test_no_upstream_imports(entry):
    later = set(LAYERS[LAYERS.index(entry) + 1:])
    assert not (imports(entry) & later), f"{entry} imports a later layer: {sorted(imports(entry) & later)}"


def find_cycle(graph):
    """A cycle of ``graph`` (node -> the nodes it imports) as a list of nodes, first repeated last, or None."""
    state = {}

    def visit(m, path):
        state[m] = "open"
        for d in sorted(graph[m]):
            if state.get(d) == "open":
                return path[path.index(d):] + [d]
            if d not in state and (cycle := visit(d, path + [d])):
                return cycle
        state[m] = "done"
        return None

    for m in sorted(graph):
        if m not in state and (cycle := visit(m, [m])):
            return cycle
    return None


def test_no_import_cycle():
    """The graph of module imports (the whole package, imports inside functions too) has no cycle."""
    graph = {m: {d for d in module_imports(p)[0] if d in MODULES and d != m} for m, p in MODULES.items()}
    assert find_cycle(graph) is None


def test_the_cycle_check_finds_a_cycle():
    """The check above can fail: a registry and its member importing each other, or a longer ring, is a cycle."""
    assert find_cycle({"reg": {"member"}, "member": {"reg"}}) == ["member", "reg", "member"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) is None


@pytest.mark.parametrize("entry", PHYSICS)
def test_physics_is_pure(entry):
    assert not (imports(entry) & {"matplotlib", "pandas", "os", "json", "yaml"})


def _prints(entry):
    """Where a module prints or writes to the standard streams: print named (called or passed as a logger),
    sys.stdout or sys.stderr used."""
    found = []
    for f in _files(entry):
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.Name) and node.id == "print":
                found.append(f"{f.name}:{node.lineno} print")
            elif isinstance(node, ast.Attribute) and node.attr in ("stdout", "stderr") and \
                    isinstance(node.value, ast.Name) and node.value.id == "sys":
                found.append(f"{f.name}:{node.lineno} sys.{node.attr}")
    return found


@pytest.mark.parametrize("entry", PHYSICS)
def test_physics_does_not_print(entry):
    """Physics reports through its return values (or logging); the task layer prints."""
    assert _prints(entry) == []


@pytest.mark.parametrize("entry", TABLES)
def test_result_tables_are_pure(entry):
    assert not (imports(entry) & {"matplotlib", "os", "json", "yaml", "figures", "tasks", "pipeline"})
    calls = {n.func.attr if isinstance(n.func, ast.Attribute) else getattr(n.func, "id", None)
             for f in _files(entry) for n in ast.walk(ast.parse(f.read_text())) if isinstance(n, ast.Call)}
    assert not calls & {"open", "read_csv", "to_csv", "read_json", "savefig"}
    assert _prints(entry) == []


@pytest.mark.parametrize("level", SIMULATION)
def test_closed_form_and_simulation_levels_are_independent(level):
    """The closed form and the simulation levels check each other, so neither imports the other."""
    assert not any(m == CLOSED_FORM or m.startswith(CLOSED_FORM + ".") for m in dotted_imports(level))
    assert not any(m == level or m.startswith(level + ".") for m in dotted_imports(CLOSED_FORM))


def test_figures_read_results_only():
    """Figure modules import the I/O module, the reference table, the unit constants and the list of levels, never a
    task, study or physics module, nor statistics."""
    assert {m for m in dotted_imports("figures") if not m.startswith("figures")} <= {
        "pipeline.io", "paper.reference", "units", "levels"}
    assert "scipy" not in imports("figures")
