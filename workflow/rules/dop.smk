# Resistance -> closed-form DOP, named calibrations and inferences, scenes.
SCENE_SCHEMA = "workflow/schemas/scene.schema.json"
DOP_SRC = [f"{SRC}resistance.py", f"{SRC}dop.py", f"{SRC}calibration.py", f"{SRC}scenes.py", f"{SRC}tasks.py",
           f"{SRC}geometry.py", f"{SRC}nstar.py"]
GEOMETRY_RESULTS = dict(do1="results/geometry/double_ogive_table4.json", fig4="results/geometry/double_ogive_fig4.json")


rule calibrate_do1:
    input:
        DOP_SRC, **GEOMETRY_RESULTS,
        scene="workflow/scenes/do1.yaml", schema=SCENE_SCHEMA, reference=config["reference"],
    output:
        json="results/calibration/do1.json",
    params:
        depth=config["calibration"]["do1"]["depth"],
        velocity=config["calibration"]["do1"]["velocity"],
    log:
        "results/logs/calibrate_do1.log",
    script:
        "../scripts/run_task.py"


rule calibrate_table3_calc:
    input:
        DOP_SRC, **GEOMETRY_RESULTS,
        cal_do1="results/calibration/do1.json",
        scene="workflow/scenes/table3.yaml", schema=SCENE_SCHEMA, reference=config["reference"],
    output:
        json="results/calibration/table3_calc.json",
    log:
        "results/logs/calibrate_table3_calc.log",
    script:
        "../scripts/run_task.py"


rule infer_diameter_450kg:
    input:
        DOP_SRC, **GEOMETRY_RESULTS,
        scene="workflow/scenes/sec22_450kg.yaml", schema=SCENE_SCHEMA, reference=config["reference"],
    output:
        json="results/geometry/diameter_450kg.json",
    params:
        nose=config["diameter_450kg"]["nose"],
        axes=config["diameter_450kg"]["axes"],
    log:
        "results/logs/infer_diameter_450kg.log",
    script:
        "../scripts/run_task.py"


rule scene:
    input:
        DOP_SRC, f"{SRC}trajectory.py", f"{SRC}resistance.py", **GEOMETRY_RESULTS,
        cal_do1="results/calibration/do1.json",
        cal_table3_calc="results/calibration/table3_calc.json",
        diameter="results/geometry/diameter_450kg.json",
        scene="workflow/scenes/{scene}.yaml", schema=SCENE_SCHEMA,
    output:
        dop="results/scenes/{scene}.csv",
        histories="results/scenes/{scene}_histories.csv",
    params:
        rtol=config["trajectory"]["rtol"],
    log:
        "results/logs/scene_{scene}.log",
    script:
        "../scripts/run_task.py"
