"""Every verification check can fail: run with a deliberately wrong reference it does not hold, and its value is
not its reference by construction. Runs every problem of both levels' verification tables (the rows of
``figures/fe_verification.csv`` and ``figures/cavity_verification.csv``: ``all_checks`` is the registry run in
order); the problems of more than about 5 s are slow tests (``make check``)."""
import math
from pathlib import Path

import pandas as pd
import pytest

from penetration.cavity import verification as CV
from penetration.checks import Check, below, identical, near, shifted
from penetration.fe import verification as V

# problems of more than about 5 s: the pipeline's rule fe_verification runs them (`make check` rebuilds the table and
# compares every row, its verdict exactly, with the committed one), and the committed rows are tested below
SLOW = {"Taylor bar", "driven HJC cavity", "Hertz", "erosion-free penetration audit", "erosion-free pilot guide"}
CASES = [(level, label) for level, registry in (("fe", V.PROBLEMS), ("cavity", CV.PROBLEMS)) for label in registry
         if label not in SLOW]
ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("table", ["figures/fe_verification.csv", "figures/cavity_verification.csv"])
def test_every_committed_row_holds_and_fails_with_a_wrong_reference(table):
    """The same three properties on every row of the committed tables, the slow problems' included."""
    t = pd.read_csv(ROOT / table, keep_default_na=False, na_values=[""])
    rows = [Check(r.problem, r.quantity, r.ours, r.reference, r.low, r.high, r.unit, r.source) for r in t.itertuples()]
    assert len(rows) >= 10
    assert all(c.holds for c in rows), [c for c in rows if not c.holds]
    assert not any(shifted(c).holds for c in rows), [c for c in rows if shifted(c).holds]
    # the table's values have 12 digits; whether a value is its reference exactly is in rel_dev, computed unrounded
    exact = [c for c, r in zip(rows, t.itertuples()) if identical(c) and not (math.isfinite(r.reference) and r.rel_dev != 0)]
    assert not exact, exact
    problems = {c.problem for c in rows}
    assert any(p.startswith("Taylor bar") for p in problems) or "cavity" in table


@pytest.mark.parametrize("level,label", CASES)
def test_every_check_holds_and_fails_with_a_wrong_reference(level, label):
    """The problem's checks hold; each fails with its reference moved by twice its accepted half-width (or its
    bound moved past the value); none equals its reference (or 0, for a bound) unless the discrete algebra makes
    it exact, which its source then says."""
    checks = {"fe": V.PROBLEMS, "cavity": CV.PROBLEMS}[level][label]()
    assert checks and all(math.isfinite(c.ours) for c in checks)
    assert all(c.holds for c in checks), [c for c in checks if not c.holds]
    assert not any(shifted(c).holds for c in checks), [c for c in checks if shifted(c).holds]
    assert not any(identical(c) for c in checks), [c for c in checks if identical(c)]
    assert all(c.low <= c.reference <= c.high for c in checks if math.isfinite(c.reference))


@pytest.mark.parametrize("module", [V, CV])
def test_all_checks_runs_every_registered_problem_in_order(module, monkeypatch):
    calls = []

    def fake(name):
        def problem():
            calls.append(name)
            return [near(name, "q", 1.0, 1.0 + 1e-9, 1e-3, "1", "s")]
        return problem
    monkeypatch.setattr(module, "PROBLEMS", {"a": fake("a"), "b": fake("b")})
    lines = []
    rows = module.all_checks(log=lines.append)
    assert calls == ["a", "b"] and [r.problem for r in rows] == ["a", "b"]
    assert lines == ["a: 1 of 1 checks hold", "b: 1 of 1 checks hold"]


def test_every_problem_function_of_the_fe_table_is_registered():
    """A public function of fe.verification's problem modules (each returns checks) is in the table (registered by
    @problem)."""
    from penetration.fe.verification import (contact as verification_contact, erosion_free as verification_erosion_free,
                                             mechanics as verification_mechanics)
    registered = {getattr(f, "func", f).__name__ for f in V.PROBLEMS.values()}
    documented = {name for mod in (verification_mechanics, verification_contact, verification_erosion_free)
                  for name, f in vars(mod).items()
                  if callable(f) and getattr(f, "__module__", "") == mod.__name__ and not name.startswith("_")}
    assert documented == registered, documented ^ registered


def test_a_wrong_reference_fails_every_kind_of_row():
    rows = [near("p", "two-sided", 1.01, 1.0, 0.02, "1", "s"),            # upper half: moved down
            near("p", "two-sided", 0.99, 1.0, 0.02, "1", "s"),            # lower half: moved up
            below("p", "bound", 0.3, 1.0, "1", "s"),
            below("p", "bound at 0", 0.0, 1.0, "1", "0 (round-off)"),
            Check("p", "lower bound", 5.0, math.nan, 2.0, math.inf, "1", "s"),
            Check("p", "interval without reference", 0.5, math.nan, 0.0, 1.0, "1", "s")]
    assert all(r.holds for r in rows)
    assert not any(shifted(r).holds for r in rows)
    moved = shifted(rows[0])
    assert moved.high - moved.low == pytest.approx(rows[0].high - rows[0].low) and moved.reference == pytest.approx(0.96)
    with pytest.raises(ValueError, match="open on both sides"):
        shifted(Check("p", "anything", 1.0, math.nan, -math.inf, math.inf, "1", "s"))


def test_a_change_that_is_exactly_zero_is_caught():
    """The far-boundary check this replaced: the same mesh run twice, a change of exactly 0."""
    assert identical(below("HJC cavity", "|change of the wall stress| / it", 0.0, 0.005, "1", "convergence"))
    assert identical(near("p", "q", 2.0, 2.0, 0.01, "1", "closed form"))
    assert not identical(near("p", "q", 2.0, 2.0, 0.01, "1", "exact in the discrete algebra"))
    assert not identical(below("p", "q", 0.0, 1e-9, "1", "conservation (round-off)"))
    assert not identical(below("p", "q", 1e-17, 1e-9, "1", "conservation"))
    # a source that names an exact solution, or says a scheme is not exactly conservative, claims no exactness
    assert identical(near("p", "q", 2.0, 2.0, 0.01, "1", "exact linear-elastic solution (outgoing spherical wave)"))
    assert identical(below("p", "q", 0.0, 0.01, "1", "conservation (small: the remap is not exactly conservative)"))
    assert not identical(below("p", "q", 0.0, 1e-9, "1", "0 (round-off of the positions)"))
    assert not identical(below("p", "q", 0.0, 1e-9, "1", "0 exactly: nothing is deleted (exact)"))
