# HJC -> cavity expansion -> cavity level of the simulation. Rules that build sigma_n
# tables use two threads (the cavity solver runs two velocity chains at once).


rule hjc_eos_paths:
    input: **task("tasks.cavity"), reference=config["reference"],
    output: csv="results/hjc/eos_paths.csv",
    params: **config["fig10"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/hjc_eos_paths.tsv"
    log: "results/logs/hjc_eos_paths.log",
    script: "../scripts/run_task.py"


rule calibrate_cavity_do1:
    input: **task("tasks.cavity"), do1="results/geometry/double_ogive_table4.json", reference=config["reference"],
    output: json="results/calibration/cavity_do1.json",
    params: cfg=config["cavity"], hjc=config["concrete"], shot=config["calibration"]["do1"],
    threads: 2
    resources: mem_mb=2000, runtime=30
    benchmark: "results/benchmarks/calibrate_cavity_do1.tsv"
    log: "results/logs/calibrate_cavity_do1.log",
    script: "../scripts/run_task.py"


rule cavity_table:
    input: **task("tasks.cavity"), cal="results/calibration/cavity_do1.json", reference=config["reference"],
    output: csv="results/cavity/sigma_n.csv",
    params: cfg=config["cavity"], hjc=config["concrete"], projectile=config["projectile"],
    threads: 2
    resources: mem_mb=2000, runtime=10
    benchmark: "results/benchmarks/cavity_table.tsv"
    log: "results/logs/cavity_table.log",
    script: "../scripts/run_task.py"


rule scene_cavity:
    input: **task("tasks.cavity"), **GEOMETRY_RESULTS, sigma="results/cavity/sigma_n.csv",
           cal="results/calibration/cavity_do1.json", reference=config["reference"],
           **scene_input("workflow/scenes/cavity/{scene}.yaml"), schema=SCENE_SCHEMA,
    output: dop="results/scenes/cavity/{scene}.csv", histories="results/scenes/cavity/{scene}_histories.csv",
    params: rtol=config["cavity"]["rtol"], cfg=config["cavity"], hjc=config["concrete"],
            size=size_params("workflow/scenes/cavity/{scene}.yaml", config),
    threads: 2
    resources: mem_mb=2000, runtime=20
    benchmark: "results/benchmarks/scene_cavity_{scene}.tsv"
    log: "results/logs/scene_cavity_{scene}.log",
    script: "../scripts/run_task.py"


rule cavity_verification:
    input: **task("tasks.verification"),
    output: csv="figures/cavity_verification.csv",
    threads: 2
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/cavity_verification.tsv"
    log: "results/logs/cavity_verification.log",
    script: "../scripts/run_task.py"


# The calibration the cavity level of the command line carries over, committed (it runs from a fresh clone).
rule cavity_calibration_record:
    input: **task("tasks.cavity"), cal="results/calibration/cavity_do1.json",
    output: csv="figures/calibration_cavity_do1.csv",
    threads: 1
    resources: mem_mb=500, runtime=2
    benchmark: "results/benchmarks/cavity_calibration_record.tsv"
    log: "results/logs/cavity_calibration_record.log",
    script: "../scripts/run_task.py"
