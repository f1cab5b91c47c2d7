# One rule per figure or table of the paper (and per study figure), named after it and after its module.
# accuracy_* plot against wall time: their PNG and timings live under figures/timing/.


rule fig01:
    input: **task("figures.fig01"), shares="results/resistance/shares.csv",
    output: png="figures/fig01.png", csv="figures/fig01.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig01.tsv"
    log: "results/logs/fig01.log",
    script: "../scripts/run_task.py"


rule fig03:
    input: **task("figures.fig03"), curves="results/nstar/curves.csv", bands="results/nstar/k_bands.csv", reference=config["reference"],
    output: png="figures/fig03.png", csv="figures/fig03.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig03.tsv"
    log: "results/logs/fig03.log",
    script: "../scripts/run_task.py"


rule fig04:
    input: **task("figures.fig04"), curves="results/nstar/curves.csv", fig4="results/geometry/double_ogive_fig4.json",
    output: png="figures/fig04.png", csv="figures/fig04.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig04.tsv"
    log: "results/logs/fig04.log",
    script: "../scripts/run_task.py"


rule fig05:
    input: **task("figures.fig05"), curves="results/nstar/curves.csv",
    output: png="figures/fig05.png", csv="figures/fig05.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig05.tsv"
    log: "results/logs/fig05.log",
    script: "../scripts/run_task.py"


