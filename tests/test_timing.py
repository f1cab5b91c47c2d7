"""Attribution of Snakemake's benchmark records to rules (figures/timing/pipeline_*.csv)."""
import pandas as pd

from penetration.tasks.timing import attribute, pipeline_timing

# the profile as Snakemake writes the workflow's wildcard constraint into every pattern
PROFILE = "{profile,full|ci|fine|finer}"
PATTERNS = {"fe_shot": f"b/fe_shot_{PROFILE}_{{scene}}_{{nose}}_{{velocity}}.tsv",
            "fe_ensemble_shot": f"b/fe_ensemble_shot_{{family}}_{PROFILE}_{{shot}}_m{{member}}.tsv",
            "fe_rear_face": "b/fe_rear_face.tsv", "fe_table3": f"b/fe_table3_{PROFILE}.tsv"}


def test_records_go_to_the_rule_and_profile_that_wrote_them():
    got = attribute(["b/fe_ensemble_shot_rear_face_full_do1_block_m3.tsv", "b/fe_shot_finer_table3_crh45_1200.tsv",
                     "b/fe_rear_face.tsv", "b/fe_table3_fine.tsv"], PATTERNS)
    assert [(g["rule"], g.get("wc_profile")) for g in got] == [("fe_ensemble_shot", "full"), ("fe_shot", "finer"),
                                                               ("fe_rear_face", None), ("fe_table3", "fine")]
    assert got[0]["wc_family"] == "rear_face" and got[0]["wc_shot"] == "do1_block" and got[0]["wc_member"] == "3"


def test_records_of_no_current_rule_are_left_out():
    """A renamed rule's old records (fe_rear_face_shot_...) and a profile that is not configured match nothing."""
    assert attribute(["b/fe_rear_face_shot_full_do1_m1.tsv", "b/fe_table3_coarse.tsv", "b/other.tsv"],
                     PATTERNS) == []


def test_sums_per_rule_and_stage(tmp_path):
    rec = {"fe_shot_full_table3_crh3_500.tsv": 10.0, "fe_shot_full_table3_crh3_800.tsv": 30.0,
           "fe_shot_ci_table3_crh3_500.tsv": 2.0, "fe_rear_face.tsv": 3.0, "stale_rule.tsv": 99.0}
    for name, s in rec.items():
        (tmp_path / name).write_text(f"s\th:m:s\tmax_rss\n{s}\t0:00:00\t100.0\n")
    pats = {k: v.replace("b/", f"{tmp_path}/") for k, v in PATTERNS.items()}

    class NS(dict):
        __getattr__ = dict.__getitem__

    out = NS(rules=str(tmp_path / "rules.csv"), stages=str(tmp_path / "stages.csv"))
    pipeline_timing(None, out, NS(folder=str(tmp_path), patterns=pats,
                                              rule_files={k: "fe" for k in PATTERNS}))
    stages = pd.read_csv(out.stages).set_index("stage")
    assert stages.loc["fe [full]", "wall_total_s"] == 40.0 and stages.loc["fe [full]", "jobs"] == 2
    assert stages.loc["fe [ci]", "wall_total_s"] == 2.0 and stages.loc["fe", "wall_total_s"] == 3.0
    assert stages.wall_total_s.sum() == 45.0   # the stale record is not counted
    # a later build of fe_table3 alone: its record replaces the row, the other rows stay, a removed rule's row goes
    for f in tmp_path.glob("*.tsv"):
        f.unlink()
    (tmp_path / "fe_table3_full.tsv").write_text("s\th:m:s\tmax_rss\n5.0\t0:00:00\t100.0\n")
    rules = pd.read_csv(out.rules)
    pd.concat([rules, rules.iloc[:1].assign(rule="gone")]).to_csv(out.rules, index=False)
    pipeline_timing(None, out, NS(folder=str(tmp_path), patterns=pats, rule_files={k: "fe" for k in PATTERNS}))
    rules = pd.read_csv(out.rules).set_index(["stage", "rule"])
    assert rules.loc[("fe [full]", "fe_shot"), "wall_total_s"] == 40.0 and rules.loc[("fe [full]", "fe_table3"), "jobs"] == 1
    assert "gone" not in rules.index.get_level_values("rule")
    assert pd.read_csv(out.stages).wall_total_s.sum() == 50.0


def test_the_pipelines_own_patterns_attribute_sample_records():
    """The rules' benchmark patterns as Snakemake holds them (the wildcard constraints written in, as
    pipeline_timing receives them): records of overlapping names (scene and scene_cavity, fe_shot and
    fe_ensemble_shot, a family with an underscore) go to the rule that wrote them."""
    from workflow_rules import loaded_rules

    patterns = {name: str(r.benchmark) for name, r in loaded_rules().items() if r.benchmark}
    samples = {"scene_cavity_do1": "scene_cavity", "scene_do1": "scene", "fe_shot_full_table3_crh3_500": "fe_shot",
               "fe_ensemble_shot_rear_face_full_do1_block_m3": "fe_ensemble_shot",
               "fe_ensemble_shot_ensemble_fine_crh45_1200_m2": "fe_ensemble_shot",
               "calibrate_fe_do1_finer_h0.00583333333333": "calibrate_fe_do1", "fe_table3_full": "fe_table3",
               "fe_window_study_ci": "fe_window_study", "fe_rear_face": "fe_rear_face", "report": "report",
               "calibrate_fe_strength_do1_free1600_table3_erosion_free_calibrated": "calibrate_fe_strength_do1",
               "fe_erosion_free_window_crh3_1200": "fe_erosion_free_window"}
    got = attribute([f"results/benchmarks/{k}.tsv" for k in samples], patterns)
    assert [g["rule"] for g in got] == list(samples.values())
    assert got[3]["wc_family"] == "rear_face" and got[4]["wc_profile"] == "fine"


def test_a_repeated_wildcard_must_match_the_same_text():
    pats = {"twice": f"b/x_{PROFILE}_{{a}}_{{a}}.tsv"}
    assert attribute(["b/x_ci_u_v_u_v.tsv"], pats)[0]["wc_a"] == "u_v"
    assert attribute(["b/x_ci_u_w.tsv"], pats) == []


def test_constraints_in_the_pattern_decide_as_snakemake_writes_them():
    """Snakemake's patterns carry the wildcard constraints inline ({scene,[A-Za-z0-9_]+}); braces inside one count."""
    pats = {"scene": "b/scene_{scene,[A-Za-z0-9_]+}.tsv", "scene_cavity": "b/scene_cavity_{scene,[a-z0-9]{3}}.tsv",
            "fe_ensemble_shot": "b/fe_ensemble_shot_{family,ensemble|rear_face}_{profile,full|ci}_{shot}_m{member,\\d+}.tsv"}
    got = attribute(["b/scene_cavity_do1.tsv", "b/scene_cavity_table3.tsv", "b/fe_ensemble_shot_rear_face_ci_do1_m7.tsv",
                     "b/fe_ensemble_shot_rear_face_ci_do1_mx.tsv"], pats)
    assert [(g["rule"], g.get("wc_scene"), g.get("wc_profile")) for g in got] == [
        ("scene_cavity", "do1", None), ("scene", "cavity_table3", None), ("fe_ensemble_shot", None, "ci")]


def test_the_pattern_with_more_literal_text_wins_whatever_its_constraints_length():
    pats = {"fe": "b/fe_{x,a_very_long_alternative_of_a_constraint|shot_z}.tsv", "fe_shot": "b/fe_shot_{y}.tsv"}
    assert [g["rule"] for g in attribute(["b/fe_shot_z.tsv"], pats)] == ["fe_shot"]
