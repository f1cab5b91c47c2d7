"""Stages import one way; physics modules do no I/O or plotting."""
import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[1] / "src/penetration"
ORDER = ["errors", "units", "mesh_convergence", "geometry", "hjc_effects", "nstar", "inference", "resistance", "dop", "trajectory", "hjc", "cavity", "cavity_level",
         "calibration", "shots", "levels", "reference", "diff", "config", "scenes", "io", "figures", "tasks", "pipeline", "cli"]
PHYSICS = ["mesh_convergence", "geometry", "nstar", "inference", "resistance", "dop", "trajectory", "hjc", "cavity", "cavity_level",
           "calibration", "shots", "levels"]


def imports(module):
    path = PKG / f"{module}.py"
    files = [path] if path.exists() else sorted((PKG / module).glob("*.py"))
    names = set()
    for node in (n for f in files for n in ast.walk(ast.parse(f.read_text()))):
        if isinstance(node, ast.ImportFrom) and node.level >= 1 and node.module:
            names.add(node.module.split(".")[0])
        elif isinstance(node, ast.ImportFrom) and node.level >= 1:
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.Import):
            names.update(a.name.split(".")[0] for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module.split(".")[0])
    return names


@pytest.mark.parametrize("module", ORDER[:-1])
def test_no_upstream_imports(module):
    later = set(ORDER[ORDER.index(module) + 1:])
    assert not (imports(module) & later), f"{module} imports a later stage"


@pytest.mark.parametrize("module", PHYSICS)
def test_physics_is_pure(module):
    assert not (imports(module) & {"matplotlib", "pandas", "os", "json", "yaml"})


def test_dop_and_simulation_levels_are_independent():
    """The closed form and the trajectory engine check each other, so neither imports the other."""
    assert "trajectory" not in imports("dop")
    assert "dop" not in imports("trajectory")


def test_figures_read_results_only():
    """Figure modules import the I/O module and the reference table, never a task or physics module."""
    assert not imports("figures") & {"tasks", "pipeline", *PHYSICS}


def test_cavity_level_does_not_use_the_closed_form():
    assert "dop" not in imports("cavity") and "dop" not in imports("cavity_level")
