"""The FE package's anatomy: one module per concept, no module over 400 lines, no function over 12 parameters,
and each formula of the explicit step written once and called from both phases of the element pass.

The oracle is the source itself (its syntax tree): a second copy of a formula, a helper that one phase stops
calling, or a module that outgrows its concept fails here."""
import ast
import re
from pathlib import Path

import pytest

FE = Path(__file__).resolve().parents[1] / "src" / "penetration" / "fe"
PKG = FE.parent
MODULES = sorted(FE.rglob("*.py"))
# the independent references are written apart from the solver on purpose (they check it): their own
# stable step or viscosity is not a second copy
REFERENCES = {"chain_reference.py", "cavity_reference.py", "hjc_reference.py", "closed_forms.py", "gas.py"}
HJC = PKG / "concrete" / "hjc.py"


def _functions(path):
    return [n for n in ast.walk(ast.parse(path.read_text())) if isinstance(n, ast.FunctionDef)]


def _calls(fn):
    return {n.func.id if isinstance(n.func, ast.Name) else n.func.attr for n in ast.walk(fn) if isinstance(n, ast.Call)
            and isinstance(n.func, (ast.Name, ast.Attribute))}


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_no_module_of_the_fe_package_exceeds_400_lines(path):
    assert len(path.read_text().splitlines()) <= 400


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_no_function_takes_more_than_12_arguments(path):
    wide = [(f.name, len(f.args.args) + len(f.args.kwonlyargs)) for f in _functions(path)
            if len(f.args.args) + len(f.args.kwonlyargs) > 12]
    assert not wide


# concept -> (the module that defines it, its function, a fragment of its formula that must occur nowhere else)
ONCE = {
    "bulk viscosity": ("timestep.py", "viscosity", r"q1 \* q1 \* lc \* tv \* tv"),
    "stable step": ("timestep.py", "stable_step", r"math\.sqrt\(Q \* Q \+ c \* c\)"),
    "energy increment": ("element.py", "energy_increment", r"\(q_old \+ q_new\) \* tv \* dt"),
    "erosion criterion": ("erosion.py", "erodes", r"eps_p >= value"),
    "node update": ("nodes.py", "new_velocity", r"dtv \* fr / m"),
    "force gather": ("nodes.py", "_corner", r"F\[k, e\]"),
    "deviatoric predictor": ("../concrete/hjc.py", "deviatoric_trial", r"2\.0 \* G \* \(d0 - tr\)"),
    "wave speed": ("constitutive.py", "wave_speed", r"math\.sqrt\(modulus / rho\)"),
}


@pytest.mark.parametrize("concept", sorted(ONCE))
def test_each_formula_of_the_step_is_defined_once(concept):
    home, name, pattern = ONCE[concept]
    homes = [p for p in MODULES + [HJC] if p.name not in REFERENCES
             and any(f.name == name for f in _functions(p))]
    assert [p.name for p in homes] == [Path(home).name]
    copies = [p.name for p in MODULES + [HJC] if p.name not in REFERENCES
              for _ in re.finditer(pattern, p.read_text())]
    assert copies == [Path(home).name], f"{concept}: the formula occurs in {copies}"


def test_both_phases_of_the_element_pass_call_the_same_helpers():
    fns = {f.name: f for f in _functions(FE / "element_pass.py")}
    fast = _calls(fns["_kinematics"])
    scalar = _calls(fns["_scalar"]) | _calls(fns["_scalar_update"])
    for helper in ("viscosity", "stable_step", "energy_increment", "erodes", "wave_speed"):
        assert helper in fast and helper in scalar, helper


def test_the_interior_and_edge_nodes_share_the_force_read_and_the_update():
    """Interior and edge nodes read an element's force through the one _corner and update through the one _update
    (the edges compose the reads under their existence tests: see nodes._edge_force)."""
    fns = {f.name: f for f in _functions(FE / "nodes.py")}
    assert "_corner" in _calls(fns["gather"]) and "_corner" in _calls(fns["_edge_force"])
    assert "gather" in _calls(fns["node_pass"]) and "_edge_force" in _calls(fns["node_pass"])
    assert "_update" in _calls(fns["node_pass"]) and "new_velocity" in _calls(fns["_update"])


def test_the_solver_package_does_not_print():
    """Progress goes through logging (logger penetration.fe), never print or stderr from physics code."""
    for path in MODULES:
        tree = ast.parse(path.read_text())
        assert not [n for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
                    and n.func.id == "print"], path.name
        assert "sys.stderr" not in path.read_text(), path.name
