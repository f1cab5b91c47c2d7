"""Each concept is written once: a test per concept that was once written twice or more, failing if a second
definition comes back. The oracle is the source (its syntax tree or text): where a concept's mark (a literal list,
a formula, a function name) occurs, and that it occurs in its one home only."""
import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "src" / "penetration"
PYTHON = sorted(PKG.rglob("*.py")) + sorted((ROOT / "workflow").rglob("*.py"))
SNAKE = [ROOT / "Snakefile", *sorted((ROOT / "workflow/rules").glob("*.smk"))]


def _rel(path):
    return path.relative_to(ROOT).as_posix()


def _trees():
    return {_rel(p): ast.parse(p.read_text()) for p in PYTHON}


TREES = _trees()


def literal_ladders(tree, names):
    """Line numbers of tuple, list or set literals whose strings are exactly ``names`` (in any order)."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            strings = [e.value for e in node.elts if isinstance(e, ast.Constant) and isinstance(e.value, str)]
            if len(strings) == len(node.elts) and set(strings) == set(names) and len(strings) == len(names):
                found.append(node.lineno)
    return found


def test_one_list_of_levels():
    """The ladder is listed in levels.py only; every other module reads it from there (the scenes' table of effects
    per level included), and no rule file spells the levels out."""
    from penetration.levels import LADDER, LEVELS
    from penetration.pipeline.scenes import LEVELS as SCENE_LEVELS
    assert LEVELS == tuple(level.name for level in LADDER) == ("analytic", "trajectory", "cavity", "fe")
    elsewhere = {path: lines for path, tree in TREES.items() if path != "src/penetration/levels.py"
                 and (lines := literal_ladders(tree, LEVELS))}
    assert elsewhere == {}
    assert tuple(SCENE_LEVELS) == LEVELS
    spelled = [_rel(p) for p in SNAKE if re.search(r"analytic\|trajectory\|cavity\|fe", p.read_text())]
    assert spelled == []


def test_the_level_check_finds_a_second_list():
    tree = ast.parse('A = ("fe", "cavity", "trajectory", "analytic")\nB = ["analytic", "cavity"]\nC = {"fe"}')
    assert literal_ladders(tree, ("analytic", "trajectory", "cavity", "fe")) == [1]


def _defines(name_pattern):
    """(file, function) of every function whose name matches ``name_pattern``."""
    return sorted((path, n.name) for path, tree in TREES.items() for n in ast.walk(tree)
                  if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and re.fullmatch(name_pattern, n.name))


def _occurs(pattern):
    """Files whose source matches the regular expression ``pattern``."""
    return sorted(_rel(p) for p in PYTHON if re.search(pattern, p.read_text()))


def test_one_richardson_extrapolation():
    """The extrapolation from three meshes (its gain r^p - 1) is computed in studies/stats.py only; grid_refinement
    and the FE verification's convergence rows call it."""
    assert _occurs(r"\*\* ?\(?p\)? - 1") == ["src/penetration/studies/stats.py"]
    assert [f for f in _defines(r"_?richardson\w*")] == [("src/penetration/studies/stats.py", "richardson")]


def test_one_student_t_and_one_welch():
    """Student-t quantiles and tests, Welch's interval and least-squares fits on log axes live in studies/stats.py."""
    assert _occurs(r"\bt\.ppf\(") == ["src/penetration/studies/stats.py"]
    assert _occurs(r"ttest_1samp|ttest_ind") == ["src/penetration/studies/stats.py"]
    assert _occurs(r"linear_regression\(") == ["src/penetration/studies/stats.py"]
    for name in ("t_interval", "welch", "slope", "within_slope", "t_quantile", "power_law_exponent"):
        assert _defines(name) == [("src/penetration/studies/stats.py", name)], name


def test_one_predict_rows():
    """The loop over a shots table's rows (skip a malformed row or one whose prediction fails, say why) is written
    once (shots.fields.row_predictions); predict_rows is defined once (shots.ladder, every level)."""
    assert _defines("predict_rows") == [("src/penetration/shots/ladder.py", "predict_rows")]
    calls = sorted(path for path, tree in TREES.items() for n in ast.walk(tree) if isinstance(n, ast.Call)
                   and isinstance(n.func, ast.Name) and n.func.id == "row_problem")
    assert calls == ["src/penetration/shots/fields.py"]


