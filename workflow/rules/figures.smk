# One rule per figure or table of the paper (and per study figure), named after it and after its module.
# The paper's figures and tables are one table (PAPER_FIGURES, PAPER_TABLES) and one loop; the study figures share
# accuracy_trajectory's declaration (use rule). accuracy_* plot against wall time: their PNG and timings live under
# figures/timing/.


# The paper's figures and tables, one rule each named after it and its module (figures.{name}): name -> the
# results it reads. A figure writes figures/{name}.png and the CSV it drew, a table its CSV.
PAPER_FIGURES = {
    "fig01": dict(shares="results/resistance/shares.csv"),
    "fig03": dict(curves="results/nstar/curves.csv", bands="results/nstar/k_bands.csv",
                  reference=config["reference"]),
    "fig04": dict(curves="results/nstar/curves.csv", fig4="results/geometry/double_ogive_fig4.json"),
    "fig05": dict(curves="results/nstar/curves.csv"),
    "fig06": dict(do1="results/geometry/double_ogive_table4.json"),
    "fig07": dict(noses="results/nstar/noses.csv"),
    "fig08": dict(histories="results/scenes/sec22_450kg_histories.csv", dop="results/scenes/sec22_450kg.csv",
                  diameter="results/geometry/diameter_450kg.json"),
    "fig09": dict(histories="results/scenes/sec22_450kg_histories.csv", dop="results/scenes/sec22_450kg.csv",
                  diameter="results/geometry/diameter_450kg.json", reference=config["reference"]),
    "fig10": dict(paths="results/hjc/eos_paths.csv", reference=config["reference"]),
    "fig12": dict(histories="results/scenes/cavity/do1_histories.csv", reference=config["reference"]),
    "fig14": dict(histories="results/scenes/cavity/table3_histories.csv", reference=config["reference"]),
    "fig15": dict(dop="results/scenes/fig15.csv", cavity="results/scenes/cavity/fig15.csv",
                  reference=config["reference"]),
    "fig16": dict(curves="results/nstar/curves.csv", noses="results/nstar/noses.csv", reference=config["reference"]),
}
PAPER_TABLES = {
    "table1": dict(reference=config["reference"]),
    "table2": dict(reference=config["reference"]),
    "table3": dict(analytic="results/scenes/table3.csv", stated="results/scenes/table3_stated.csv",
                   fit="results/calibration/table3_calc.json", cavity="results/scenes/cavity/table3.csv",
                   reference=config["reference"]),
    "table4": dict(noses="results/nstar/noses.csv", reference=config["reference"]),
}
# a paper figure's params beyond its dpi
PAPER_PARAMS = {name: dict(points=config["figures"]["points_per_segment"]) for name in ("fig06", "fig07")}
FIGURES = [*PAPER_FIGURES, "validation", "cavity_sigma_n", "nose_contrasts", "hjc_scaling"]  # the figures of rule all
TABLES = list(PAPER_TABLES)


def paper_outputs(name):
    """A paper figure's PNG (in the report) and CSV, or a table's CSV."""
    if name in PAPER_TABLES:
        return dict(csv=f"figures/{name}.csv")
    return dict(png=report(f"figures/{name}.png", caption=f"../report/captions/{name}.rst", category="Paper figures"),
                csv=f"figures/{name}.csv")


def paper_params(name):
    """A paper figure's dpi and PAPER_PARAMS; a table has none."""
    return {} if name in PAPER_TABLES else dict(dpi=config["figures"]["dpi"], **PAPER_PARAMS.get(name, {}))


for name, inputs in {**PAPER_FIGURES, **PAPER_TABLES}.items():
    rule:
        name: name
        input: **task(f"figures.{name}"), **inputs,
        output: **paper_outputs(name),
        params: **paper_params(name),
        threads: 1
        resources: mem_mb=1000, runtime=5
        benchmark: f"results/benchmarks/{name}.tsv"
        log: f"results/logs/{name}.log",
        script: "../scripts/run_task.py"


