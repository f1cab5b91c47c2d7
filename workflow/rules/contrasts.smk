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


