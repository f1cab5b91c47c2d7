# The finite-element level. Every output lives under a mesh profile ({profile}: full or ci, config fe.profiles,
# or a convergence or band profile of fe_convergence.profiles, fe_band.bands); one job per shot (threads 2; 1 for
# the ci profile's small shots). FE_OUTPUTS are the paper's (rule all); the FE level's studies (mesh study,
# contrast convergence, bands, ensembles, rear face, moving windows, the erosion-free target's) are
# workflow/rules/fe_studies.smk. A figure is declared like fe_fig12, a table like fe_table3 (use rule ... with:); the
# FE runs each their own.

FE_SCENES = fe_scene_shots("workflow/scenes/fe", SCENE_SCHEMA)
# the scene whose job computes each shot: a shot that two scenes share with the same physics runs once (Fig 15's
# sweep takes Table 3's nine shots at 800-1200 m/s from Table 3's jobs)
FE_OWNER = fe_shot_owners("workflow/scenes/fe", SCENE_SCHEMA)
# the scenes whose shots need the DO1 calibration of their mesh (erosion_strain: calibrated)
FE_CALIBRATED = fe_calibrated_scenes("workflow/scenes/fe", SCENE_SCHEMA)
# the erosion-free scenes whose strength scale is calibrated on DO1 on their own target (fe.strength_scale: calibrated)
FE_STRENGTH_CALIBRATED = fe_calibrated_scenes("workflow/scenes/fe", SCENE_SCHEMA, "strength_scale")


def fe_shot_calibration(w):
    """The DO1 calibration a shot's scene needs: the erosion strain of the profile's mesh, the strength scale of the
    scene's erosion-free target, or none."""
    if w.scene in FE_CALIBRATED:
        return fe_calibration(w.profile)
    if w.scene in FE_STRENGTH_CALIBRATED:
        return f"results/fe/{w.profile}/{w.scene}/calibration_do1.json"
    return []


def fe_shots(scene):
    return [f"results/fe/{{profile}}/{FE_OWNER[(scene, nose, v)]}/{nose}_{v}.json" for nose, v in FE_SCENES[scene]]


def fe_histories(scene):
    return [f"results/fe/{{profile}}/{FE_OWNER[(scene, nose, v)]}/{nose}_{v}_histories.csv" for nose, v in FE_SCENES[scene]]


def fe_unique_shots(*scenes):
    """The shot files of the scenes, each shot once."""
    return list(dict.fromkeys(path for scene in scenes for path in fe_shots(scene)))


rule calibrate_fe_do1:
    input: **task("tasks.fe"), do1="results/geometry/double_ogive_table4.json", reference=config["reference"],
    output: json="results/fe/{profile}/calibration_h{size}.json",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], shot=config["calibration"]["do1"],
            profile=lambda w: w.profile, size=lambda w: w.size,
    threads: 2
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/calibrate_fe_do1_{profile}_h{size}.tsv"
    log: "results/logs/calibrate_fe_do1_{profile}_h{size}.log",
    script: "../scripts/run_task.py"


# The strength scale of an erosion-free scene's target (fe.strength_scale: calibrated) making the DO1 depth the
# measured one, at one mesh (a calibration: its residual is written with it).
rule calibrate_fe_strength_do1:
    input: **task("tasks.fe"), **GEOMETRY_RESULTS, reference=config["reference"],
           **scene_input("workflow/scenes/fe/{scene}.yaml"), schema=SCENE_SCHEMA,
    output: json="results/fe/{profile}/{scene}/calibration_do1.json",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], shot=config["calibration"]["do1"],
            profile=lambda w: w.profile, bracket=config["fe_erosion_free"]["calibration"]["bracket"],
    wildcard_constraints: scene="|".join(sorted(FE_STRENGTH_CALIBRATED)) or "no_scene",
    threads: 2
    resources: mem_mb=2000, runtime=90
    benchmark: "results/benchmarks/calibrate_fe_strength_do1_{profile}_{scene}.tsv"
    log: "results/logs/calibrate_fe_strength_do1_{profile}_{scene}.log",
    script: "../scripts/run_task.py"


