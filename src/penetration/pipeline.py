"""Dispatch from a Snakemake rule to the task of the same name."""
from . import figures  # noqa: F401  (registers the figure and table tasks)
from .tasks import TASKS


def run(name, inputs, outputs, params):
    """Entry point used by workflow/scripts/run_task.py."""
    if name not in TASKS:
        raise KeyError(f"no task named {name!r}; known: {sorted(TASKS)}")
    return TASKS[name](inputs, outputs, params)
