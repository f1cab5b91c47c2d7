"""The Snakemake DAG: one figure needs only its own chain; bad config stops early."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def snakemake(*args):
    return subprocess.run([sys.executable, "-m", "snakemake", "-c1", "--forceall", "-n", *args],
                          capture_output=True, text=True, cwd=ROOT)


def planned_rules(out):
    """Rule names from the 'Job stats' table of a dry run."""
    lines = out.split("Job stats:", 1)[1].splitlines()
    rules = set()
    for line in lines[3:]:
        parts = line.split()
        if not parts or parts[0] == "total":
            break
        rules.add(parts[0])
    return rules


def test_single_figure_needs_only_its_chain():
    out = snakemake("figures/fig16.png")
    assert out.returncode == 0, out.stderr
    rules = planned_rules(out.stdout)
    assert {"fig16", "geometry", "infer_table4_do1", "infer_fig4_design"} <= rules
    assert not rules & {"fig03", "fig04", "table1", "diff", "reproduce_check"}


def test_table1_needs_no_geometry():
    rules = planned_rules(snakemake("figures/table1.csv").stdout)
    assert rules == {"table1"}


def test_invalid_config_stops_before_jobs():
    out = snakemake("--config", "projectile={'density': -5.0, 'diameter': 'table2.diameter'}")
    assert out.returncode != 0
    text = out.stdout + out.stderr
    assert "projectile.density" in text and "allowed" in text
    assert "Job stats" not in text


def test_a_committed_piece_is_not_an_input_and_a_missing_one_is(tmp_path, monkeypatch):
    """uncommitted: a rule's input function that leaves out the pieces on disk (records read through the params)
    and names the missing ones, with the rule's wildcards filled in."""
    from penetration.pipeline.dispatch import uncommitted

    monkeypatch.chdir(tmp_path)
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "fs_1.csv").write_text("x\n")
    fn = uncommitted(["{profile}/fs_1.csv", "{profile}/fs_2.csv"])
    assert fn({"profile": "full"}) == ["full/fs_2.csv"]
    assert fn({"profile": "ci"}) == ["ci/fs_1.csv", "ci/fs_2.csv"]