rule accuracy_trajectory:
    input: **task("figures.accuracy_trajectory"), csv="results/studies/trajectory_tolerance.csv",
    output: png=report("figures/timing/accuracy_trajectory.png", caption="../report/captions/accuracy_trajectory.rst", category="Timing (machine-dependent)"), csv="figures/accuracy_trajectory.csv", timing="figures/timing/accuracy_trajectory.csv",
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/accuracy_trajectory.tsv"
    log: "results/logs/accuracy_trajectory.log",
    script: "../scripts/run_task.py"


use rule accuracy_trajectory as validation with:
    input: **task("tasks.analytic"), predictions="results/validation/predictions.csv",
    output: png=report("figures/validation.png", caption="../report/captions/validation.rst", category="Validation"), csv="figures/validation.csv",
    params: dpi=config["figures"]["dpi"], law=config["validation"]["strength_law"],
    benchmark: "results/benchmarks/validation.tsv"
    log: "results/logs/validation.log",


use rule accuracy_trajectory as cavity_sigma_n with:
    input: **task("figures.cavity_sigma_n"), sigma="results/cavity/sigma_n.csv", cal_do1="results/calibration/do1.json",
           shots="results/scenes/cavity/table3.csv",
    output: png=report("figures/cavity_sigma_n.png", caption="../report/captions/cavity_sigma_n.rst", category="Cavity level"), csv="figures/cavity_sigma_n.csv", static="figures/static_resistance.csv",
    params: dpi=config["figures"]["dpi"], rho=config["cavity_plot"]["rho"], fc=config["cavity_plot"]["fc"],
    benchmark: "results/benchmarks/cavity_sigma_n.tsv"
    log: "results/logs/cavity_sigma_n.log",


use rule accuracy_trajectory as cavity_table3_sensitivity with:
    input: **task("figures.cavity_table3_sensitivity"), csv="results/cavity/calibration_variants.csv",
    output: png=report("figures/cavity_table3_sensitivity.png", caption="../report/captions/cavity_table3_sensitivity.rst", category="Cavity level"), csv="figures/cavity_table3_sensitivity.csv",
    params: dpi=config["figures"]["dpi"], goal_pct=STUDIES["cavity_calibration_variants"]["goal_pct"],
    benchmark: "results/benchmarks/cavity_table3_sensitivity.tsv"
    log: "results/logs/cavity_table3_sensitivity.log",


use rule accuracy_trajectory as accuracy_cavity with:
    input: **task("figures.accuracy_cavity"), csv="results/studies/cavity_solver.csv",
    output: png=report("figures/timing/accuracy_cavity.png", caption="../report/captions/accuracy_cavity.rst", category="Timing (machine-dependent)"), csv="figures/accuracy_cavity.csv", timing="figures/timing/accuracy_cavity.csv",
    params: dpi=config["figures"]["dpi"],
    benchmark: "results/benchmarks/accuracy_cavity.tsv"
    log: "results/logs/accuracy_cavity.log",


use rule accuracy_trajectory as nose_contrasts with:
    input: **task("figures.nose_contrasts"), csv="results/contrasts/nose_contrasts.csv", reference=config["reference"],
    output: png=report("figures/nose_contrasts.png", caption="../report/captions/nose_contrasts.rst", category="Conclusions"), csv="figures/nose_contrasts.csv", table="figures/nose_contrasts_table.csv",
    params: dpi=config["figures"]["dpi"],
            band=study_input("figures/fe/contrast_band.csv"), limit=study_input("figures/fe/contrast_extrapolation.csv"),
            free=chaos_study(),
    benchmark: "results/benchmarks/nose_contrasts.tsv"
    log: "results/logs/nose_contrasts.log",


# Every level on the development shots (users' shots at every level, levels.py): nothing fitted to them; the
# cavity and fe levels carry their DO1 calibrations over, the fe level on the mesh profile's calibration.
rule validation_level:
    input: **task("tasks.levels"), shots=config["validation"]["shots"], reference=config["reference"],
           cal_cavity="results/calibration/cavity_do1.json",
    output: csv="results/validation/{level}.csv",
    params: cfg=cfg_slice("concrete", "cavity", "validation"), law=config["validation"]["strength_law"], level=lambda w: w.level,
    wildcard_constraints: level="trajectory|cavity",
    threads: 2
    resources: mem_mb=2000, runtime=20
    benchmark: "results/benchmarks/validation_level_{level}.tsv"
    log: "results/logs/validation_level_{level}.log",
    script: "../scripts/run_task.py"


