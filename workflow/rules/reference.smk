# The diff of every reproduced number against the paper, and the check that
# nothing drifted from the committed results.

rule diff:
    input:
        f"{SRC}reference.py", f"{SRC}tasks.py",
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
        sensitivity="figures/cavity_table3_sensitivity.csv",
    output:
        diff="figures/diff.csv",
        summary="figures/diff_summary.md",
    log:
        "results/logs/diff.log",
    script:
        "../scripts/run_task.py"


rule reproduce_check:
    input:
        csvs=expand("figures/{f}.csv", f=FIGURES + TABLES + ["validation", "do1_family_sensitivity", "cavity_table3_sensitivity"]),
        diff="figures/diff.csv",
    output:
        report="results/check/reproduce_check.txt",
    params:
        rtol=config["check"]["rtol"],
        atol=config["check"]["atol"],
    log:
        "results/logs/reproduce_check.log",
    script:
        "../scripts/run_task.py"
