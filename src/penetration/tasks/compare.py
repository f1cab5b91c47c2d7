"""A user's nose study as a Snakemake target: a study YAML compared at its levels (shots.compare), as the command
line's compare does it."""
from __future__ import annotations

from pathlib import Path

from ..figures.compare import write_comparison
from ..pipeline.config import load_with
from ..pipeline.io import task
from ..shots import compare as C


@task
def compare_study(inputs, outputs, params):
    study = C.study_from_doc(load_with(Path(inputs.study), {}), f"study {inputs.study}")
    noses, ctxs, validated = C.prepare(study, ".", params.profile, "li_chen", "laboratory", say=print,
                                       workers=params.workers)
    jobs = C.plan(study)
    print(C.describe_plan(jobs, params.workers), flush=True)
    done = C.run_jobs(study, noses, ctxs, jobs, params.workers,
                      lambda i, n: print(f"compare: run {i}/{n} done", flush=True) if i == n or i % 10 == 0 else None)
    failed = [f"{j.level} {j.variant} {j.nose} {j.velocity:g} m/s: {e}" for j, e in C.base_failures(done)]
    if failed:
        raise RuntimeError("runs failed: " + "; ".join(failed))
    table = C.tabulate(study, noses, done, validated, "laboratory", "li_chen", ctxs)
    write_comparison(C.output_files(Path(outputs.csv).parent), table, **C.drawing(study, noses))