# The fe level as users get it: the committed record of its DO1 failure strain (read as a study input, so that
# validating the level never recomputes the calibration, minutes of FE runs per trial at 8 across).
rule validation_fe:
    input: **task("tasks.levels"), shots=config["validation"]["shots"], reference=config["reference"],
    output: csv="results/validation/fe_{profile}.csv",
    params: cfg=lambda w: cfg_slice("concrete", "cavity", "validation", fe=fe_cfg(w.profile)), law=config["validation"]["strength_law"],
            profile=lambda w: w.profile, cal_fe=lambda w: study_input(f"figures/fe/{w.profile}/calibration_fe_do1.csv"),
    threads: 2
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/validation_fe_{profile}.tsv"
    log: "results/logs/validation_fe_{profile}.log",
    script: "../scripts/run_task.py"


# The cavity level's strength scale calibrated on the laboratory shots (a study, committed: the calibration users'
# shots take, and its out-of-sample validation): the protocol of validation.laboratory, each fold scored on the shots it
# held out.
rule calibrate_cavity_laboratory:
    input: **task("tasks.laboratory"), shots=config["validation"]["shots"], reference=config["reference"],
    output: csv="figures/calibration_cavity_laboratory.csv", predictions="figures/validation_cavity_laboratory.csv",
            grid="figures/calibration_cavity_laboratory_grid.csv", timing="figures/timing/calibration_cavity_laboratory.csv",
    params: cfg=cfg_slice("concrete", "cavity", "validation"), shots_path=config["validation"]["shots"],
    threads: 1
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/calibrate_cavity_laboratory.tsv"
    log: "results/logs/calibrate_cavity_laboratory.log",
    script: "../scripts/run_task.py"


# The fe level's failure strain at a mesh profile calibrated on the laboratory shots (a study), as the cavity level's,
# its grid in pieces (every shot at one failure strain of the grid, fs_VALUE.csv): a piece is a record, once
# committed it is read through the params, never rebuilt (delete it to recompute it), so a grid of hours runs over
# sessions.
FE_LAB_GRID = [f"{v:g}" for v in config["validation"]["laboratory"]["failure_strains"]]


LAB_PIECE_INPUTS = record_inputs("tasks.laboratory", "figures/fe/{profile}/laboratory_grid/fs_{value}.csv",
                                 data=lambda w: [config["validation"]["shots"], config["reference"]])


rule fe_laboratory_grid_value:
    input: **LAB_PIECE_INPUTS,
    output: csv=update("figures/fe/{profile}/laboratory_grid/fs_{value}.csv"),
    params: cfg=lambda w: cfg_slice("concrete", "cavity", "validation", fe=fe_cfg(w.profile)), profile=lambda w: w.profile,
            value=lambda w: float(w.value),
    wildcard_constraints: profile="full|ci", value="|".join(v.replace(".", r"\.") for v in FE_LAB_GRID),
    threads: 1   # the shots one after another on one thread: two pieces side by side do more per hour
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/fe_laboratory_grid_value_{profile}_{value}.tsv"
    log: "results/logs/fe_laboratory_grid_value_{profile}_{value}.log",
    script: "../scripts/run_task.py"


