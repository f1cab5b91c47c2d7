# Resistance -> closed-form DOP (Eq 9): named calibrations and inferences, Fig 1 shares, validation.


rule calibrate_do1:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, scene="workflow/scenes/do1.yaml", schema=SCENE_SCHEMA,
           reference=config["reference"],
    output: json="results/calibration/do1.json",
    params: shot=config["calibration"]["do1"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/calibrate_do1.tsv"
    log: "results/logs/calibrate_do1.log",
    script: "../scripts/run_task.py"


rule calibrate_table3_calc:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, cal_do1="results/calibration/do1.json",
           scene="workflow/scenes/table3.yaml", schema=SCENE_SCHEMA, reference=config["reference"],
    output: json="results/calibration/table3_calc.json",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/calibrate_table3_calc.tsv"
    log: "results/logs/calibrate_table3_calc.log",
    script: "../scripts/run_task.py"


rule infer_diameter_450kg:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, scene="workflow/scenes/sec22_450kg.yaml", schema=SCENE_SCHEMA,
           reference=config["reference"], cal_do1="results/calibration/do1.json",
    output: json="results/geometry/diameter_450kg.json",
    params: nose=config["diameter_450kg"]["nose"], axes=config["diameter_450kg"]["axes"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/infer_diameter_450kg.tsv"
    log: "results/logs/infer_diameter_450kg.log",
    script: "../scripts/run_task.py"


rule resistance_shares:
    input: **task("tasks.analytic"),
    output: csv="results/resistance/shares.csv",
    params: cfg=config["fig01"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/resistance_shares.tsv"
    log: "results/logs/resistance_shares.log",
    script: "../scripts/run_task.py"


rule validation_predictions:
    input: **task("tasks.analytic"), shots=config["validation"]["shots"],
    output: csv="results/validation/predictions.csv",
    params: law=config["validation"]["strength_law"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/validation_predictions.tsv"
    log: "results/logs/validation_predictions.log",
    script: "../scripts/run_task.py"
