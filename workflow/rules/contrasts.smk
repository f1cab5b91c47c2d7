# The nose-shape contrasts (the paper's conclusions) gathered from every level.


# study: the nose contrasts of Table 3 under each of the cavity level's calibration variants
rule cavity_variant_contrasts:
    input: **task("tasks.contrasts"), variants="results/cavity/calibration_variants.csv",
    output: csv="figures/cavity_variant_contrasts.csv",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/cavity_variant_contrasts.tsv"
    log: "results/logs/cavity_variant_contrasts.log",
    script: "../scripts/run_task.py"


use rule cavity_variant_contrasts as nose_contrasts_data with:
    input: **task("tasks.contrasts"), **GEOMETRY_RESULTS, table3="figures/table3.csv", fig15="results/scenes/fig15.csv",
           cavity_fig15="results/scenes/cavity/fig15.csv",
           cal_do1="results/calibration/do1.json", **scene_input("workflow/scenes/fig15.yaml"), schema=SCENE_SCHEMA,
    output: csv="results/contrasts/nose_contrasts.csv",
    params: rtol=config["trajectory"]["rtol"],
    benchmark: "results/benchmarks/nose_contrasts_data.tsv"
    log: "results/logs/nose_contrasts_data.log",




# The verdict on the paper's nose contrasts, one table: every model's contrast +- its numerical uncertainty, the
# unstated inputs' spread apart, the paper's value (reads the studies' committed outputs; config verdict).
rule verdict:
    input: **task("tasks.contrasts"), table="figures/nose_contrasts_table.csv",
    output: csv="figures/verdict.csv", md="figures/verdict.md",
    params: sensitivity=study_input("figures/cavity_table3_sensitivity.csv"),
            eroding=study_input("figures/fe/contrast_extrapolation.csv"),
            chaos=chaos_study(),
            unstated=[study_input(f"figures/fe/unstated_{t}_v{v:g}.csv") for t in config["fe_realisations"]["unstated"]
                      for v in config["fe_realisations"]["velocities"]],
            provenance=config["verdict"]["provenance"], free_velocities=config["fe_realisations"]["velocities"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/verdict.tsv"
    log: "results/logs/verdict.log",
    script: "../scripts/run_task.py"
