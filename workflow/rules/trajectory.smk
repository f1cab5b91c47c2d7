# Scenes at the analytic and trajectory levels; the trajectory engine's tolerance sweep.


rule scene:
    input: **task("tasks.trajectory"), **GEOMETRY_RESULTS,
           cal_do1="results/calibration/do1.json", cal_table3_calc="results/calibration/table3_calc.json",
           diameter="results/geometry/diameter_450kg.json", **scene_input("workflow/scenes/{scene}.yaml"), schema=SCENE_SCHEMA,
    output: dop="results/scenes/{scene}.csv", histories="results/scenes/{scene}_histories.csv",
    params: rtol=config["trajectory"]["rtol"], size=size_params("workflow/scenes/{scene}.yaml", config),
    threads: 1
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/scene_{scene}.tsv"
    log: "results/logs/scene_{scene}.log",
    script: "../scripts/run_task.py"


rule trajectory_tolerance_sweep:
    input: **task("tasks.trajectory"), **GEOMETRY_RESULTS, cal_do1="results/calibration/do1.json",
           **scene_input("workflow/scenes/do1.yaml"), schema=SCENE_SCHEMA,
    output: csv="results/studies/trajectory_tolerance.csv",
    params: study=STUDIES["trajectory_tolerance"],
    threads: 1
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/trajectory_tolerance_sweep.tsv"
    log: "results/logs/trajectory_tolerance_sweep.log",
    script: "../scripts/run_task.py"
