# Replication of Liu, Pi & Huang (2015), "Penetration performance of
# double-ogive-nose projectiles". `snakemake -c2` rebuilds every figure and
# table implemented so far; `snakemake -c2 figures/fig16.png` one figure.
import json
from penetration.config import validate

configfile: "workflow/config.yaml"
# Stop before any job runs if the config (file plus --config overrides) is invalid.
validate(config, json.load(open("workflow/schemas/config.schema.json")), "workflow/config.yaml (with overrides)")

SRC = "src/penetration/"


wildcard_constraints:
    scene=r"[A-Za-z0-9_]+",
TASK = "workflow/scripts/run_task.py"
FIG_SRC = [f"{SRC}figures/common.py", f"{SRC}tasks.py", f"{SRC}reference.py"]
FIGURES = ["fig01", "fig03", "fig04", "fig05", "fig06", "fig07", "fig08", "fig09", "fig10", "fig12", "fig14", "fig15", "fig16"]
TABLES = ["table1", "table2", "table3", "table4"]


include: "workflow/rules/geometry.smk"
include: "workflow/rules/dop.smk"
include: "workflow/rules/cavity.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/reference.smk"


rule all:
    default_target: True
    input:
        expand("figures/{f}.png", f=FIGURES),
        expand("figures/{f}.csv", f=FIGURES),
        expand("figures/{t}.csv", t=TABLES),
        "figures/diff.csv",
        "figures/diff_summary.md",
        "figures/validation.png",
        "figures/validation.csv",
        "figures/accuracy_trajectory.png",
        "figures/cavity_sigma_n.png",
        "figures/accuracy_cavity.png",
        "figures/do1_family_sensitivity.csv",
        "figures/cavity_table3_sensitivity.png",
        "figures/ablation_cavity.csv",
