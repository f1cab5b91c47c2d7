# Resistance -> closed-form DOP (Eq 9): named calibrations and inferences, Fig 1 shares, validation.


rule calibrate_table3_calc:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, cal_do1="results/calibration/do1.json",
           **scene_input("workflow/scenes/table3.yaml"), schema=SCENE_SCHEMA, reference=config["reference"],
    output: json="results/calibration/table3_calc.json",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/calibrate_table3_calc.tsv"
    log: "results/logs/calibrate_table3_calc.log",
    script: "../scripts/run_task.py"


use rule calibrate_table3_calc as calibrate_do1 with:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, **scene_input("workflow/scenes/do1.yaml"), schema=SCENE_SCHEMA,
           reference=config["reference"],
    output: json="results/calibration/do1.json",
    params: shot=config["calibration"]["do1"],
    benchmark: "results/benchmarks/calibrate_do1.tsv"
    log: "results/logs/calibrate_do1.log",


# An inference on the paper's own numbers (no model of ours): Eq 9's effective N* and S per nose and Table 3 column.
use rule calibrate_table3_calc as paper_eq9_effective with:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, **scene_input("workflow/scenes/table3.yaml"), schema=SCENE_SCHEMA,
           reference=config["reference"], cal_do1="results/calibration/do1.json",
    output: csv="figures/paper_eq9_effective.csv",
    benchmark: "results/benchmarks/paper_eq9_effective.tsv"
    log: "results/logs/paper_eq9_effective.log",


use rule calibrate_table3_calc as infer_diameter_450kg with:
    input: **task("tasks.analytic"), **GEOMETRY_RESULTS, **scene_input("workflow/scenes/sec22_450kg.yaml"), schema=SCENE_SCHEMA,
           reference=config["reference"], cal_do1="results/calibration/do1.json",
    output: json="results/geometry/diameter_450kg.json",
    params: nose=config["diameter_450kg"]["nose"], axes=config["diameter_450kg"]["axes"],
    benchmark: "results/benchmarks/infer_diameter_450kg.tsv"
    log: "results/logs/infer_diameter_450kg.log",


use rule calibrate_table3_calc as resistance_shares with:
    input: **task("tasks.analytic"),
    output: csv="results/resistance/shares.csv",
    params: cfg=config["fig01"],
    benchmark: "results/benchmarks/resistance_shares.tsv"
    log: "results/logs/resistance_shares.log",


use rule calibrate_table3_calc as validation_predictions with:
    input: **task("tasks.analytic"), shots=config["validation"]["shots"],
    output: csv="results/validation/predictions.csv",
    params: law=config["validation"]["strength_law"],
    benchmark: "results/benchmarks/validation_predictions.tsv"
    log: "results/logs/validation_predictions.log",