rule calibrate_fe_laboratory:
    input: **task("tasks.laboratory"), shots=config["validation"]["shots"], reference=config["reference"],
           grid=uncommitted([f"figures/fe/{{profile}}/laboratory_grid/fs_{v}.csv" for v in FE_LAB_GRID]),
    output: csv="figures/fe/{profile}/calibration_fe_laboratory.csv",
            predictions="figures/fe/{profile}/validation_fe_laboratory.csv",
            grid="figures/fe/{profile}/calibration_fe_laboratory_grid.csv",
            timing="figures/timing/calibration_fe_laboratory_{profile}.csv",
    params: cfg=lambda w: cfg_slice("concrete", "cavity", "validation", fe=fe_cfg(w.profile)),
            shots_path=config["validation"]["shots"], profile=lambda w: w.profile,
            grid=lambda w: [study_input(f"figures/fe/{w.profile}/laboratory_grid/fs_{v}.csv") for v in FE_LAB_GRID],
    wildcard_constraints: profile="full|ci",
    threads: 2
    resources: mem_mb=2000, runtime=180
    benchmark: "results/benchmarks/calibrate_fe_laboratory_{profile}.tsv"
    log: "results/logs/calibrate_fe_laboratory_{profile}.log",
    script: "../scripts/run_task.py"


# DO1 as a test of the levels calibrated on the laboratory shots (a study): its excess over each prediction (the fe
# level at the default mesh).
rule do1_test:
    input: **task("tasks.laboratory"), reference=config["reference"], do1="results/geometry/double_ogive_table4.json",
           laboratory="figures/calibration_cavity_laboratory.csv",
           fe_laboratory="figures/fe/full/calibration_fe_laboratory.csv",
    output: csv="figures/do1_test.csv",
    params: cfg=cfg_slice("concrete", "cavity", "validation", fe=fe_cfg("full")), shot=config["calibration"]["do1"],
    threads: 2
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/do1_test.tsv"
    log: "results/logs/do1_test.log",
    script: "../scripts/run_task.py"


# DO1 as a test of the fe level at the default mesh over realisations of the erosion chaos (a study,
# config do1_test_fe): each realisation one job, in the semi-infinite target and in the experiment's block.
DO1_TEST_FE = config["do1_test_fe"]


rule do1_test_fe_shot:
    input: **task("tasks.laboratory"), reference=config["reference"], do1="results/geometry/double_ogive_table4.json",
           laboratory="figures/calibration_cavity_laboratory.csv",
           fe_laboratory="figures/fe/full/calibration_fe_laboratory.csv",
    output: json="results/do1_test/fe_{target}_m{member}.json",
    params: cfg=cfg_slice("concrete", "cavity", "validation", fe=fe_cfg("full")), shot=config["calibration"]["do1"],
            target=lambda w: w.target, member=lambda w: w.member, velocity_step=DO1_TEST_FE["velocity_step"],
    wildcard_constraints: target="semi_infinite|block", member=r"\d+",
    threads: 1   # as fe_shot: two one-thread shots side by side do more per hour
    resources: mem_mb=2000, runtime=10
    benchmark: "results/benchmarks/do1_test_fe_shot_{target}_m{member}.tsv"
    log: "results/logs/do1_test_fe_shot_{target}_m{member}.log",
    script: "../scripts/run_task.py"


rule do1_test_fe:
    input: **task("tasks.laboratory"),
           shots=[f"results/do1_test/fe_{t}_m{k}.json" for t in DO1_TEST_FE["targets"] for k in range(DO1_TEST_FE["members"])],
    output: csv="figures/fe/do1_test.csv", members="figures/fe/do1_test_members.csv",
    params: confidence=DO1_TEST_FE["confidence"], targets=DO1_TEST_FE["targets"],
    threads: 1
    resources: mem_mb=500, runtime=2
    benchmark: "results/benchmarks/do1_test_fe.tsv"
    log: "results/logs/do1_test_fe.log",
    script: "../scripts/run_task.py"


use rule accuracy_trajectory as validation_levels with:
    input: **task("tasks.levels"), analytic="results/validation/predictions.csv",
           trajectory="results/validation/trajectory.csv", cavity="results/validation/cavity.csv",
           fe="results/validation/fe_{profile}.csv", laboratory="figures/validation_cavity_laboratory.csv",
           fe_laboratory="figures/fe/{profile}/validation_fe_laboratory.csv",
    output: png=report("figures/fe/{profile}/validation_levels.png", caption="../report/captions/fe_validation_levels.rst", category="Users' shots"), csv="figures/fe/{profile}/validation_levels.csv",
            summary="figures/fe/{profile}/validation_levels_summary.csv",
            timing="figures/timing/validation_levels_{profile}.csv",
    params: dpi=config["figures"]["dpi"], law=config["validation"]["strength_law"], profile=lambda w: w.profile,
    benchmark: "results/benchmarks/validation_levels_{profile}.tsv"
    log: "results/logs/validation_levels_{profile}.log",


