# The finite-element level's studies (workflow/studies.yaml lists their outputs; `snakemake -c2 studies`): the mesh
# study, the contrasts' convergence, bands and extrapolation, the erosion-free target's grid study, quasi-static check,
# calibration and window, the ensembles, the rear face and the moving window. Rules of the shapes of fe.smk's fe_fig12
# and fe_table3 are declared with `use rule ... with:` (fe.smk is included first).

use rule fe_fig12 as fe_mesh_study with:
    input: **task("tasks.fe_studies"),
           calibrations=lambda w: [f"results/fe/{w.profile}/calibration_h{h}.json" for h in config["fe"]["profiles"][w.profile]["mesh_study_sizes"]],
    output: png=report("figures/timing/fe_mesh_study_{profile}.png", caption="../report/captions/fe_mesh_study.rst", category="Timing (machine-dependent)"), csv="figures/timing/fe_mesh_study_{profile}.csv",
    params: dpi=config["figures"]["dpi"],
    benchmark: "results/benchmarks/fe_mesh_study_{profile}.tsv"
    log: "results/logs/fe_mesh_study_{profile}.log",


use rule fe_fig12 as fe_contrast_convergence with:
    input: **task("tasks.fe_studies"), reference=config["reference"],
           ratios=expand("figures/fe/{profile}/table3_ratios.csv", profile=["ci", "full", *CONVERGENCE_PROFILES]),
           tables=expand("figures/fe/{profile}/table3.csv", profile=["ci", "full", *CONVERGENCE_PROFILES]),
           calibrations=[fe_calibration(p) for p in ("ci", "full", *CONVERGENCE_PROFILES)],
           ensemble="figures/fe/contrast_ensemble.csv",
    output: png=report("figures/fe/contrast_convergence.png", caption="../report/captions/contrast_convergence.rst", category="Finite-element level"), csv="figures/fe/contrast_convergence.csv",
    params: dpi=config["figures"]["dpi"],
    benchmark: "results/benchmarks/fe_contrast_convergence.tsv"
    log: "results/logs/fe_contrast_convergence.log",


# every band's meshes, centre first, band after band (params.bands: the centres and their numbers of meshes)
BAND_MESHES = [p for centre, band in BANDS.items() for p in (centre, *band)]


use rule fe_fig12 as fe_contrast_band with:
    input: **task("tasks.fe_studies"),
           ratios=expand("figures/fe/{profile}/table3_ratios.csv", profile=BAND_MESHES),
           tables=expand("figures/fe/{profile}/table3.csv", profile=BAND_MESHES),
           calibrations=[fe_calibration(p) for p in BAND_MESHES],
    output: png=report("figures/fe/contrast_band.png", caption="../report/captions/contrast_band.rst", category="Finite-element level"),
            csv="figures/fe/contrast_band.csv", depths="figures/fe/contrast_band_depths.csv",
            meshes="figures/fe/contrast_band_meshes.csv",
    params: dpi=config["figures"]["dpi"], confidence=config["fe_band"]["confidence"],
            bands=[(centre, 1 + len(band)) for centre, band in BANDS.items()],
    benchmark: "results/benchmarks/fe_contrast_band.tsv"
    log: "results/logs/fe_contrast_band.log",


use rule fe_fig12 as fe_contrast_extrapolation with:
    input: **task("tasks.fe_studies"), meshes="figures/fe/contrast_band_meshes.csv",
           singles="figures/fe/contrast_convergence.csv",
           tables=expand("figures/fe/{profile}/table3.csv", profile=BAND_MESHES),
    output: png=report("figures/fe/contrast_extrapolation.png", caption="../report/captions/contrast_extrapolation.rst", category="Finite-element level"),
            csv="figures/fe/contrast_extrapolation.csv", depths="figures/fe/contrast_extrapolation_depths.csv",
    params: dpi=config["figures"]["dpi"], confidence=config["fe_band"]["confidence"],
    benchmark: "results/benchmarks/fe_contrast_extrapolation.tsv"
    log: "results/logs/fe_contrast_extrapolation.log",


# The study in pieces: one committed record per mesh and scene (every shot's summary: six shots) and one of the
# eroding level's Table 3 shots at its default mesh (the per-shot time the study's is set against), each
# figures/fe/erosion_free/pieces/{profile}/{scene}.json. A piece is a record: once committed it is read, never rebuilt,
# so a study longer than a session resumes from its committed pieces on a fresh clone (delete a piece to recompute
# it). A missing piece runs its shots.
FREE_PIECES = {**{f"{p}/{scene}": [path.format(profile=p) for path in fe_shots(scene)]
                  for p in FREE_PROFILES for scene in config["fe_erosion_free"]["scenes"]},
               "full/table3": [path.format(profile="full") for path in fe_shots("table3")]}


