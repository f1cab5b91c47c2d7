# Studies of the cavity level: ablation, solver sweep, calibration variants, DO1 family.


rule cavity_ablation:
    input: **task("tasks.cavity_studies"), **GEOMETRY_RESULTS, cal="results/calibration/cavity_do1.json",
           reference=config["reference"], **scene_input("workflow/scenes/cavity/table3.yaml"), schema=SCENE_SCHEMA,
    output: csv="figures/ablation_cavity.csv", timing="figures/timing/ablation_cavity.csv",
    params: cfg=config["cavity"], hjc=config["concrete"], shot=config["calibration"]["do1"], study=STUDIES["cavity_ablation"],
    threads: 2
    resources: mem_mb=2000, runtime=30
    benchmark: "results/benchmarks/cavity_ablation.tsv"
    log: "results/logs/cavity_ablation.log",
    script: "../scripts/run_task.py"


use rule cavity_ablation as cavity_solver_sweep with:
    input: **task("tasks.cavity_studies"), do1="results/geometry/double_ogive_table4.json",
           cal="results/calibration/cavity_do1.json", sigma="results/cavity/sigma_n.csv", reference=config["reference"],
    output: csv="results/studies/cavity_solver.csv",
    params: cfg=config["cavity"], hjc=config["concrete"], shot=config["calibration"]["do1"], study=STUDIES["cavity_solver"],
    benchmark: "results/benchmarks/cavity_solver_sweep.tsv"
    log: "results/logs/cavity_solver_sweep.log",


use rule cavity_ablation as cavity_calibration_variants with:
    input: **task("tasks.cavity_studies"), **GEOMETRY_RESULTS, cal="results/calibration/cavity_do1.json",
           reference=config["reference"], **scene_input("workflow/scenes/cavity/table3.yaml"), schema=SCENE_SCHEMA,
    output: csv="results/cavity/calibration_variants.csv",
    params: cfg=config["cavity"], hjc=config["concrete"], shot=config["calibration"]["do1"], study=STUDIES["cavity_calibration_variants"],
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/cavity_calibration_variants.tsv"
    log: "results/logs/cavity_calibration_variants.log",


rule do1_family_sensitivity:
    input: **task("tasks.cavity_studies"), family="results/geometry/double_ogive_table4_family.csv",
           sigma="results/cavity/sigma_n.csv", reference=config["reference"],
    output: csv="figures/do1_family_sensitivity.csv",
    params: cfg=config["cavity"], shot=config["calibration"]["do1"], study=STUDIES["do1_family"],
    threads: 1
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/do1_family_sensitivity.tsv"
    log: "results/logs/do1_family_sensitivity.log",
    script: "../scripts/run_task.py"