# Each level's error on a contrast between two noses, on the development shots' measured nose pairs (a study: it
# reads validation_levels' committed predictions).
rule validation_nose_pairs:
    input: **task("tasks.levels"), shots="figures/fe/{profile}/validation_levels.csv",
           summary="figures/fe/{profile}/validation_levels_summary.csv",
    output: csv="figures/fe/{profile}/validation_nose_pairs.csv",
            summary="figures/fe/{profile}/validation_nose_pairs_summary.csv",
    wildcard_constraints: profile="full|ci",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/validation_nose_pairs_{profile}.tsv"
    log: "results/logs/validation_nose_pairs_{profile}.log",
    script: "../scripts/run_task.py"


rule hjc_scaling:
    input: **task("tasks.levels"), shots=config["validation"]["shots"],
           reference=config["reference"], sets="workflow/data/hjc_sets.csv",
    output: csv="figures/hjc_scaling.csv", criteria="figures/hjc_scaling_criteria.csv",
            png=report("figures/hjc_scaling.png", caption="../report/captions/hjc_scaling.rst", category="Users' shots"),
    params: cfg=cfg_slice("concrete"), dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/hjc_scaling.tsv"
    log: "results/logs/hjc_scaling.log",
    script: "../scripts/run_task.py"


# Accuracy against cost over the ladder (full builds: the FE meshes of the convergence profiles).
ACCURACY_PROFILES = ["ci", "full", *CONVERGENCE_PROFILES]


rule accuracy_cost:
    input: **task("tasks.levels"), reference=config["reference"], table3="figures/table3.csv",
           cal_do1="results/calibration/do1.json", do1=GEOMETRY_RESULTS["do1"],
           trajectory="figures/accuracy_trajectory.csv", trajectory_timing="figures/timing/accuracy_trajectory.csv",
           cal_cavity="results/calibration/cavity_do1.json", cavity_study="figures/accuracy_cavity.csv",
           cavity_study_timing="figures/timing/accuracy_cavity.csv",
           fe_tables=expand("figures/fe/{profile}/table3.csv", profile=ACCURACY_PROFILES),
           fe_calibrations=[fe_calibration(p) for p in ACCURACY_PROFILES],
           fe_benchmarks=[f"results/benchmarks/fe_shot_{p}_table3_{nose}_{v}.tsv" for p in ACCURACY_PROFILES
                          for nose, v in FE_SCENES["table3"]],
    output: csv="figures/accuracy_cost.csv", timing="figures/timing/accuracy_cost.csv",
    params: cfg=cfg_slice("concrete", "cavity"), fe_profiles=ACCURACY_PROFILES,
    threads: 2
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/accuracy_cost.tsv"
    log: "results/logs/accuracy_cost.log",
    script: "../scripts/run_task.py"


use rule accuracy_trajectory as accuracy_prediction with:
    input: **task("tasks.accuracy"), timing="figures/timing/accuracy_cost.csv", table3="figures/table3.csv",
           contrasts="figures/nose_contrasts_table.csv",
           fe_tables=expand("figures/fe/{profile}/table3.csv", profile=ACCURACY_PROFILES),
           fe_ratios=expand("figures/fe/{profile}/table3_ratios.csv", profile=ACCURACY_PROFILES),
           validation=expand("figures/fe/{profile}/validation_levels_summary.csv", profile=["full", "ci"]),
    output: csv="figures/accuracy_prediction.csv",
            png=report("figures/timing/accuracy_cost.png", caption="../report/captions/accuracy_cost.rst", category="Timing (machine-dependent)"),
    params: dpi=config["figures"]["dpi"], fe_profiles=ACCURACY_PROFILES, validation_profiles=["full", "ci"],
    benchmark: "results/benchmarks/accuracy_prediction.tsv"
    log: "results/logs/accuracy_prediction.log",