FREE_PIECE_INPUTS = record_inputs("tasks.fe_erosion_free", "figures/fe/erosion_free/pieces/{piece}.json",
                                  shots=lambda w: FREE_PIECES[w.piece])


rule fe_erosion_free_piece:
    input: **FREE_PIECE_INPUTS,
    output: json=update("figures/fe/erosion_free/pieces/{piece}.json"),
    params: piece=lambda w: w.piece, expected=lambda w: len(FREE_PIECES[w.piece]),
    wildcard_constraints: piece="|".join(FREE_PIECES),
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fe_erosion_free_piece_{piece}.tsv"
    log: "results/logs/fe_erosion_free_piece_{piece}.log",
    script: "../scripts/run_task.py"


FREE_STUDY_PIECES = [f"figures/fe/erosion_free/pieces/{piece}.json" for piece in FREE_PIECES if piece != "full/table3"]
FREE_ERODING_PIECE = "figures/fe/erosion_free/pieces/full/table3.json"


use rule fe_fig12 as fe_erosion_free_convergence with:
    input: **task("tasks.fe_erosion_free"), reference=config["reference"],
           pieces=uncommitted(FREE_STUDY_PIECES), eroding=uncommitted([FREE_ERODING_PIECE]),
    output: png=report("figures/fe/erosion_free/convergence.png", caption="../report/captions/fe_erosion_free_convergence.rst", category="Finite-element level"),
            csv="figures/fe/erosion_free/convergence.csv", depths="figures/fe/erosion_free/convergence_shots.csv",
            holes="figures/fe/erosion_free/convergence_holes.csv", cost="figures/timing/fe_erosion_free_convergence.csv",
    params: dpi=config["figures"]["dpi"], across=config["fe_erosion_free"]["profiles"],
            goal_depth=config["fe_erosion_free"]["gci_goal_depth"], goal_contrast=config["fe_erosion_free"]["gci_goal_contrast"],
            eroding_across=config["fe"]["profiles"]["full"]["elements_across"],
            pieces=[study_input(p) for p in FREE_STUDY_PIECES], eroding=study_input(FREE_ERODING_PIECE),
    benchmark: "results/benchmarks/fe_erosion_free_convergence.tsv"
    log: "results/logs/fe_erosion_free_convergence.log",


# The erosion-free depths with one strength scale calibrated on DO1 (a study: the calibration and the scene's shots at
# the finest profile), beside the same shots with Table 1's HJC as stated and the paper's Table 3.
FREE_CAL = config["fe_erosion_free"]["calibration"]


rule fe_erosion_free_calibrated:
    input: **task("tasks.fe_erosion_free"), reference=config["reference"],
           cal=f"results/fe/{FREE_CAL['profile']}/{FREE_CAL['scene']}/calibration_do1.json",
           shots=[p.format(profile=FREE_CAL["profile"]) for p in fe_shots(FREE_CAL["scene"])],
           stated=[p.format(profile=FREE_CAL["profile"]) for p in fe_shots(config["fe_erosion_free"]["scenes"][-1])],
    output: csv="figures/fe/erosion_free/calibrated.csv", calibration="figures/fe/erosion_free/calibration.csv",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fe_erosion_free_calibrated.tsv"
    log: "results/logs/fe_erosion_free_calibrated.log",
    script: "../scripts/run_task.py"


# The semi-infinite target's radius (a study): shots of the erosion-free target at several radii (fe_target_radius).
TARGET_RADIUS = config["fe_target_radius"]


rule fe_target_radius:
    input: **task("tasks.fe_window"), **GEOMETRY_RESULTS, reference=config["reference"],
           **scene_input(f"workflow/scenes/fe/{TARGET_RADIUS['scene']}.yaml"), schema=SCENE_SCHEMA,
    output: csv="figures/fe/erosion_free/target_radius.csv",
    params: cfg=fe_cfg(TARGET_RADIUS["profile"]), hjc=config["concrete"], profile=TARGET_RADIUS["profile"],
            shots=TARGET_RADIUS["shots"], radii=TARGET_RADIUS["radii"],
    threads: 2
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/fe_target_radius.tsv"
    log: "results/logs/fe_target_radius.log",
    script: "../scripts/run_task.py"


