"""A verification check: a quantity we compute, its independent reference (closed form, published or oracle
solution) and the interval accepted around it; the verification modules return lists of them, the tests assert
them and the pipeline writes them out."""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace


@dataclass(frozen=True)
class Check:
    problem: str
    quantity: str
    ours: float
    reference: float  # the closed-form or published value (NaN where the check is a bound only)
    low: float  # the accepted interval [low, high]
    high: float
    unit: str
    source: str

    @property
    def holds(self) -> bool:
        return bool(self.low <= self.ours <= self.high)

    @property
    def rel_dev(self) -> float:
        """ours / reference - 1 (NaN without a reference)."""
        return self.ours / self.reference - 1 if math.isfinite(self.reference) and self.reference != 0 else math.nan

    def row(self) -> dict:
        row = asdict(self)
        return {**{k: row[k] for k in ("problem", "quantity", "ours", "reference")}, "rel_dev": self.rel_dev,
                **{k: row[k] for k in ("low", "high", "unit", "source")}, "holds": self.holds}


def near(problem, quantity, ours, reference, rtol, unit, source):
    """ours within rtol (relative) of reference."""
    return Check(problem, quantity, float(ours), reference, reference - rtol * abs(reference),
                 reference + rtol * abs(reference), unit, source)


def below(problem, quantity, ours, bound, unit, source):
    """ours at most bound (no reference value)."""
    return Check(problem, quantity, float(ours), math.nan, -math.inf, bound, unit, source)


def shifted(check: Check) -> Check:
    """The check with a deliberately wrong reference: a two-sided interval moved by its full width (twice its
    half-width) away from the computed value, a one-sided bound moved past it. A check that can fail does not
    hold for it; an interval open on both sides cannot fail and is refused."""
    c = check
    if math.isfinite(c.low) and math.isfinite(c.high):
        step = (c.high - c.low) * (1.0 if c.ours <= 0.5 * (c.low + c.high) else -1.0)
        return replace(c, reference=c.reference + step, low=c.low + step, high=c.high + step)
    margin = 1e-6 * abs(c.ours) + 1e-300
    if math.isfinite(c.high):
        return replace(c, high=c.ours - margin)
    if math.isfinite(c.low):
        return replace(c, low=c.ours + margin)
    raise ValueError(f"{c.problem}: {c.quantity}: an interval open on both sides cannot fail")


# How a source states that the discrete algebra makes a value its reference exactly, or that round-off is what the
# check measures: in these words (a source that merely names an exact solution, or says a scheme is not exactly
# conservative, states neither).
EXACT_MARKS = ("(exact)", "exact in the discrete algebra", "(round-off", "round-off)")


def identical(check: Check) -> bool:
    """The computed value is exactly its reference (or exactly 0 for a bound on a quantity whose ideal is 0): a
    check that may hold by construction, unless its source says the discrete algebra makes it exact (or names
    round-off as what it measures) in one of EXACT_MARKS."""
    c = check
    ideal = c.reference if math.isfinite(c.reference) else 0.0
    return c.ours == ideal and not any(mark in c.source for mark in EXACT_MARKS)


def run_all(problems, log=None):
    """The checks of every (label, problem) pair, the problem a callable returning Checks; one line each to ``log``
    (a callable; None: quiet)."""
    checks = []
    for label, problem in problems:
        new = problem()
        if log is not None:
            log(f"{label}: {sum(c.holds for c in new)} of {len(new)} checks hold")
        checks += new
    return checks
