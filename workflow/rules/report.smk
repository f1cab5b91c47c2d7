# The replication report (workflow/report.py, a jupytext percent file): executed in a kernel and rendered to one
# standalone HTML file; it reads the figures and results of `all` and the findings (no physics).


rule report:
    input: **task("tasks.report"), source="workflow/report.py", reference=config["reference"], findings=config["findings"],
           outputs=REPORT_INPUTS,
           timing=["figures/timing/pipeline_rules.csv", "figures/timing/pipeline_stages.csv"],
           fits=[GEOMETRY_RESULTS["do1"], "results/calibration/do1.json", "results/calibration/cavity_do1.json",
                 "results/geometry/diameter_450kg.json", "results/scenes/sec22_450kg.csv"],
    output: html="figures/report.html",
    params: profile=config["fe_profile"], timeout_s=600, studies=STUDY_OUTPUTS,
    threads: 1
    resources: mem_mb=2000, runtime=15
    benchmark: "results/benchmarks/report.tsv"
    log: "results/logs/report.log",
    script: "../scripts/run_task.py"


# Every job's recorded wall time, per rule and per stage (after every job of `all` but the report, whose record and
# this rule's own are those of their previous run).
rule pipeline_timing:
    input: **task("tasks.timing"), outputs=REPORT_INPUTS,
    output: rules="figures/timing/pipeline_rules.csv", stages="figures/timing/pipeline_stages.csv",
    params: folder="results/benchmarks",
            patterns=lambda w: {r.name: str(r.benchmark) for r in workflow.rules if r.benchmark},
            rule_files=lambda w: {r.name: Path(r.snakefile).stem for r in workflow.rules},
    threads: 1
    resources: mem_mb=500, runtime=2
    benchmark: "results/benchmarks/pipeline_timing.tsv"
    log: "results/logs/pipeline_timing.log",
    script: "../scripts/run_task.py"