# The moving window on the erosion-free target (a study): each shot of fe_erosion_free.window with the window and
# with the whole domain, several realisations each (the task of fe_window_study).
FREE_WINDOW = config["fe_erosion_free"]["window"]


rule fe_erosion_free_window:
    input: **task("tasks.fe_window"), **GEOMETRY_RESULTS, reference=config["reference"],
           **scene_input(f"workflow/scenes/fe/{FREE_WINDOW['scene']}.yaml"), schema=SCENE_SCHEMA,
    output: runs="figures/fe/erosion_free/window_{nose}_{velocity}.csv",
            summary="figures/fe/erosion_free/window_{nose}_{velocity}_summary.csv",
            timing="figures/timing/fe_erosion_free_window_{nose}_{velocity}.csv",
    params: cfg=fe_cfg(FREE_WINDOW["profile"]), hjc=config["concrete"], profile=FREE_WINDOW["profile"],
            nose=lambda w: w.nose, velocity=lambda w: w.velocity, members=FREE_WINDOW["members"],
            velocity_step=config["fe_window"]["velocity_step"], confidence=config["fe_window"]["confidence"],
            goal_pct=config["fe_window"]["goal_pct"],
    wildcard_constraints: nose="|".join(sorted({n for s in FE_SCENES.values() for n, _ in s}, key=len, reverse=True)),
    threads: 2
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/fe_erosion_free_window_{nose}_{velocity}.tsv"
    log: "results/logs/fe_erosion_free_window_{nose}_{velocity}.log",
    script: "../scripts/run_task.py"


# The quasi-static check of the erosion-free target (a study): a CRH 3 ogive driven at a low speed, each mesh and
# hole one job (fe.quasi_static); then its refinement against the cavity stresses.
QS = config["fe_erosion_free"]["quasi_static"]


rule fe_quasi_static_run:
    input: **task("tasks.fe_erosion_free"),
    output: json="results/fe/quasi_static/hole{hole}_across{across}.json",
    params: across=lambda w: w.across, hole=lambda w: w.hole, velocity=QS["velocity"], guide=QS["guide"],
    threads: 2
    resources: mem_mb=2000, runtime=20
    benchmark: "results/benchmarks/fe_quasi_static_run_hole{hole}_across{across}.tsv"
    log: "results/logs/fe_quasi_static_run_hole{hole}_across{across}.log",
    script: "../scripts/run_task.py"


rule fe_quasi_static:
    input: **task("tasks.fe_erosion_free"),
           runs=[f"results/fe/quasi_static/hole{h:g}_across{n:g}.json" for h in QS["holes"] for n in QS["across"]],
    output: csv="figures/fe/erosion_free/quasi_static.csv", runs="figures/fe/erosion_free/quasi_static_runs.csv",
    params: velocity=QS["velocity"], band=QS["band"],
    threads: 1
    resources: mem_mb=1000, runtime=10
    benchmark: "results/benchmarks/fe_quasi_static.tsv"
    log: "results/logs/fe_quasi_static.log",
    script: "../scripts/run_task.py"


def fe_ensemble_members(profile):
    """The JSONs of the Table 3 ensemble's members k >= 1 at a profile (member 0 is the profile's own Table 3 shot)."""
    n = config["fe_ensemble"]["members"]
    return [f"results/fe/{profile}/ensemble/{nose}_{v}_m{k}.json" for nose, v in FE_SCENES["table3"] for k in range(1, n + 1)]


# the rear-face study's chain of targets, from the semi-infinite target to the block, one change a step
REAR_FACE_SCENES = ("do1", "do1_depth54", "do1_depth54_free_bottom", "do1_block_absorbing_sides", "do1_block")


def fe_rear_face_members(profile):
    """The JSONs of the rear-face ensemble's members k >= 1 (member 0: the scenes' own shots)."""
    n = config["fe_rear_face"]["members"]
    return [f"results/fe/{profile}/rear_face/{scene}_m{k}.json" for scene in REAR_FACE_SCENES for k in range(1, n + 1)]


# The shots whose realisations of the erosion chaos the ensembles run, per family: name -> (scene, nose, velocity)
# (the Table 3 ensemble's velocity as its path spells it)
FE_REALISED = {"ensemble": {f"{nose}_{v}": ("table3", nose, f"{v}") for nose, v in FE_SCENES["table3"]},
               "rear_face": {scene: (scene, *FE_SCENES[scene][0]) for scene in REAR_FACE_SCENES}}