rule fe_shot:
    input: **task("tasks.fe"), **GEOMETRY_RESULTS, reference=config["reference"],
           cal=fe_shot_calibration, **scene_input("workflow/scenes/fe/{scene}.yaml"), schema=SCENE_SCHEMA,
    output: json="results/fe/{profile}/{scene}/{nose}_{velocity}.json",
            histories="results/fe/{profile}/{scene}/{nose}_{velocity}_histories.csv",
            fields="results/fe/{profile}/{scene}/{nose}_{velocity}_fields.csv",
            audit="results/fe/{profile}/{scene}/{nose}_{velocity}_audit.csv",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], profile=lambda w: w.profile, nose=lambda w: w.nose,
            velocity=lambda w: w.velocity, size=size_params("workflow/scenes/fe/{scene}.yaml", config),
    # the scenes' and noses' names exactly, so that the benchmark record's name (underscores between the
    # wildcards) names one job: accuracy_cost reads these records
    wildcard_constraints: scene="|".join(sorted(FE_SCENES, key=len, reverse=True)),
                          nose="|".join(sorted({n for s in FE_SCENES.values() for n, _ in s}, key=len, reverse=True)),
    # one thread: two shots side by side do more per hour than one shot on two threads (DO1 at the full mesh: 1.57
    # times as fast on two threads as on one, but two one-thread shots side by side each as fast as alone, 1.36 times
    # the throughput; workflow/benchmarks/fe_threads.py, figures/timing/fe_threads.csv); the result is bit-identical
    # on any thread count (tests/test_fe.py). `--set-threads fe_shot=2` speeds up a single shot.
    threads: 1
    resources: mem_mb=2000, runtime=30
    benchmark: "results/benchmarks/fe_shot_{profile}_{scene}_{nose}_{velocity}.tsv"
    log: "results/logs/fe_shot_{profile}_{scene}_{nose}_{velocity}.log",
    script: "../scripts/run_task.py"


def fe_out(name):
    return f"figures/fe/{{profile}}/{name}"


rule fe_table3:
    input: **task("tasks.fe_tables"), reference=config["reference"], shots=fe_shots("table3"),
           cal=lambda w: fe_calibration(w.profile), **scene_input("workflow/scenes/fe/table3.yaml"),
    output: csv=fe_out("table3.csv"), ratios=fe_out("table3_ratios.csv"),
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fe_table3_{profile}.tsv"
    log: "results/logs/fe_table3_{profile}.log",
    script: "../scripts/run_task.py"


# The calibration the fe level of the command line carries over at a profile's mesh, committed (it runs from a fresh
# clone).
use rule fe_table3 as fe_calibration_record with:
    input: **task("tasks.fe"), cal=lambda w: fe_calibration(w.profile),
    output: csv="figures/fe/{profile}/calibration_fe_do1.csv",
    resources: mem_mb=500, runtime=2
    benchmark: "results/benchmarks/fe_calibration_record_{profile}.tsv"
    log: "results/logs/fe_calibration_record_{profile}.log",


rule fe_fig12:
    input: **task("figures.fe_level"), reference=config["reference"], shot="results/fe/{profile}/do1/double_ogive_835.json",
           histories="results/fe/{profile}/do1/double_ogive_835_histories.csv",
    output: png=report(fe_out("fig12.png"), caption="../report/captions/fe_fig12.rst", category="Finite-element level"), csv=fe_out("fig12.csv"),
    params: dpi=config["figures"]["dpi"],
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fe_fig12_{profile}.tsv"
    log: "results/logs/fe_fig12_{profile}.log",
    script: "../scripts/run_task.py"


use rule fe_table3 as fe_meshes with:
    input: **task("tasks.fe"), do1="results/geometry/double_ogive_table4.json",
    output: csv="results/fe/{profile}/meshes.csv",
    params: cfg=lambda w: fe_cfg(w.profile), profile=lambda w: w.profile,
    benchmark: "results/benchmarks/fe_meshes_{profile}.tsv"
    log: "results/logs/fe_meshes_{profile}.log",


use rule fe_fig12 as fe_fig13 with:
    input: **task("figures.fe_level"), meshes="results/fe/{profile}/meshes.csv",
    output: png=report(fe_out("fig13.png"), caption="../report/captions/fe_fig13.rst", category="Finite-element level"), csv=fe_out("fig13.csv"),
    params: dpi=config["figures"]["dpi"], profile=lambda w: w.profile,
    benchmark: "results/benchmarks/fe_fig13_{profile}.tsv"
    log: "results/logs/fe_fig13_{profile}.log",


use rule fe_fig12 as fe_fig14 with:
    input: **task("figures.fe_level"), reference=config["reference"], shots=fe_shots("table3"), histories=fe_histories("table3"),
    output: png=report(fe_out("fig14.png"), caption="../report/captions/fe_fig14.rst", category="Finite-element level"), csv=fe_out("fig14.csv"), cutoff_png=report(fe_out("fig14_cutoff.png"), caption="../report/captions/fe_fig14_cutoff.rst", category="Finite-element level"),
            cutoff_csv=fe_out("fig14_cutoff.csv"),
    params: dpi=config["figures"]["dpi"],
    benchmark: "results/benchmarks/fe_fig14_{profile}.tsv"
    log: "results/logs/fe_fig14_{profile}.log",