def test_the_calibration_memo_hashes_the_code_closure():
    """The finished trials of a DO1 calibration are keyed by the sources of the FE calibration's code closure
    (pipeline.dispatch.code_closure), not by a hand-kept list: the solver, HJC and the calibration itself are in it,
    and no task lists package sources by name."""
    from penetration.tasks.fe import trial_sources
    names = {p.relative_to(PKG).as_posix() for p in trial_sources()}
    assert {"fe/level.py", "fe/solver.py", "fe/element_pass.py", "concrete/hjc.py", "fe/spec.py"} <= names
    assert not any(n.startswith(("tasks/", "figures/")) for n in names)
    assert _occurs(r"PACKAGE ?/ ?\"[a-z_/]+\.py\"") == []


def test_one_switch_between_the_eroding_and_the_erosion_free_target():
    """A target states its formulation (TargetSpec.formulation, read where a shot's model is built); the solver sees
    one object, Controls.erosion_free (the erosion-free target's own controls, None on the eroding target): no
    boolean flag, no copy on the model, and no field of the erosion-free target among the solver's controls."""
    import dataclasses

    from penetration.fe.erosion_free.controls import ErosionFree
    from penetration.fe.spec import Controls
    solver = {f.name: f for f in dataclasses.fields(Controls)}
    assert solver["erosion_free"].default is None
    assert not set(solver) & {f.name for f in dataclasses.fields(ErosionFree)}
    flags = sorted(path for path, tree in TREES.items() for n in ast.walk(tree) if isinstance(n, ast.Attribute)
                   and n.attr == "erosion_free" and isinstance(n.ctx, ast.Store))
    assert flags == []
    readers = sorted({path for path, tree in TREES.items() for n in ast.walk(tree)
                      if isinstance(n, ast.Attribute) and n.attr == "formulation"})
    assert all(p in ("src/penetration/fe/spec.py", "src/penetration/fe/shot.py", "src/penetration/fe/level.py")
               or p.startswith(("src/penetration/tasks/", "workflow/")) for p in readers), readers


VERDICT_WORDS = {"holds", "weaker", "fails", "matches", "misses", "cannot decide", "fitted to it", "good", "poor",
                 "undecided", "reproduced", "deviates"}


def test_one_verdict_per_claim():
    """A claim's verdict is computed once: the paper's claims at every level by paper.claims (the task claims writes
    them; the report lays them out), a contrast's ranking on the erosion-free target by studies.grid (its verdict
    column; the diff, the docs and the claims read it). The study's columns the verdict rests on are read by no one
    else, and no function of the report returns a verdict word."""
    for name in ("least_gain", "gains_at_v", "do1", "smaller_peak", "predicts", "contrast_ranking", "claim_rows"):
        assert _defines(name) == [("src/penetration/paper/claims.py", name)], name
    assert _defines("ranking_verdict") == [("src/penetration/studies/grid.py", "ranking_verdict")]
    assert _occurs(r"ls_ranking") == ["src/penetration/studies/grid.py"]
    report = TREES["workflow/report.py"]
    judging = sorted(f.name for f in ast.walk(report) if isinstance(f, ast.FunctionDef)
                     for n in ast.walk(f) if isinstance(n, ast.Constant) and n.value in VERDICT_WORDS)
    assert judging == []


def test_one_run_spec_assembly():
    """A run spec is assembled in fe.level.run_spec only (a scene's shot, both DO1 calibrations, a user's shot, the
    benchmarks): no other module of the package or the workflow constructs a RunSpec (workflow/records/ keeps the
    scripts of past runs as they ran)."""
    builds = sorted(path for path, tree in TREES.items() for n in ast.walk(tree) if isinstance(n, ast.Call)
                    and getattr(n.func, "id", getattr(n.func, "attr", None)) == "RunSpec"
                    and not path.startswith("workflow/records/"))
    assert builds == ["src/penetration/fe/level.py"]
    assert _defines("run_spec") == [("src/penetration/fe/level.py", "run_spec")]
