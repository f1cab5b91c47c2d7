# The replication report (workflow/report.py, a jupytext percent file): executed in a kernel and rendered to one
# standalone HTML file; it reads the figures and results of `all` and the findings (no physics).


rule report:
    input: **task("tasks.report"), source="workflow/report.py", findings=config["findings"], outputs=REPORT_INPUTS,
           fits=[GEOMETRY_RESULTS["do1"], "results/calibration/do1.json", "results/calibration/cavity_do1.json",
                 "results/geometry/diameter_450kg.json", "results/scenes/sec22_450kg.csv"],
    output: html="figures/report.html",
    params: profile=config["fe_profile"], timeout_s=600,
    threads: 1
    resources: mem_mb=2000, runtime=15
    benchmark: "results/benchmarks/report.tsv"
    log: "results/logs/report.log",
    script: "../scripts/run_task.py"
