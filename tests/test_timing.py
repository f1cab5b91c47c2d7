"""Attribution of Snakemake's benchmark records to rules (figures/timing/pipeline_*.csv)."""
import pandas as pd

from penetration.tasks.timing import attribute, pipeline_timing

PATTERNS = {"fe_shot": "b/fe_shot_{profile}_{scene}_{nose}_{velocity}.tsv",
            "fe_ensemble_shot": "b/fe_ensemble_shot_{family}_{profile}_{shot}_m{member}.tsv",
            "fe_rear_face": "b/fe_rear_face.tsv", "fe_table3": "b/fe_table3_{profile}.tsv"}
PROFILES = ("full", "ci", "fine", "finer")


def test_records_go_to_the_rule_and_profile_that_wrote_them():
    got = attribute(["b/fe_ensemble_shot_rear_face_full_do1_block_m3.tsv", "b/fe_shot_finer_table3_crh45_1200.tsv",
                     "b/fe_rear_face.tsv", "b/fe_table3_fine.tsv"], PATTERNS, PROFILES)
    assert [(g["rule"], g.get("wc_profile")) for g in got] == [("fe_ensemble_shot", "full"), ("fe_shot", "finer"),
                                                               ("fe_rear_face", None), ("fe_table3", "fine")]
    assert got[0]["wc_family"] == "rear_face" and got[0]["wc_shot"] == "do1_block" and got[0]["wc_member"] == "3"


def test_records_of_no_current_rule_are_left_out():
    """A renamed rule's old records (fe_rear_face_shot_...) and a profile that is not configured match nothing."""
    assert attribute(["b/fe_rear_face_shot_full_do1_m1.tsv", "b/fe_table3_coarse.tsv", "b/other.tsv"],
                     PATTERNS, PROFILES) == []


def test_sums_per_rule_and_stage(tmp_path):
    rec = {"fe_shot_full_table3_crh3_500.tsv": 10.0, "fe_shot_full_table3_crh3_800.tsv": 30.0,
           "fe_shot_ci_table3_crh3_500.tsv": 2.0, "fe_rear_face.tsv": 3.0, "stale_rule.tsv": 99.0}
    for name, s in rec.items():
        (tmp_path / name).write_text(f"s\th:m:s\tmax_rss\n{s}\t0:00:00\t100.0\n")
    pats = {k: v.replace("b/", f"{tmp_path}/") for k, v in PATTERNS.items()}

    class NS(dict):
        __getattr__ = dict.__getitem__

    out = NS(rules=str(tmp_path / "rules.csv"), stages=str(tmp_path / "stages.csv"))
    pipeline_timing(None, out, NS(folder=str(tmp_path), patterns=pats, profiles=list(PROFILES),
                                              rule_files={k: "fe" for k in PATTERNS}))
    stages = pd.read_csv(out.stages).set_index("stage")
    assert stages.loc["fe [full]", "wall_total_s"] == 40.0 and stages.loc["fe [full]", "jobs"] == 2
    assert stages.loc["fe [ci]", "wall_total_s"] == 2.0 and stages.loc["fe", "wall_total_s"] == 3.0
    assert stages.wall_total_s.sum() == 45.0   # the stale record is not counted