rule fig06:
    input: **task("figures.fig06"), do1="results/geometry/double_ogive_table4.json",
    output: png="figures/fig06.png", csv="figures/fig06.csv",
    params: dpi=config["figures"]["dpi"], points=config["figures"]["points_per_segment"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig06.tsv"
    log: "results/logs/fig06.log",
    script: "../scripts/run_task.py"


rule fig07:
    input: **task("figures.fig07"), noses="results/nstar/noses.csv",
    output: png="figures/fig07.png", csv="figures/fig07.csv",
    params: dpi=config["figures"]["dpi"], points=config["figures"]["points_per_segment"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig07.tsv"
    log: "results/logs/fig07.log",
    script: "../scripts/run_task.py"


rule fig08:
    input: **task("figures.fig08"), histories="results/scenes/sec22_450kg_histories.csv", dop="results/scenes/sec22_450kg.csv", diameter="results/geometry/diameter_450kg.json",
    output: png="figures/fig08.png", csv="figures/fig08.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig08.tsv"
    log: "results/logs/fig08.log",
    script: "../scripts/run_task.py"


rule fig09:
    input: **task("figures.fig09"), histories="results/scenes/sec22_450kg_histories.csv", dop="results/scenes/sec22_450kg.csv", diameter="results/geometry/diameter_450kg.json", reference=config["reference"],
    output: png="figures/fig09.png", csv="figures/fig09.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig09.tsv"
    log: "results/logs/fig09.log",
    script: "../scripts/run_task.py"


rule fig10:
    input: **task("figures.fig10"), paths="results/hjc/eos_paths.csv", reference=config["reference"],
    output: png="figures/fig10.png", csv="figures/fig10.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig10.tsv"
    log: "results/logs/fig10.log",
    script: "../scripts/run_task.py"


rule fig12:
    input: **task("figures.fig12"), histories="results/scenes/cavity/do1_histories.csv", reference=config["reference"],
    output: png="figures/fig12.png", csv="figures/fig12.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig12.tsv"
    log: "results/logs/fig12.log",
    script: "../scripts/run_task.py"


rule fig14:
    input: **task("figures.fig14"), histories="results/scenes/cavity/table3_histories.csv", reference=config["reference"],
    output: png="figures/fig14.png", csv="figures/fig14.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig14.tsv"
    log: "results/logs/fig14.log",
    script: "../scripts/run_task.py"


rule fig15:
    input: **task("figures.fig15"), dop="results/scenes/fig15.csv", cavity="results/scenes/cavity/fig15.csv", reference=config["reference"],
    output: png="figures/fig15.png", csv="figures/fig15.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig15.tsv"
    log: "results/logs/fig15.log",
    script: "../scripts/run_task.py"


rule fig16:
    input: **task("figures.fig16"), curves="results/nstar/curves.csv", noses="results/nstar/noses.csv", reference=config["reference"],
    output: png="figures/fig16.png", csv="figures/fig16.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fig16.tsv"
    log: "results/logs/fig16.log",
    script: "../scripts/run_task.py"


rule table1:
    input: **task("figures.table1"), reference=config["reference"],
    output: csv="figures/table1.csv",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/table1.tsv"
    log: "results/logs/table1.log",
    script: "../scripts/run_task.py"


rule table2:
    input: **task("figures.table2"), reference=config["reference"],
    output: csv="figures/table2.csv",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/table2.tsv"
    log: "results/logs/table2.log",
    script: "../scripts/run_task.py"


rule table3:
    input: **task("figures.table3"), analytic="results/scenes/table3.csv", stated="results/scenes/table3_stated.csv", fit="results/calibration/table3_calc.json", cavity="results/scenes/cavity/table3.csv", reference=config["reference"],
    output: csv="figures/table3.csv",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/table3.tsv"
    log: "results/logs/table3.log",
    script: "../scripts/run_task.py"


rule table4:
    input: **task("figures.table4"), noses="results/nstar/noses.csv", reference=config["reference"],
    output: csv="figures/table4.csv",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/table4.tsv"
    log: "results/logs/table4.log",
    script: "../scripts/run_task.py"


rule validation:
    input: **task("figures.validation"), predictions="results/validation/predictions.csv",
    output: png="figures/validation.png", csv="figures/validation.csv",
    params: dpi=config["figures"]["dpi"], law=config["validation"]["strength_law"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/validation.tsv"
    log: "results/logs/validation.log",
    script: "../scripts/run_task.py"


rule cavity_sigma_n:
    input: **task("figures.cavity_sigma_n"), sigma="results/cavity/sigma_n.csv", cal_do1="results/calibration/do1.json",
           shots="results/scenes/cavity/table3.csv",
    output: png="figures/cavity_sigma_n.png", csv="figures/cavity_sigma_n.csv", static="figures/static_resistance.csv",
    params: dpi=config["figures"]["dpi"], rho=config["cavity_plot"]["rho"], fc=config["cavity_plot"]["fc"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/cavity_sigma_n.tsv"
    log: "results/logs/cavity_sigma_n.log",
    script: "../scripts/run_task.py"


rule cavity_table3_sensitivity:
    input: **task("figures.cavity_table3_sensitivity"), csv="results/cavity/calibration_variants.csv",
    output: png="figures/cavity_table3_sensitivity.png", csv="figures/cavity_table3_sensitivity.csv",
    params: dpi=config["figures"]["dpi"], goal_pct=STUDIES["cavity_calibration_variants"]["goal_pct"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/cavity_table3_sensitivity.tsv"
    log: "results/logs/cavity_table3_sensitivity.log",
    script: "../scripts/run_task.py"


rule accuracy_trajectory:
    input: **task("figures.accuracy_trajectory"), csv="results/studies/trajectory_tolerance.csv",
    output: png="figures/timing/accuracy_trajectory.png", csv="figures/accuracy_trajectory.csv", timing="figures/timing/accuracy_trajectory.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/accuracy_trajectory.tsv"
    log: "results/logs/accuracy_trajectory.log",
    script: "../scripts/run_task.py"


rule accuracy_cavity:
    input: **task("figures.accuracy_cavity"), csv="results/studies/cavity_solver.csv",
    output: png="figures/timing/accuracy_cavity.png", csv="figures/accuracy_cavity.csv", timing="figures/timing/accuracy_cavity.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/accuracy_cavity.tsv"
    log: "results/logs/accuracy_cavity.log",
    script: "../scripts/run_task.py"


rule nose_contrasts:
    input: **task("figures.nose_contrasts"), csv="results/contrasts/nose_contrasts.csv", reference=config["reference"],
    output: png="figures/nose_contrasts.png", csv="figures/nose_contrasts.csv", table="figures/nose_contrasts_table.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/nose_contrasts.tsv"
    log: "results/logs/nose_contrasts.log",
    script: "../scripts/run_task.py"
