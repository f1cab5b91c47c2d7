# The diff of every reproduced number against the paper, and the check that
# nothing drifted from the committed results beyond the tolerance of its precision.


rule diff:
    input:
        **task("tasks.reference"),
        reference=config["reference"],
        findings=config["findings"],
        noses="results/nstar/noses.csv",
        bands="results/nstar/k_bands.csv",
        table3="figures/table3.csv",
        fit_calc="results/calibration/table3_calc.json",
        cal_do1="results/calibration/do1.json",
        do1_scene="results/scenes/do1.csv",
        sec22="results/scenes/sec22_450kg.csv",
        shares="results/resistance/shares.csv",
        fig15="results/scenes/fig15.csv",
        cavity_table3="results/scenes/cavity/table3.csv",
        cavity_do1="results/scenes/cavity/do1.csv",
        cal_cavity="results/calibration/cavity_do1.json",
        contrasts="figures/nose_contrasts.csv",
        contrast_table="figures/nose_contrasts_table.csv",
        verdict="figures/verdict.csv",
    output: diff="figures/diff.csv", summary="figures/diff_summary.md",
    params: erosion_free=chaos_study(),
            erosion_free_calibrated=study_input("figures/fe/erosion_free/calibrated.csv"),
            # DO1 predicted with and without the scale effect, per level whose study has run (rule scale_validation)
            scale_do1={level: study_input(f"figures/scale/do1_{level}.csv") for level in ("analytic", "cavity", "fe")},
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/diff.tsv"
    log: "results/logs/diff.log",
    script: "../scripts/run_task.py"


# Every claim of the paper judged at every level, once (the report lays it out): at the FE profile built.
use rule diff as claims with:
    input: **task("tasks.reference"), reference=config["reference"], contrasts="figures/nose_contrasts_table.csv",
           diff="figures/diff.csv", fe_diff="figures/fe/{profile}/diff.csv",
           fe_calibration="figures/fe/{profile}/calibration_fe_do1.csv",
           cavity_calibration="figures/calibration_cavity_do1.csv", verdict="figures/verdict.csv",
    output: csv="figures/fe/{profile}/claims.csv",
    params: band=study_input("figures/fe/contrast_band.csv"),
            extrapolation=study_input("figures/fe/contrast_extrapolation.csv"),
            validation=lambda w: study_input(f"figures/fe/{w.profile}/validation_levels_summary.csv"),
    benchmark: "results/benchmarks/claims_{profile}.tsv"
    log: "results/logs/claims_{profile}.log",


use rule diff as reproduce_check with:
    input: **task("tasks.reference"), outputs=list(CHECK["outputs"]), diff="figures/diff.csv",
    output: report="results/check/reproduce_check.txt",
    params: check=CHECK,
    benchmark: "results/benchmarks/reproduce_check.tsv"
    log: "results/logs/reproduce_check.log",


# The studies' reproduction check (`make check-studies`): their committed outputs against a rebuild.
use rule diff as reproduce_check_studies with:
    input: **task("tasks.reference"), outputs=list(CHECK_STUDIES),
    output: report="results/check/reproduce_check_studies.txt",
    params: check={**CHECK, "outputs": CHECK_STUDIES},
    benchmark: "results/benchmarks/reproduce_check_studies.tsv"
    log: "results/logs/reproduce_check_studies.log",
