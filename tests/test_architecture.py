"""Stages import one way; physics modules do no I/O, plotting or printing; figures only draw.

Every module of the package (found on the file system, a subpackage counting as one) has its place in ORDER, so a new
module cannot slip past these tests.
"""
import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[1] / "src/penetration"
# the direction of imports: a module imports only modules before it
ORDER = ["errors", "units", "checks", "mesh_convergence", "geometry", "hjc_effects", "nstar", "inference", "resistance",
         "dop", "calibration", "trajectory", "hjc", "concrete", "triaxial", "cavity", "cavity_level", "cavity_oracles",
         "cavity_verification", "fe", "fe_level", "shots", "levels", "trust", "warmup", "reference", "diff",
         "fe_studies", "grid_study", "laboratory", "config", "scenes", "numba_cache", "io", "docs", "figures", "tasks", "pipeline", "build", "cli",
         "__main__"]
# pure: no file I/O, plotting or printing
PHYSICS = ["errors", "units", "checks", "mesh_convergence", "geometry", "hjc_effects", "nstar", "inference",
           "resistance", "dop", "calibration", "trajectory", "hjc", "concrete", "triaxial", "cavity", "cavity_level",
           "cavity_oracles", "cavity_verification", "fe", "fe_level", "shots", "levels", "trust"]
# the simulation levels, which the closed form (dop) checks and which never import it
SIMULATION = ["trajectory", "cavity", "cavity_level", "fe", "fe_level"]
# pure functions on result tables (frames in, frames out): no file I/O, plotting or printing
TABLES = ["fe_studies", "grid_study", "laboratory"]

# known violations: the tests run and must fail until the code is fixed (strict), then the mark goes
KNOWN = {"pure": {}, "quiet": {}}


def _marked(kind, modules):
    return [pytest.param(m, marks=KNOWN[kind][m]) if m in KNOWN[kind] else m for m in modules]


def package_modules():
    """The package's modules and subpackages by name (a subpackage is one entry), from the file system."""
    return {p.stem for p in PKG.glob("*.py") if p.stem != "__init__"} | {
        p.name for p in PKG.iterdir() if p.is_dir() and (p / "__init__.py").is_file()}


def _files(module):
    path = PKG / f"{module}.py"
    return [path] if path.exists() else sorted((PKG / module).rglob("*.py"))


def imports(module):
    """Names a module (or every file of a subpackage) imports: the package's top-level modules it uses and the
    top-level names of other packages; a subpackage's imports of its own modules are left out."""
    names = set()
    for f in _files(module):
        depth = len(f.relative_to(PKG).parts) - 1  # 0: a module of the package, 1: a module of a subpackage
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                if node.level != depth + 1:
                    continue  # within the subpackage
                names.update([node.module.split(".")[0]] if node.module else [a.name for a in node.names])
            elif isinstance(node, ast.ImportFrom) and node.module:
                parts = node.module.split(".")
                names.add(parts[1] if parts[0] == "penetration" and len(parts) > 1 else parts[0])
            elif isinstance(node, ast.Import):
                for a in node.names:
                    parts = a.name.split(".")
                    names.add(parts[1] if parts[0] == "penetration" and len(parts) > 1 else parts[0])
    return names


def test_every_module_has_its_place():
    """A module in neither list fails here: ORDER holds every module once, PHYSICS and the others are among them."""
    assert len(ORDER) == len(set(ORDER))
    assert set(ORDER) == package_modules()
    assert set(PHYSICS) | set(SIMULATION) | set(TABLES) <= set(ORDER)


@pytest.mark.parametrize("module", ORDER[:-1])
def test_no_upstream_imports(module):
    later = set(ORDER[ORDER.index(module) + 1:])
    assert not (imports(module) & later), f"{module} imports a later stage: {sorted(imports(module) & later)}"


@pytest.mark.parametrize("module", _marked("pure", PHYSICS))
def test_physics_is_pure(module):
    assert not (imports(module) & {"matplotlib", "pandas", "os", "json", "yaml"})


def _prints(module):
    """Where a module prints or writes to the standard streams: print named (called or passed as a logger),
    sys.stdout or sys.stderr used."""
    found = []
    for f in _files(module):
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.Name) and node.id == "print":
                found.append(f"{f.name}:{node.lineno} print")
            elif isinstance(node, ast.Attribute) and node.attr in ("stdout", "stderr") and \
                    isinstance(node.value, ast.Name) and node.value.id == "sys":
                found.append(f"{f.name}:{node.lineno} sys.{node.attr}")
    return found


@pytest.mark.parametrize("module", _marked("quiet", PHYSICS))
def test_physics_does_not_print(module):
    """Physics reports through its return values (or logging); the task layer prints."""
    assert _prints(module) == []


@pytest.mark.parametrize("module", TABLES)
def test_result_tables_are_pure(module):
    assert not (imports(module) & {"matplotlib", "os", "json", "yaml", "io", "figures", "tasks", "pipeline"})
    calls = {n.func.attr if isinstance(n.func, ast.Attribute) else getattr(n.func, "id", None)
             for f in _files(module) for n in ast.walk(ast.parse(f.read_text())) if isinstance(n, ast.Call)}
    assert not calls & {"open", "read_csv", "to_csv", "read_json", "savefig"}
    assert _prints(module) == []


@pytest.mark.parametrize("level", SIMULATION)
def test_dop_and_simulation_levels_are_independent(level):
    """The closed form and the simulation levels check each other, so neither imports the other."""
    assert "dop" not in imports(level)
    assert level not in imports("dop")


def test_figures_read_results_only():
    """Figure modules import the I/O module, the reference table and the unit constants, never a task, study or
    physics module, nor statistics."""
    assert imports("figures") & package_modules() <= {"io", "reference", "units"}
    assert "scipy" not in imports("figures")
