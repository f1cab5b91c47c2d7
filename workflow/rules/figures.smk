# One rule per figure or table of the paper, named after it.


rule fig03:
    input: FIG_SRC, f"{SRC}figures/fig03.py", curves="results/nstar/curves.csv", bands="results/nstar/k_bands.csv", reference=config["reference"],
    output: png="figures/fig03.png", csv="figures/fig03.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig03.log",
    script: "../scripts/run_task.py"


rule fig04:
    input: FIG_SRC, f"{SRC}figures/fig04.py", curves="results/nstar/curves.csv", fig4="results/geometry/double_ogive_fig4.json",
    output: png="figures/fig04.png", csv="figures/fig04.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig04.log",
    script: "../scripts/run_task.py"


rule fig05:
    input: FIG_SRC, f"{SRC}figures/fig05.py", f"{SRC}figures/fig04.py", curves="results/nstar/curves.csv",
    output: png="figures/fig05.png", csv="figures/fig05.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig05.log",
    script: "../scripts/run_task.py"


rule fig06:
    input: FIG_SRC, f"{SRC}figures/fig06.py", do1="results/geometry/double_ogive_table4.json",
    output: png="figures/fig06.png", csv="figures/fig06.csv",
    params: dpi=config["figures"]["dpi"], points=config["figures"]["points_per_segment"],
    log: "results/logs/fig06.log",
    script: "../scripts/run_task.py"


rule fig07:
    input: FIG_SRC, f"{SRC}figures/fig07.py", noses="results/nstar/noses.csv",
    output: png="figures/fig07.png", csv="figures/fig07.csv",
    params: dpi=config["figures"]["dpi"], points=config["figures"]["points_per_segment"],
    log: "results/logs/fig07.log",
    script: "../scripts/run_task.py"


rule fig16:
    input: FIG_SRC, f"{SRC}figures/fig16.py", curves="results/nstar/curves.csv", noses="results/nstar/noses.csv", reference=config["reference"],
    output: png="figures/fig16.png", csv="figures/fig16.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig16.log",
    script: "../scripts/run_task.py"


rule table1:
    input: FIG_SRC, f"{SRC}figures/tables.py", reference=config["reference"],
    output: csv="figures/table1.csv",
    log: "results/logs/table1.log",
    script: "../scripts/run_task.py"


rule table2:
    input: FIG_SRC, f"{SRC}figures/tables.py", reference=config["reference"],
    output: csv="figures/table2.csv",
    log: "results/logs/table2.log",
    script: "../scripts/run_task.py"


rule table4:
    input: FIG_SRC, f"{SRC}figures/tables.py", noses="results/nstar/noses.csv", reference=config["reference"],
    output: csv="figures/table4.csv",
    log: "results/logs/table4.log",
    script: "../scripts/run_task.py"


rule resistance_shares:
    input: f"{SRC}calibration.py", f"{SRC}resistance.py", f"{SRC}tasks.py",
    output: csv="results/resistance/shares.csv",
    params: cfg=config["fig01"],
    log: "results/logs/resistance_shares.log",
    script: "../scripts/run_task.py"


rule fig01:
    input: FIG_SRC, f"{SRC}figures/fig01.py", shares="results/resistance/shares.csv",
    output: png="figures/fig01.png", csv="figures/fig01.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig01.log",
    script: "../scripts/run_task.py"


rule fig08:
    input: FIG_SRC, f"{SRC}figures/fig08.py", histories="results/scenes/sec22_450kg_histories.csv", dop="results/scenes/sec22_450kg.csv",
    output: png="figures/fig08.png", csv="figures/fig08.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig08.log",
    script: "../scripts/run_task.py"


rule fig09:
    input: FIG_SRC, f"{SRC}figures/fig08.py", histories="results/scenes/sec22_450kg_histories.csv", dop="results/scenes/sec22_450kg.csv", reference=config["reference"],
    output: png="figures/fig09.png", csv="figures/fig09.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig09.log",
    script: "../scripts/run_task.py"


rule fig15:
    input: FIG_SRC, f"{SRC}figures/fig15.py", dop="results/scenes/fig15.csv", cavity="results/scenes/cavity/fig15.csv", reference=config["reference"],
    output: png="figures/fig15.png", csv="figures/fig15.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig15.log",
    script: "../scripts/run_task.py"


rule table3:
    input: FIG_SRC, f"{SRC}figures/tables.py", analytic="results/scenes/table3.csv", stated="results/scenes/table3_stated.csv", fit="results/calibration/table3_calc.json", cavity="results/scenes/cavity/table3.csv", reference=config["reference"],
    output: csv="figures/table3.csv",
    log: "results/logs/table3.log",
    script: "../scripts/run_task.py"


rule validation_predictions:
    input: f"{SRC}tasks.py", f"{SRC}dop.py", f"{SRC}resistance.py", shots=config["validation"]["shots"],
    output: csv="results/validation/predictions.csv",
    params: law=config["validation"]["strength_law"],
    log: "results/logs/validation_predictions.log",
    script: "../scripts/run_task.py"


rule validation:
    input: FIG_SRC, f"{SRC}figures/validation.py", predictions="results/validation/predictions.csv",
    output: png="figures/validation.png", csv="figures/validation.csv",
    params: dpi=config["figures"]["dpi"], law=config["validation"]["strength_law"],
    log: "results/logs/validation.log",
    script: "../scripts/run_task.py"


rule trajectory_accuracy:
    input: DOP_SRC, f"{SRC}trajectory.py", **GEOMETRY_RESULTS, cal_do1="results/calibration/do1.json", scene="workflow/scenes/do1.yaml", schema=SCENE_SCHEMA,
    output: csv="results/bench/trajectory_accuracy.csv",
    params: methods=["DOP853", "RK45"], rtols=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11], repeat=5,
    log: "results/logs/trajectory_accuracy.log",
    script: "../scripts/run_task.py"


rule accuracy_trajectory:
    input: FIG_SRC, f"{SRC}figures/accuracy.py", csv="results/bench/trajectory_accuracy.csv",
    output: png="figures/accuracy_trajectory.png", csv="figures/accuracy_trajectory.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/accuracy_trajectory.log",
    script: "../scripts/run_task.py"


rule hjc_eos_paths:
    input: f"{SRC}hjc.py", f"{SRC}tasks.py", reference=config["reference"],
    output: csv="results/hjc/eos_paths.csv",
    params: mu_top=0.2, unload_from=[0.02, 0.05, 0.09, 0.15], unload_to=-0.01, steps=400,
    log: "results/logs/hjc_eos_paths.log",
    script: "../scripts/run_task.py"


rule fig10:
    input: FIG_SRC, f"{SRC}figures/fig10.py", paths="results/hjc/eos_paths.csv", reference=config["reference"],
    output: png="figures/fig10.png", csv="figures/fig10.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig10.log",
    script: "../scripts/run_task.py"
