"""The workflow's rules as Snakemake loads them, for the tests of what the rules declare.

A rule's declarations may be inherited from its kind's first rule (`use rule ... with:`) or made by a loop (the
paper's figures and tables), so the text of the .smk files does not show each rule's: the loaded workflow does.
"""
import functools
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@functools.lru_cache(maxsize=None)
def loaded_rules() -> dict:
    """Rule name -> snakemake.rules.Rule of the Snakefile with its default config."""
    from snakemake.api import SnakemakeApi
    from snakemake.settings.types import OutputSettings, ResourceSettings

    with SnakemakeApi(OutputSettings(quiet=True)) as api:
        workflow = api.workflow(resource_settings=ResourceSettings(), snakefile=ROOT / "Snakefile", workdir=ROOT)
        return {rule.name: rule for rule in workflow._workflow.rules}
