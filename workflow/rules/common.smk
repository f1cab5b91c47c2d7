# What every rule file reads: the config checked at load (its mesh profiles, the reproduction check's file, the study
# grids and scenes), and the helpers rules share (a profile's fe slice, config slices as params, a calibration's path,
# the inputs of a committed record). Included first by the Snakefile.
from pathlib import Path

from penetration.pipeline.config import (check_config, check_config_files, checked_outputs, load_check, mesh_profiles,
                                         scale_grid)
from penetration.pipeline.dispatch import (fe_calibrated_scenes, fe_scene_shots, fe_shot_owners, load_studies, scene_input,
                                          size_params, study_input, study_outputs, task, uncommitted)
from penetration.levels import LEVELS
from penetration.pipeline.scenes import scene_names

# Stop before any job runs if the config (file plus --config overrides) is invalid.
check_config(config, "workflow/schemas/config.schema.json", "workflow/config.yaml (with overrides)")
check_config_files(workflow.configfiles)  # a key given twice in a config file (Snakemake keeps the last silently)
# a scene file whose name the scene wildcard cannot match is refused, naming it (not Snakemake's "No rule to produce")
for folder in ("workflow/scenes", "workflow/scenes/cavity", "workflow/scenes/fe"):
    scene_names(folder)
STUDIES = load_studies("workflow/studies", "workflow/schemas/study.schema.json")
SCENE_SCHEMA = "workflow/schemas/scene.schema.json"
GEOMETRY_RESULTS = dict(do1="results/geometry/double_ogive_table4.json", fig4="results/geometry/double_ogive_fig4.json")


# the FE level's mesh profiles beyond full and ci: the convergence study's, the bands' (centre -> its profiles) and
# the erosion-free grid study's, with every one's element size (checked: distinct names, bands on full or a
# convergence profile)
PROFILES = mesh_profiles(config)
CONVERGENCE_PROFILES, BANDS, FREE_PROFILES, EXTRA_PROFILES = PROFILES.convergence, PROFILES.bands, PROFILES.free, PROFILES.extra
BAND_PROFILES = PROFILES.band_profiles


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
    """The `fe` config slice for a profile's jobs (a profile beyond full and ci joins its element size)."""
    return PROFILES.fe_slice(config["fe"], profile)


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
    it to rebuild it (its task refuses to run without its runs). The rule marks the record update(): a job that
    a change of the rule's metadata starts anyway leaves it in place, and Snakemake restores it when the task
    refuses."""
    t = task(module)
    while_missing = lambda f: (lambda w: [] if Path(record.format(**w)).exists() else f(w))
    return {"task": ancient(t["task"]), "code": while_missing(lambda w: t["code"]),
            **{name: while_missing(f) for name, f in runs.items()}}




def chaos_study():
    """The erosion-free grid study with the chaos in its error model, as the paper's rules read it: its committed
    output per velocity of fe_realisations (study_input; a velocity not yet run is "missing" and left out)."""
    return [study_input(f"figures/fe/erosion_free/chaos_v{v:g}.csv") for v in config["fe_realisations"]["velocities"]]