def realised(w):
    """(scene, nose, velocity) of a realisation's shot."""
    return FE_REALISED[w.family][w.shot]


rule fe_ensemble_shot:
    input: **task("tasks.fe"), **GEOMETRY_RESULTS, reference=config["reference"],
           cal=lambda w: fe_calibration(w.profile), **scene_input(lambda w: f"workflow/scenes/fe/{realised(w)[0]}.yaml"), schema=SCENE_SCHEMA,
    output: json="results/fe/{profile}/{family}/{shot}_m{member}.json",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], profile=lambda w: w.profile,
            nose=lambda w: realised(w)[1], velocity=lambda w: realised(w)[2],
            member=lambda w: w.member, velocity_step=config["fe_ensemble"]["velocity_step"],
    wildcard_constraints: family="|".join(FE_REALISED), member=r"\d+",
                          shot="|".join(sorted((s.replace(".", r"\.") for f in FE_REALISED.values() for s in f), key=len, reverse=True)),
    threads: 1   # as fe_shot: two one-thread shots side by side do more per hour
    resources: mem_mb=2000, runtime=lambda w: 30 if w.family == "ensemble" else 10
    benchmark: "results/benchmarks/fe_ensemble_shot_{family}_{profile}_{shot}_m{member}.tsv"
    log: "results/logs/fe_ensemble_shot_{family}_{profile}_{shot}_m{member}.log",
    script: "../scripts/run_task.py"


use rule fe_fig12 as fe_contrast_ensemble with:
    input: **task("tasks.fe_studies"), ratios="figures/fe/full/table3_ratios.csv", table="figures/fe/full/table3.csv",
           shots=[path.format(profile="full") for path in fe_shots("table3")], members=fe_ensemble_members("full"),
    output: png=report("figures/fe/contrast_ensemble.png", caption="../report/captions/contrast_ensemble.rst", category="Finite-element level"), csv="figures/fe/contrast_ensemble.csv",
            depths="figures/fe/contrast_ensemble_depths.csv",
    params: dpi=config["figures"]["dpi"], confidence=config["fe_ensemble"]["confidence"],
    benchmark: "results/benchmarks/fe_contrast_ensemble.tsv"
    log: "results/logs/fe_contrast_ensemble.log",


use rule fe_fig12 as fe_rear_face with:
    input: **task("tasks.fe_rear_face"),
           shots=[p.format(profile="full") for scene in REAR_FACE_SCENES for p in fe_shots(scene)],
           histories=[p.format(profile="full") for scene in REAR_FACE_SCENES for p in fe_histories(scene)],
           members=fe_rear_face_members("full"), cal=fe_calibration("full"),
    output: png=report("figures/fe/rear_face.png", caption="../report/captions/fe_rear_face.rst", category="Finite-element level"),
            csv="figures/fe/rear_face.csv", members="figures/fe/rear_face_members.csv",
            effects="figures/fe/rear_face_effects.csv",
    params: dpi=config["figures"]["dpi"], confidence=config["fe_ensemble"]["confidence"], chain=REAR_FACE_SCENES,
    benchmark: "results/benchmarks/fe_rear_face.tsv"
    log: "results/logs/fe_rear_face.log",


rule fe_window_study:
    input: **task("tasks.fe_window"), **GEOMETRY_RESULTS, reference=config["reference"],
           cal=lambda w: fe_calibration(w.profile), **scene_input("workflow/scenes/fe/do1.yaml"), schema=SCENE_SCHEMA,
    output: runs=fe_out("window.csv"), summary=fe_out("window_summary.csv"), timing="figures/timing/fe_window_{profile}.csv",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], profile=lambda w: w.profile,
            velocity=lambda w: FE_SCENES["do1"][0][1], **config["fe_window"],
    threads: 2
    resources: mem_mb=2000, runtime=lambda w: 20 if w.profile == "ci" else 60
    benchmark: "results/benchmarks/fe_window_study_{profile}.tsv"
    log: "results/logs/fe_window_study_{profile}.log",
    script: "../scripts/run_task.py"



# Realisations of the FE chaos (config fe_realisations): a scene's shot struck at v (1 + member velocity_step), member
# >= 1 (member 0 is the scene's own shot, rule fe_shot), and the committed pieces the studies read: one per cell (a
# scene at a profile), velocity and member, its noses' summaries.
REAL = config["fe_realisations"]
REAL_UNSTATED = REAL["unstated"]


