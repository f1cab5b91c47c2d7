"""Task of the FE level's verification problems (penetration.fe.verification)."""
from __future__ import annotations

import pandas as pd

from ..fe import verification
from ..io import task, write_csv


@task
def fe_verification(inputs, outputs, params):
    """Every check of the verification problems with its reference and the interval accepted around it. A check
    that does not hold is written as such (holds = False) and named in the log; the tests fail on it."""
    checks = verification.all_checks()
    write_csv(pd.DataFrame([c.row() for c in checks]), outputs.csv)
    for c in checks:
        if not c.holds:
            print(f"warning: {c.problem}: {c.quantity} = {c.ours:.6g} {c.unit} outside [{c.low:.6g}, {c.high:.6g}]")
