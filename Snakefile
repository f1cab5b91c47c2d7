# Replication of Liu, Pi & Huang (2015), "Penetration performance of double-ogive-nose projectiles".
#
# Two targets:
#   `snakemake -c2` (rule all)         every figure and table of the paper at every level, the finite-element level
#                                      at the mesh profile `fe_profile` (default full), the diff and the report;
#   `snakemake -c2 studies`            the research studies, listed once in workflow/studies.yaml. Their outputs
#                                      are committed; the report reads them from disk, and no output of `all`
#                                      depends on a study.
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
# (workflow/rules/figures.smk). What the rule files share (the checked config, the mesh profiles, the helpers) is
# workflow/rules/common.smk, included first.
configfile: "workflow/config.yaml"


include: "workflow/rules/common.smk"
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
    "t3shot": list(config["fe_realisations"]["window"]["shots"]),
    "rv": [f"{v:g}" for v in config["fe_realisations"]["velocities"]], "utarget": list(config["fe_realisations"]["unstated"]),
    "fs": [f"{v:g}" for v in config["validation"]["laboratory"]["failure_strains"]],
    "slevel": list(config["scale_effect"]["levels"]),
    "cvariant": [v for v in config["scale_effect"]["levels"].get("cavity", []) if v != "none"],
    "fvariant": [v for v in config["scale_effect"]["levels"].get("fe", []) if v != "none"],
    "ss": [f"{v:g}" for v in config["validation"]["laboratory"]["strength_scales"]],
    "sfs": [f"{v:g}" for v in config["scale_effect"]["fe_failure_strains"]],
    "sprofile": [config["scale_effect"]["fe_profile"]]}, CHECK_STUDIES)
STUDY_OUTPUTS = [path for paths in RESEARCH.values() for path in paths]


include: "workflow/rules/report.smk"


rule all:
    default_target: True
    input: "figures/report.html", REPORT_INPUTS,


rule studies:
    input: STUDY_OUTPUTS,
