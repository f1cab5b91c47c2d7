# HJC -> cavity expansion -> cavity level of the simulation.
CAVITY_SRC = [f"{SRC}hjc.py", f"{SRC}cavity.py", f"{SRC}cavity_level.py", f"{SRC}trajectory.py", f"{SRC}resistance.py",
              f"{SRC}tasks.py"]


rule calibrate_cavity_do1:
    input: CAVITY_SRC, do1="results/geometry/double_ogive_table4.json", reference=config["reference"],
    output: json="results/calibration/cavity_do1.json",
    params: cfg=config["cavity"], depth=config["calibration"]["do1"]["depth"], velocity=config["calibration"]["do1"]["velocity"],
    log: "results/logs/calibrate_cavity_do1.log",
    script: "../scripts/run_task.py"


rule cavity_table:
    input: CAVITY_SRC, cal="results/calibration/cavity_do1.json", reference=config["reference"],
    output: csv="results/cavity/sigma_n.csv",
    params: cfg=config["cavity"], radius=config["projectile"]["radius"],
    log: "results/logs/cavity_table.log",
    script: "../scripts/run_task.py"


rule scene_cavity:
    input:
        CAVITY_SRC, DOP_SRC, **GEOMETRY_RESULTS,
        sigma="results/cavity/sigma_n.csv",
        cal="results/calibration/cavity_do1.json",
        reference=config["reference"],
        scene="workflow/scenes/cavity/{scene}.yaml", schema=SCENE_SCHEMA,
    output:
        dop="results/scenes/cavity/{scene}.csv",
        histories="results/scenes/cavity/{scene}_histories.csv",
    params:
        rtol=1.0e-7,
        cfg=config["cavity"],
    log:
        "results/logs/scene_cavity_{scene}.log",
    script:
        "../scripts/run_task.py"


rule cavity_ablation:
    input: CAVITY_SRC, do1="results/geometry/double_ogive_table4.json", cal="results/calibration/cavity_do1.json", reference=config["reference"],
    output: csv="figures/ablation_cavity.csv",
    params: cfg=config["cavity"],
    log: "results/logs/cavity_ablation.log",
    script: "../scripts/run_task.py"


rule fig12:
    input: FIG_SRC, f"{SRC}figures/fig12.py", histories="results/scenes/cavity/do1_histories.csv", reference=config["reference"],
    output: png="figures/fig12.png", csv="figures/fig12.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig12.log",
    script: "../scripts/run_task.py"


rule fig14:
    input: FIG_SRC, f"{SRC}figures/fig14.py", histories="results/scenes/cavity/table3_histories.csv",
    output: png="figures/fig14.png", csv="figures/fig14.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/fig14.log",
    script: "../scripts/run_task.py"


rule cavity_sigma_n:
    input: FIG_SRC, f"{SRC}figures/cavity_sigma.py", sigma="results/cavity/sigma_n.csv", cal_do1="results/calibration/do1.json",
    output: png="figures/cavity_sigma_n.png", csv="figures/cavity_sigma_n.csv",
    params: dpi=config["figures"]["dpi"], rho=config["cavity_plot"]["rho"], fc=config["cavity_plot"]["fc"],
    log: "results/logs/cavity_sigma_n.log",
    script: "../scripts/run_task.py"


rule cavity_accuracy:
    input: CAVITY_SRC, do1="results/geometry/double_ogive_table4.json", cal="results/calibration/cavity_do1.json", sigma="results/cavity/sigma_n.csv", reference=config["reference"],
    output: csv="results/bench/cavity_accuracy.csv",
    params: cfg=config["cavity"], velocity=800.0, zones=[50, 100, 200, 400], cfls=[0.8, 0.5, 0.25, 0.125],
            table_nodes=[5, 9, 17, 33, 65], table_span=[50.0, 2000.0], rtols=[1e-3, 1e-5, 1e-7, 1e-9, 1e-11],
    log: "results/logs/cavity_accuracy.log",
    script: "../scripts/run_task.py"


rule accuracy_cavity:
    input: FIG_SRC, f"{SRC}figures/accuracy.py", csv="results/bench/cavity_accuracy.csv",
    output: png="figures/accuracy_cavity.png", csv="figures/accuracy_cavity.csv",
    params: dpi=config["figures"]["dpi"],
    log: "results/logs/accuracy_cavity.log",
    script: "../scripts/run_task.py"


rule cavity_table3_sensitivity:
    input:
        CAVITY_SRC, DOP_SRC, **GEOMETRY_RESULTS,
        cal="results/calibration/cavity_do1.json",
        reference=config["reference"],
        scene="workflow/scenes/cavity/table3.yaml", schema=SCENE_SCHEMA,
    output: csv="results/cavity/table3_sensitivity.csv",
    params: cfg=config["cavity"],
            variants=[{"parameter": "strength_scale", "zones": z} for z in (50, 100, 200)]
                     + [{"parameter": "erosion_strain", "zones": 100}]
                     + [{"parameter": "strength_scale", "zones": 100, "friction": mu} for mu in (0.02, 0.05, 0.1)],
            depth=config["calibration"]["do1"]["depth"], velocity=config["calibration"]["do1"]["velocity"],
    log: "results/logs/cavity_table3_sensitivity.log",
    script: "../scripts/run_task.py"


rule cavity_table3_sensitivity_figure:
    input: FIG_SRC, f"{SRC}figures/cavity_sensitivity.py", csv="results/cavity/table3_sensitivity.csv",
    output: png="figures/cavity_table3_sensitivity.png", csv="figures/cavity_table3_sensitivity.csv",
    params: dpi=config["figures"]["dpi"], goal_pct=7.5,
    log: "results/logs/cavity_table3_sensitivity_figure.log",
    script: "../scripts/run_task.py"


rule do1_family_sensitivity:
    input: CAVITY_SRC, family="results/geometry/double_ogive_table4_family.csv", sigma="results/cavity/sigma_n.csv",
    output: csv="figures/do1_family_sensitivity.csv",
    params: velocities=[500.0, 835.0, 1200.0], mass=81.1, effects=["crater", "cavity"],
    log: "results/logs/do1_family_sensitivity.log",
    script: "../scripts/run_task.py"