use rule fe_fig12 as fe_fig15 with:
    input: **task("figures.fe_level"), reference=config["reference"], shots=fe_shots("fig15"),
    output: png=report(fe_out("fig15.png"), caption="../report/captions/fe_fig15.rst", category="Finite-element level"), csv=fe_out("fig15.csv"),
    params: dpi=config["figures"]["dpi"], limit=study_input("figures/fe/contrast_extrapolation_depths.csv"),
            profile=lambda w: w.profile,
    benchmark: "results/benchmarks/fe_fig15_{profile}.tsv"
    log: "results/logs/fe_fig15_{profile}.log",


use rule fe_fig12 as fe_do1_fields with:
    input: **task("figures.fe_level"), shot="results/fe/{profile}/do1/double_ogive_835.json",
           fields="results/fe/{profile}/do1/double_ogive_835_fields.csv",
    output: png=report(fe_out("do1_fields.png"), caption="../report/captions/fe_do1_fields.rst", category="Finite-element level"), csv=fe_out("do1_profile.csv"),
    params: dpi=config["figures"]["dpi"],
    benchmark: "results/benchmarks/fe_do1_fields_{profile}.tsv"
    log: "results/logs/fe_do1_fields_{profile}.log",


rule fe_nose_pressure:
    input: **task("tasks.fe"), **GEOMETRY_RESULTS, reference=config["reference"], cal=lambda w: fe_calibration(w.profile),
           **scene_input("workflow/scenes/fe/fig15.yaml"), schema=SCENE_SCHEMA,
    output: json="results/fe/{profile}/nose_pressure.json",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], profile=lambda w: w.profile,
            steel_yield=config["fe_checks"]["steel_yield_pa"],
    threads: 2
    resources: mem_mb=2000, runtime=10
    benchmark: "results/benchmarks/fe_nose_pressure_{profile}.tsv"
    log: "results/logs/fe_nose_pressure_{profile}.log",
    script: "../scripts/run_task.py"


rule fe_verification:
    input: **task("tasks.verification"),
    output: csv="figures/fe_verification.csv",
    # small problems, which a second thread hardly speeds: one thread, so that another job runs beside it
    threads: 1
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/fe_verification.tsv"
    log: "results/logs/fe_verification.log",
    script: "../scripts/run_task.py"


use rule fe_table3 as fe_summary with:
    input: **task("tasks.fe_tables"), shots=fe_unique_shots("table3", "fig15", "do1"),
           do1="results/fe/{profile}/do1/double_ogive_835.json", block="results/fe/{profile}/do1_block/double_ogive_835.json",
           cal=lambda w: fe_calibration(w.profile), pressure="results/fe/{profile}/nose_pressure.json",
    output: json=fe_out("summary.json"), timing="figures/timing/fe_do1_{profile}.json",
    params: profile=lambda w: w.profile,
    benchmark: "results/benchmarks/fe_summary_{profile}.tsv"
    log: "results/logs/fe_summary_{profile}.log",


FE_OUTPUTS = ["calibration_fe_do1.csv", "table3.csv", "table3_ratios.csv", "fig12.png", "fig12.csv", "fig13.png", "fig13.csv", "fig14.png",
              "fig14.csv", "fig14_cutoff.png", "fig14_cutoff.csv", "fig15.png", "fig15.csv", "do1_fields.png",
              "do1_profile.csv", "summary.json"]


use rule fe_table3 as fe_diff with:
    input: **task("tasks.fe_tables"), reference=config["reference"], table3=fe_out("table3.csv"),
           ratios=fe_out("table3_ratios.csv"), do1="results/fe/{profile}/do1/double_ogive_835.json",
           cal=lambda w: fe_calibration(w.profile),
    output: csv=fe_out("diff.csv"), summary=fe_out("diff_summary.md"),
    params: profile=lambda w: w.profile, limit=study_input("figures/fe/contrast_extrapolation.csv"),
    benchmark: "results/benchmarks/fe_diff_{profile}.tsv"
    log: "results/logs/fe_diff_{profile}.log",


FE_OUTPUTS += ["diff.csv", "diff_summary.md"]


use rule fe_fig12 as fe_contrasts with:
    input: **task("tasks.fe_tables"), shots=fe_shots("fig15"), reference=config["reference"],
    output: png=report(fe_out("contrasts.png"), caption="../report/captions/fe_contrasts.rst", category="Finite-element level"), csv=fe_out("contrasts.csv"),
    params: dpi=config["figures"]["dpi"],
    benchmark: "results/benchmarks/fe_contrasts_{profile}.tsv"
    log: "results/logs/fe_contrasts_{profile}.log",


FE_OUTPUTS += ["contrasts.png", "contrasts.csv"]
