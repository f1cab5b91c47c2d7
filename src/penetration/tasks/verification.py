"""Tasks of the verification problems of the cavity level (penetration.cavity.verification) and of the FE level
(penetration.fe.verification): every check with its reference and accepted interval, as a table."""
from __future__ import annotations

import pandas as pd

from ..cavity import verification as cavity_checks
from ..fe import verification
from ..pipeline.io import task, write_csv


@task
def fe_verification(inputs, outputs, params):
    """Every check of the verification problems with its reference and the interval accepted around it. A check
    that does not hold is written as such (holds = False) and named in the log; the tests fail on it."""
    _write(verification.all_checks(print), outputs.csv)


@task
def cavity_verification(inputs, outputs, params):
    """The same for the cavity level's solver: closed forms, the similarity oracles, convergence."""
    _write(cavity_checks.all_checks(print), outputs.csv)


def _write(checks, path):
    write_csv(pd.DataFrame([c.row() for c in checks]), path)
    for c in checks:
        if not c.holds:
            print(f"warning: {c.problem}: {c.quantity} = {c.ours:.6g} {c.unit} outside [{c.low:.6g}, {c.high:.6g}]")