rule fe_realisation:
    input: **task("tasks.fe"), **GEOMETRY_RESULTS, reference=config["reference"],
           cal=fe_shot_calibration, **scene_input("workflow/scenes/fe/{scene}.yaml"), schema=SCENE_SCHEMA,
    output: json="results/fe/{profile}/{scene}/{nose}_{velocity}_m{member}.json",
    params: cfg=lambda w: fe_cfg(w.profile), hjc=config["concrete"], profile=lambda w: w.profile, nose=lambda w: w.nose,
            velocity=lambda w: w.velocity, member=lambda w: w.member, velocity_step=REAL["velocity_step"],
    wildcard_constraints: scene="|".join(sorted(FE_SCENES, key=len, reverse=True)),
                          nose="|".join(sorted({n for s in FE_SCENES.values() for n, _ in s}, key=len, reverse=True)),
                          member=r"[1-9][0-9]*",
    threads: 1   # as fe_shot: two one-thread shots side by side do more per hour
    resources: mem_mb=2000, runtime=60
    benchmark: "results/benchmarks/fe_realisation_{profile}_{scene}_{nose}_{velocity}_m{member}.tsv"
    log: "results/logs/fe_realisation_{profile}_{scene}_{nose}_{velocity}_m{member}.log",
    script: "../scripts/run_task.py"


def realisation_shots(scene, profile, velocity, member):
    """The shot files of a piece: the scene's noses at one velocity, one member (0: the scene's own shots)."""
    tail = "" if int(member) == 0 else f"_m{int(member)}"
    return [f"results/fe/{profile}/{FE_OWNER[(scene, n, v)]}/{n}_{v}{tail}.json"
            for n, v in FE_SCENES[scene] if float(v) == float(velocity)]


REAL_PIECE = "figures/fe/realisations/{profile}/{scene}/v{velocity}_m{member}.json"


def real_pieces(scene, profiles):
    """The pieces of a scene at these profiles: every velocity of fe_realisations and every member."""
    return [REAL_PIECE.format(profile=p, scene=scene, velocity=f"{v:g}", member=k)
            for p in profiles for v in REAL["velocities"] for k in range(REAL["members"])]


REAL_PIECE_INPUTS = record_inputs("tasks.fe_chaos", REAL_PIECE,
                                  shots=lambda w: realisation_shots(w.scene, w.profile, w.velocity, w.member))


rule fe_realisation_piece:
    input: **REAL_PIECE_INPUTS,
    output: json=update(REAL_PIECE),
    params: piece=lambda w: f"{w.profile}/{w.scene}/v{w.velocity}_m{w.member}",
            expected=lambda w: len(realisation_shots(w.scene, w.profile, w.velocity, w.member)),
            member=lambda w: int(w.member), velocity_step=REAL["velocity_step"],
    wildcard_constraints: scene="|".join(sorted(FE_SCENES, key=len, reverse=True)), member=r"[0-9]+",
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fe_realisation_piece_{profile}_{scene}_v{velocity}_m{member}.tsv"
    log: "results/logs/fe_realisation_piece_{profile}_{scene}_v{velocity}_m{member}.log",
    script: "../scripts/run_task.py"


CHAOS = REAL["chaos"]
REAL_VELOCITIES = [f"{v:g}" for v in REAL["velocities"]]


def real_pieces_at(scene, profiles, velocity):
    """The pieces of a scene at these profiles and one velocity, every member."""
    return [REAL_PIECE.format(profile=p, scene=scene, velocity=velocity, member=k)
            for p in profiles for k in range(REAL["members"])]


for _v, _meshes in CHAOS.get("meshes", {}).items():
    if _v not in REAL_VELOCITIES or any(m not in FREE_PROFILES for m in _meshes) \
            or _meshes != [m for m in FREE_PROFILES if m in _meshes]:
        raise ValueError(f"fe_realisations.chaos.meshes.{_v}: {_meshes} is not allowed: a velocity of "
                         f"fe_realisations.velocities {REAL_VELOCITIES} -> profiles of fe_erosion_free.profiles "
                         f"{list(FREE_PROFILES)}, coarse to fine")


def chaos_profiles(velocity):
    """The meshes of the grid study at one velocity: fe_realisations.chaos.meshes where it names them, else every
    profile of fe_erosion_free."""
    return CHAOS.get("meshes", {}).get(str(velocity), list(FREE_PROFILES))