# The sweep target: `snakemake -c2 sweep` (not part of `all`).
SWEEP = config.get("sweep", {})
SWEEP_RUNS = [(lv, n) for lv, sizes in SWEEP.get("sizes", {}).items() for n in sizes]


rule sweep_level:
    input: **task("tasks.levels"), reference=config["reference"],
           cal_cavity="results/calibration/cavity_do1.json", cal_fe=fe_calibration(SWEEP.get("fe_profile", "ci")),
    output: csv="results/sweep/{level}_n{n}.csv",
    params: cfg=cfg_slice("concrete", "cavity", "validation", "fe", "sweep"), level=lambda w: w.level, n=lambda w: w.n,
    wildcard_constraints: level="|".join(LEVELS), n=r"[0-9]+",
    threads: 2
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/sweep_level_{level}_n{n}.tsv"
    log: "results/logs/sweep_{level}_n{n}.log",
    script: "../scripts/run_task.py"


use rule accuracy_trajectory as sweep_figures with:
    input: **task("figures.sweep"), csvs=[f"results/sweep/{lv}_n{n}.csv" for lv, n in SWEEP_RUNS],
           benchmarks=[f"results/benchmarks/sweep_level_{lv}_n{n}.tsv" for lv, n in SWEEP_RUNS],
    output: png=report("figures/sweep/depth.png", caption="../report/captions/sweep_depth.rst", category="Users' shots"), csv="figures/sweep/depth.csv", cost_png=report("figures/timing/sweep_cost.png", caption="../report/captions/sweep_cost.rst", category="Timing (machine-dependent)"),
            cost_csv="figures/timing/sweep_cost.csv",
    params: dpi=config["figures"]["dpi"], levels=[lv for lv, _ in SWEEP_RUNS], sizes=[n for _, n in SWEEP_RUNS],
            law=config["validation"]["strength_law"],
    benchmark: "results/benchmarks/sweep_figures.tsv"
    log: "results/logs/sweep_figures.log",


rule sweep:
    input: rules.sweep_figures.output,


# A user's nose study (not part of `all`): `snakemake -c2 results/compare/NAME/compare.csv` runs the study
# workflow/compare/NAME.yaml (`python -m penetration compare --help`); `snakemake -c2 compare --config
# compare=NAME` the same. It reads the committed calibrations and nose-pair validation from disk.
rule compare_study:
    input: **task("tasks.compare"), study="workflow/compare/{name}.yaml",
    output: csv="results/compare/{name}/compare.csv", png="results/compare/{name}/compare.png",
            noses="results/compare/{name}/noses.csv", noses_png="results/compare/{name}/noses.png",
    params: profile="ci", workers=2,
    threads: 2
    resources: mem_mb=2000, runtime=30
    benchmark: "results/benchmarks/compare_study_{name}.tsv"
    log: "results/logs/compare_study_{name}.log",
    script: "../scripts/run_task.py"


rule compare:
    input: f"results/compare/{config.get('compare', 'nose_study')}/compare.csv",


# The scale effect at one level (a study): its one factor calibrated on the laboratory shots with each variant of
# config scale_effect (concrete/size.py) and without it, scored by leaving each series out, and DO1 predicted. The
# cavity level and the fe level at scale_effect.fe_profile read their grids in committed pieces, one per variant and
# grid value (the variant none: the laboratory calibration's own grid).
SCALE = config["scale_effect"]
SCALE_FE_PROFILE = SCALE["fe_profile"]
SCALE_PIECE = "figures/scale/fe_{profile}/{variant}/fs_{value}.csv"


def scale_fe_grid(variant):
    """The fe level's grid values with one variant, as written in the pieces' names (pipeline.config.scale_grid)."""
    return [f"{v:g}" for v in scale_grid(config, "fe", variant)]


def scale_fe_pieces(variant):
    """The committed grid pieces of the fe level's calibration with one variant (none: the laboratory calibration's
    own pieces)."""
    if variant == "none":
        return [f"figures/fe/{SCALE_FE_PROFILE}/laboratory_grid/fs_{v}.csv" for v in scale_fe_grid(variant)]
    return [SCALE_PIECE.format(profile=SCALE_FE_PROFILE, variant=variant, value=v) for v in scale_fe_grid(variant)]


