# Nose geometry -> inference of unstated dimensions -> N* of the study's noses.

rule infer_fig4_design:
    input:
        f"{SRC}inference.py", f"{SRC}geometry.py", f"{SRC}nstar.py", f"{SRC}tasks.py",
    output:
        json="results/geometry/double_ogive_fig4.json",
        family="results/geometry/double_ogive_fig4_family.csv",
    params:
        cfg=config["fig4_design"],
    log:
        "results/logs/infer_fig4_design.log",
    script:
        "../scripts/run_task.py"


rule infer_table4_do1:
    input:
        f"{SRC}inference.py", f"{SRC}geometry.py", f"{SRC}nstar.py", f"{SRC}tasks.py",
        reference=config["reference"],
    output:
        json="results/geometry/double_ogive_table4.json",
        family="results/geometry/double_ogive_table4_family.csv",
    params:
        cfg=config["table4_do1"],
        projectile=config["projectile"],
    log:
        "results/logs/infer_table4_do1.log",
    script:
        "../scripts/run_task.py"


rule geometry:
    input:
        f"{SRC}geometry.py", f"{SRC}nstar.py", f"{SRC}inference.py", f"{SRC}tasks.py",
        fig4="results/geometry/double_ogive_fig4.json",
        do1="results/geometry/double_ogive_table4.json",
    output:
        noses="results/nstar/noses.csv",
        curves="results/nstar/curves.csv",
        bands="results/nstar/k_bands.csv",
    params:
        projectile=config["projectile"],
        table4=config["table4"],
        fig4=config["fig4_design"],
        points=config["figures"]["points_per_segment"],
    log:
        "results/logs/geometry.log",
    script:
        "../scripts/run_task.py"