# The erosion-free grid study with the chaos in its error model, one velocity at a time (a study resumes velocity by
# velocity): the meshes of chaos_profiles, the realisations' mean and standard deviation per cell, the
# mean against element size with the chaos as its error.
use rule fe_fig12 as fe_erosion_free_chaos with:
    input: **task("tasks.fe_chaos"), reference=config["reference"],
           pieces=lambda w: [p for p in real_pieces_at(CHAOS["scene"], chaos_profiles(w.velocity), w.velocity) if not Path(p).exists()],
    output: png=report("figures/fe/erosion_free/chaos_v{velocity}.png", caption="../report/captions/fe_erosion_free_chaos.rst", category="Finite-element level"),
            csv="figures/fe/erosion_free/chaos_v{velocity}.csv", cells="figures/fe/erosion_free/chaos_v{velocity}_cells.csv",
            shots="figures/fe/erosion_free/chaos_v{velocity}_shots.csv",
    params: dpi=config["figures"]["dpi"], across=config["fe_erosion_free"]["profiles"],
            pieces=lambda w: [study_input(p) for p in real_pieces_at(CHAOS["scene"], chaos_profiles(w.velocity), w.velocity)],
            goals=CHAOS["goals"], noise_sigmas=CHAOS["noise_sigmas"], members=REAL["members"],
    wildcard_constraints: velocity="|".join(REAL_VELOCITIES),
    benchmark: "results/benchmarks/fe_erosion_free_chaos_v{velocity}.tsv"
    log: "results/logs/fe_erosion_free_chaos_v{velocity}.log",


def unstated_pieces(target, velocity):
    c = REAL_UNSTATED[target]
    return [p for s in c["scenes"] for p in real_pieces_at(s, [c["profile"]], velocity)]


# The inputs the paper does not state, one target and velocity at a time: nose friction on both FE targets, the
# paper's failure strain as stated on the eroding one, the lip's ejection on the erosion-free one; each scene's
# contrasts over its realisations beside its target's baseline.
rule fe_unstated_inputs:
    input: **task("tasks.fe_chaos"), reference=config["reference"],
           pieces=lambda w: [p for p in unstated_pieces(w.target, w.velocity) if not Path(p).exists()],
           scenes=lambda w: [f"workflow/scenes/fe/{s}.yaml" for s in REAL_UNSTATED[w.target]["scenes"]],
           schema=SCENE_SCHEMA,
    output: csv="figures/fe/unstated_{target}_v{velocity}.csv", shots="figures/fe/unstated_{target}_v{velocity}_shots.csv",
    params: target=lambda w: w.target, scenes=lambda w: REAL_UNSTATED[w.target]["scenes"],
            pieces=lambda w: [study_input(p) for p in unstated_pieces(w.target, w.velocity)],
    wildcard_constraints: target="|".join(REAL_UNSTATED), velocity="|".join(REAL_VELOCITIES),
    threads: 1
    resources: mem_mb=1000, runtime=5
    benchmark: "results/benchmarks/fe_unstated_inputs_{target}_v{velocity}.tsv"
    log: "results/logs/fe_unstated_inputs_{target}_v{velocity}.log",
    script: "../scripts/run_task.py"


# The moving window of the eroding target at 1200 m/s (a study): Table 3's shots of fe_realisations.window at the full
# mesh, with the window and with the whole domain (the task of fe_erosion_free_window).
T3_WINDOW = REAL["window"]


use rule fe_erosion_free_window as fe_table3_window with:
    input: **task("tasks.fe_window"), **GEOMETRY_RESULTS, reference=config["reference"], cal=fe_calibration("full"),
           **scene_input("workflow/scenes/fe/table3.yaml"), schema=SCENE_SCHEMA,
    output: runs="figures/fe/full/window_table3_{nose}_{velocity}.csv",
            summary="figures/fe/full/window_table3_{nose}_{velocity}_summary.csv",
            timing="figures/timing/fe_table3_window_{nose}_{velocity}.csv",
    params: cfg=fe_cfg("full"), hjc=config["concrete"], profile="full",
            nose=lambda w: w.nose, velocity=lambda w: w.velocity, members=T3_WINDOW["members"],
            velocity_step=config["fe_window"]["velocity_step"], confidence=config["fe_window"]["confidence"],
            goal_pct=config["fe_window"]["goal_pct"],
    benchmark: "results/benchmarks/fe_table3_window_{nose}_{velocity}.tsv"
    log: "results/logs/fe_table3_window_{nose}_{velocity}.log",
