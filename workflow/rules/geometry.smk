# Nose geometry -> inference of unstated dimensions -> N* of the study's noses.


rule infer_fig4_design:
    input: **task("tasks.geometry"),
    output: json="results/geometry/double_ogive_fig4.json", family="results/geometry/double_ogive_fig4_family.csv",
    params: cfg=config["fig4_design"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/infer_fig4_design.tsv"
    log: "results/logs/infer_fig4_design.log",
    script: "../scripts/run_task.py"


use rule infer_fig4_design as infer_table4_do1 with:
    input: **task("tasks.geometry"), reference=config["reference"],
    output: json="results/geometry/double_ogive_table4.json", family="results/geometry/double_ogive_table4_family.csv",
    params: cfg=config["table4_do1"], projectile=config["projectile"],
    benchmark: "results/benchmarks/infer_table4_do1.tsv"
    log: "results/logs/infer_table4_do1.log",


rule geometry:
    input: **task("tasks.geometry"), **GEOMETRY_RESULTS, reference=config["reference"],
    output: noses="results/nstar/noses.csv", curves="results/nstar/curves.csv", bands="results/nstar/k_bands.csv",
    params: projectile=config["projectile"], table4=config["table4"], fig4=config["fig4_design"],
            points=config["figures"]["points_per_segment"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/geometry.tsv"
    log: "results/logs/geometry.log",
    script: "../scripts/run_task.py"
