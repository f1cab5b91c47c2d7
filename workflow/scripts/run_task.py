"""Run the package task named after the calling Snakemake rule."""
from penetration.pipeline import run

run(snakemake.rule, snakemake.input, snakemake.output, snakemake.params)  # noqa: F821