SCALE_CAVITY_PIECE = "figures/scale/cavity/{variant}/s_{value}.csv"
CAVITY_LAB_GRID = [f"{v:g}" for v in config["validation"]["laboratory"]["strength_scales"]]


def scale_cavity_pieces(variant):
    """The committed grid pieces of the cavity level's calibration with one variant (none: the laboratory
    calibration's own grid and its timing record)."""
    if variant == "none":
        return {"table": "figures/calibration_cavity_laboratory_grid.csv",
                "timing": "figures/timing/calibration_cavity_laboratory.csv"}
    return [SCALE_CAVITY_PIECE.format(variant=variant, value=v) for v in CAVITY_LAB_GRID]


SCALE_GRIDS = {"fe": {name: scale_fe_pieces(name) for name in SCALE["levels"].get("fe", [])},
               "cavity": {name: scale_cavity_pieces(name) for name in SCALE["levels"].get("cavity", [])}}
SCALE_FE_VALUES = "|".join(v.replace(".", r"\.") for n in SCALE["levels"].get("fe", []) if n != "none"
                           for v in scale_fe_grid(n))
SCALE_CAVITY_VALUES = "|".join(v.replace(".", r"\.") for v in CAVITY_LAB_GRID)
SCALE_VARIANTS = "|".join(n for n in SCALE["variants"] if n != "none")


def scale_grid_missing(w):
    """A level's grid pieces not on disk yet (built first); none at the analytic level."""
    pieces = [p for ps in SCALE_GRIDS.get(w.level, {}).values() for p in (ps.values() if isinstance(ps, dict) else ps)]
    return uncommitted(pieces)(w)


def scale_cfg(w):
    """The config sections the study reads at a level (the fe level's mesh profile too)."""
    extra = {"fe": fe_cfg(SCALE_FE_PROFILE)} if w.level == "fe" else {}
    return cfg_slice("concrete", "cavity", "validation", "scale_effect", **extra)


rule scale_validation:
    input: **task("tasks.scale"), shots=config["validation"]["shots"], reference=config["reference"],
           do1="results/geometry/double_ogive_table4.json", grid=scale_grid_missing,
    output: csv="figures/scale/calibration_{level}.csv", predictions="figures/scale/predictions_{level}.csv",
            summary="figures/scale/validation_{level}.csv", do1="figures/scale/do1_{level}.csv",
    params: cfg=scale_cfg, shots_path=config["validation"]["shots"], shot=config["calibration"]["do1"],
            level=lambda w: w.level, grids=lambda w: SCALE_GRIDS.get(w.level, {}),
    wildcard_constraints: level="analytic|cavity|fe"
    threads: 2
    resources: mem_mb=2000, runtime=120
    benchmark: "results/benchmarks/scale_validation_{level}.tsv"
    log: "results/logs/scale_validation_{level}.log",
    script: "../scripts/run_task.py"


SCALE_PIECE_INPUTS = record_inputs("tasks.scale", SCALE_PIECE,
                                   data=lambda w: [config["validation"]["shots"], config["reference"]])


rule scale_fe_grid_value:
    input: **SCALE_PIECE_INPUTS,
    output: csv=update(SCALE_PIECE),
    params: cfg=lambda w: cfg_slice("concrete", "cavity", "validation", "scale_effect", fe=fe_cfg(w.profile)),
            profile=lambda w: w.profile, value=lambda w: float(w.value), variant=lambda w: w.variant,
    wildcard_constraints: profile="full|ci", value=SCALE_FE_VALUES, variant=SCALE_VARIANTS,
    threads: 1   # the shots one after another on one thread: two pieces side by side do more per hour
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/scale_fe_grid_value_{profile}_{variant}_{value}.tsv"
    log: "results/logs/scale_fe_grid_value_{profile}_{variant}_{value}.log",
    script: "../scripts/run_task.py"


