# Replication of Liu, Pi & Huang (2015), "Penetration performance of double-ogive-nose projectiles".
#
# Two targets:
#   `snakemake -c2` (rule all)         every figure and table of the paper at every level, the finite-element level
#                                      at the mesh profile `fe_profile` (default full), the diff and the report;
#   `snakemake -c2 studies`            the research studies (mesh bands and convergence profiles, ensembles of the
#                                      erosion chaos, the rear face, the moving window, the mesh study of the
#                                      failure strain, the cavity and trajectory solver studies, accuracy against
#                                      cost). Their outputs are committed; the report reads them from disk, and no
#                                      output of `all` depends on a study.
# `snakemake -c2 figures/fig16.png` builds one figure and what it needs.
#
# Every rule is declarations plus one call into src/: `**task(MODULE)` names
# the module holding the rule's task (the function of the rule's name) and
# lists as code inputs every package module that module imports, so editing
# a module re-runs exactly the rules whose tasks use it. Every rule declares
# threads, resources (mem_mb, runtime in minutes) and a benchmark record.
# Rules of one shape are declared once: the first of a kind in its file is
# written out, the others are `use rule FIRST as NAME with:` (they inherit its
# threads, resources and script, and state their own inputs, outputs, params,
# benchmark and log); the paper's figures and tables are one table and a loop
# (workflow/rules/figures.smk).
from pathlib import Path

from penetration.pipeline.config import check_config, check_config_files, load_check
from penetration.pipeline.dispatch import (fe_calibrated_scenes, fe_scene_shots, fe_shot_owners, load_studies, scene_input,
                                          study_input, study_outputs, task, uncommitted)
from penetration.levels import LEVELS
from penetration.pipeline.scenes import scene_names
from penetration.tasks.reference import checked_outputs

configfile: "workflow/config.yaml"
# Stop before any job runs if the config (file plus --config overrides) is invalid.
check_config(config, "workflow/schemas/config.schema.json", "workflow/config.yaml (with overrides)")
check_config_files(workflow.configfiles)  # a key given twice in a config file (Snakemake keeps the last silently)
# a scene file whose name the scene wildcard cannot match is refused, naming it (not Snakemake's "No rule to produce")
for folder in ("workflow/scenes", "workflow/scenes/cavity", "workflow/scenes/fe"):
    scene_names(folder)
STUDIES = load_studies("workflow/studies", "workflow/schemas/study.schema.json")
SCENE_SCHEMA = "workflow/schemas/scene.schema.json"
GEOMETRY_RESULTS = dict(do1="results/geometry/double_ogive_table4.json", fig4="results/geometry/double_ogive_fig4.json")


# mesh profiles of the convergence study of the FE nose contrasts (Table 3 only), finer than `full`
# (check_config's schema has refused the names full and ci)
CONVERGENCE_PROFILES = list(config["fe_convergence"]["profiles"])
# mesh profiles of the bands of element sizes around `full` and convergence profiles (the mesh realisations of
# the FE nose contrasts): centre -> its band's profiles
BANDS = {centre: list(band) for centre, band in config["fe_band"]["bands"].items()}
BAND_PROFILES = [p for band in BANDS.values() for p in band]  # a name in two bands shows twice (refused below)
BAND_SIZES = {p: h for band in config["fe_band"]["sizes"].values() for p, h in band.items()}
# mesh profiles of the erosion-free target's grid-convergence study (coarse first, refined by one constant ratio)
FREE_PROFILES = list(config["fe_erosion_free"]["profiles"])
# element size of every profile beyond full and ci
EXTRA_PROFILES = {**config["fe_convergence"]["sizes"], **BAND_SIZES,
                  **config["fe_erosion_free"]["sizes"]}  # profile -> element size (m)
if len(EXTRA_PROFILES) != len(CONVERGENCE_PROFILES) + len(BAND_PROFILES) + len(FREE_PROFILES):
    raise ValueError(f"fe_erosion_free.profiles {FREE_PROFILES}: names must differ from fe_convergence's and fe_band's")
for centre in BANDS:
    if centre not in ["full", *CONVERGENCE_PROFILES]:
        raise ValueError(f"fe_band.bands.{centre}: allowed centres full or a profile of fe_convergence.profiles "
                         f"{CONVERGENCE_PROFILES}")