SCALE_CAVITY_PIECE_INPUTS = record_inputs("tasks.scale", SCALE_CAVITY_PIECE,
                                          data=lambda w: [config["validation"]["shots"], config["reference"]])


rule scale_cavity_grid_value:
    input: **SCALE_CAVITY_PIECE_INPUTS,
    output: csv=update(SCALE_CAVITY_PIECE),
    params: cfg=lambda w: cfg_slice("concrete", "cavity", "validation", "scale_effect"), value=lambda w: float(w.value),
            variant=lambda w: w.variant,
    wildcard_constraints: value=SCALE_CAVITY_VALUES, variant=SCALE_VARIANTS,
    threads: 1   # the shots one after another on one thread: two pieces side by side do more per hour
    resources: mem_mb=2000, runtime=20
    benchmark: "results/benchmarks/scale_cavity_grid_value_{variant}_{value}.tsv"
    log: "results/logs/scale_cavity_grid_value_{variant}_{value}.log",
    script: "../scripts/run_task.py"


# Geometric similarity (a study): X/d against calibre at each level with the scale effect's variants, their factors
# calibrated by scale_validation, beside the empirical formulas' size laws.
SIMILARITY_LEVELS = list(SCALE["similarity"]["levels"])
# Table 3 at the analytic and cavity levels: the fe level's variants are calibrated at scale_effect.fe_profile's mesh,
# not one of Table 3's
TABLE3_SCALE_LEVELS = [level for level in SIMILARITY_LEVELS if level != "fe"]
SIMILARITY_CFG = cfg_slice("concrete", "cavity", "validation", "scale_effect",
                           **({"fe": fe_cfg(SCALE_FE_PROFILE)} if "fe" in SIMILARITY_LEVELS else {}))


rule scale_similarity:
    input: **task("tasks.scale"), reference=config["reference"],
           calibrations=[f"figures/scale/calibration_{level}.csv" for level in SIMILARITY_LEVELS],
    output: csv="figures/scale/similarity.csv", png="figures/scale/similarity.png",
    params: cfg=SIMILARITY_CFG, dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=2000, runtime=30
    benchmark: "results/benchmarks/scale_similarity.tsv"
    log: "results/logs/scale_similarity.log",
    script: "../scripts/run_task.py"


# Table 3 (all at 140 mm) at each level with the scale effect's variants (a study): the contrasts and their changes.
rule scale_table3:
    input: **task("tasks.scale"), **GEOMETRY_RESULTS, **scene_input("workflow/scenes/table3_stated.yaml"),
           schema=SCENE_SCHEMA, reference=config["reference"],
           calibrations=[f"figures/scale/calibration_{level}.csv" for level in TABLE3_SCALE_LEVELS],
    output: csv="figures/scale/table3.csv",
    params: cfg=cfg_slice("concrete", "cavity", "validation", "scale_effect"),
    threads: 1
    resources: mem_mb=2000, runtime=30
    benchmark: "results/benchmarks/scale_table3.tsv"
    log: "results/logs/scale_table3.log",
    script: "../scripts/run_task.py"


# How much calibre dependence DO1 asks of each level (a study, seconds): each level's factor fitted on each laboratory
# series alone beside its calibration on DO1 (the fe level's at the study's mesh), and the factor on the resistance that
# each mechanism of the scale effect gives at the series' and DO1's calibres and velocities.
rule scale_do1_gap:
    input: **task("tasks.scale"), shots=config["validation"]["shots"], reference=config["reference"],
           calibrations=[f"figures/scale/calibration_{level}.csv" for level in SCALE["levels"]],
           analytic="results/calibration/do1.json", cavity="results/calibration/cavity_do1.json",
           fe=f"figures/fe/{SCALE_FE_PROFILE}/calibration_fe_do1.csv",
    output: csv="figures/scale/do1_gap.csv",
    params: cfg=cfg_slice("validation", "scale_effect"), shot=config["calibration"]["do1"],
    threads: 1
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/scale_do1_gap.tsv"
    log: "results/logs/scale_do1_gap.log",
    script: "../scripts/run_task.py"