if len(BAND_PROFILES) != len(set(BAND_PROFILES)) or set(BAND_PROFILES) & set(CONVERGENCE_PROFILES):
    raise ValueError(f"fe_band.bands: profile names {BAND_PROFILES} must be distinct and not those of fe_convergence")


wildcard_constraints:
    scene=r"[A-Za-z0-9_]+",
    profile="|".join(["full", "ci", *EXTRA_PROFILES]),
    size=r"[0-9.]+",
    nose=r"[a-z0-9_]+",
    velocity=r"[0-9.]+",
    member=r"[0-9]+",

# FE outputs: `all` builds the configured profile only (full: the level's default mesh; ci: the CI's coarse one).
FE_PROFILES = [config["fe_profile"]]
# the reproduction check (its own file, config `check`): its outputs under figures/fe/{profile}/ stand for the profile
# built; the studies' ({band}: each band profile)
CHECK = load_check(config["check"], "workflow/schemas/check.schema.json")
CHECK_STUDIES = checked_outputs(CHECK, ["full", "ci"], BAND_PROFILES, "studies")
CHECK["outputs"] = checked_outputs(CHECK, FE_PROFILES)


def fe_cfg(profile):
    """The `fe` config slice for a profile's jobs; a convergence or band profile (fe_convergence, fe_band) joins its
    profiles."""
    if profile not in EXTRA_PROFILES:
        return config["fe"]
    h = EXTRA_PROFILES[profile]
    return {**config["fe"], "profiles": {**config["fe"]["profiles"], profile: {"element_size": h, "mesh_study_sizes": [h]}}}


def cfg_slice(*keys, **slices):
    """The config sections a task reads, as its params: a change elsewhere in the config leaves its job alone
    (Snakemake reruns a job whose params changed)."""
    return {**{k: config[k] for k in keys}, **slices}


def fe_calibration(profile):
    return f"results/fe/{profile}/calibration_h{fe_cfg(profile)['profiles'][profile]['element_size']}.json"


def record_inputs(module, record, **runs):
    """The inputs of a rule whose output is a committed record of a study (a piece): while ``record`` (a path with
    the rule's wildcards) is missing, its task, code and runs (``runs``: name -> input function); once it is on disk
    only the task file, as ancient, so that nothing can turn newer and asking for the record by name never deletes
    it to rebuild it (its task refuses to run without its runs)."""
    t = task(module)
    while_missing = lambda f: (lambda w: [] if Path(record.format(**w)).exists() else f(w))
    return {"task": ancient(t["task"]), "code": while_missing(lambda w: t["code"]),
            **{name: while_missing(f) for name, f in runs.items()}}


include: "workflow/rules/geometry.smk"
include: "workflow/rules/analytic.smk"
include: "workflow/rules/trajectory.smk"
include: "workflow/rules/cavity.smk"
include: "workflow/rules/cavity_studies.smk"
include: "workflow/rules/contrasts.smk"
include: "workflow/rules/fe.smk"
include: "workflow/rules/fe_studies.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/reference.smk"


# Everything `all` builds; the replication report reads these (and the studies' committed outputs) and is built last.
REPORT_INPUTS = [
    expand("figures/{f}.png", f=FIGURES),
    expand("figures/{t}.csv", t=TABLES),
    list(CHECK["outputs"]),
    "figures/diff_summary.md",
    expand("figures/fe/{profile}/{name}", profile=FE_PROFILES, name=FE_OUTPUTS),
    expand("figures/fe/{profile}/claims.csv", profile=FE_PROFILES),
    expand("figures/timing/fe_do1_{profile}.json", profile=FE_PROFILES),
]

# The studies' outputs (`snakemake -c2 studies`, `make studies`), listed once in workflow/studies.yaml: committed, read
# by the report from disk, compared by `make check-studies` (their classes: `studies` in workflow/check.yaml).
RESEARCH = study_outputs("workflow/studies.yaml", "workflow/schemas/studies.schema.json", {
    "profile": ["full", "ci"], "band": BAND_PROFILES, "shot": list(config["fe_erosion_free"]["window"]["shots"]),
    "fs": [f"{v:g}" for v in config["validation"]["laboratory"]["failure_strains"]]}, CHECK_STUDIES)
STUDY_OUTPUTS = [path for paths in RESEARCH.values() for path in paths]


include: "workflow/rules/report.smk"


rule all:
    default_target: True
    input: "figures/report.html", REPORT_INPUTS,


rule studies:
    input: STUDY_OUTPUTS,
