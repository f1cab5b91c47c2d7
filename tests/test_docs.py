"""The numbers the README and docs/ quote are their outputs' (penetration.pipeline.docs): every generated block equals what
the outputs committed at git HEAD give. This test checks the committed documents against the committed outputs."""
import pytest
from conftest import committed, committed_files

from penetration.pipeline.docs import BLOCK, next_mesh_cost, render

DOCUMENTS = ["README.md"] + [p for p in committed_files("docs") if p.endswith(".md")]


@pytest.mark.parametrize("path", DOCUMENTS)
def test_generated_blocks_equal_what_the_committed_outputs_give(path):
    text = committed(path)
    assert render(text, committed) == text, f"python -m penetration.pipeline.docs {path}"


def test_the_readme_quotes_its_results_through_generated_blocks():
    names = [m.group("name") for m in BLOCK.finditer(committed("README.md"))]
    assert {"levels", "claims", "rebuild"} <= set(names) and len(names) == len(set(names))


def test_a_stale_block_is_found(tmp_path):
    text = "x\n<!-- generated: answer -->\nDO/CRH 4.5 1.000-1.001\n<!-- end generated -->\n"
    assert render(text, committed) != text
    with pytest.raises(KeyError, match="known"):
        render("<!-- generated: nothing -->\n<!-- end generated -->", committed)


def test_the_next_mesh_cost_follows_a_power_law_of_the_elements_across():
    # shots whose job time is exactly 2 s * n**3 on meshes refined by 1.25: the fit recovers the power 3, and the
    # next mesh (20 * 1.25 = 25 across) costs the finest mesh's 3 shots scaled by 1.25**3
    shots = [{"elements_across": n, "wall_time_s": 2.0 * n ** 3 * k} for n in (8.192, 10.24, 12.8, 16.0, 20.0)
             for k in (0.5, 1.0, 1.5)]
    following, power, seconds = next_mesh_cost(shots)
    assert following == pytest.approx(25.0)
    assert power == pytest.approx(3.0, rel=1e-12)
    assert seconds == pytest.approx(3 * 2.0 * 25.0 ** 3, rel=1e-12)
    with pytest.raises(ValueError, match="elements_across"):
        next_mesh_cost(shots[:3])


def test_the_studies_built_with_an_older_code_are_listed_and_only_they():
    from penetration.pipeline.docs import built_with
    studies = ("a:\n  what: first\n  outputs: [figures/a.csv]\n  built_with: the old solver\n"
               "b:\n  what: second\n  outputs: [figures/b.csv]\n")
    block = built_with(lambda path: studies)
    assert block.startswith("1 of 2 studies") and "| `a` | first | the old solver |" in block and "`b`" not in block
    current = built_with(lambda path: studies.replace("  built_with: the old solver\n", ""))
    assert "current code" in current and "|" not in current


def test_the_rebuild_times_name_the_last_run_on_each_machine_newest_first():
    from penetration.pipeline.docs import rebuild
    header = "date,commit,target,install_s,target_s,total_s,clean_but_timing,machine,install_cache\n"
    rows = ["2026-01-01T00:00:00Z,aaa,reproduce,60,1200,1260,False,M1,",
            "2026-01-02T00:00:00Z,bbb,reproduce,60,600,660,False,M2,",
            "2026-01-03T00:00:00Z,ccc,reproduce,60,1800,1860,False,M1,warm",
            "2026-01-04T00:00:00Z,ddd,ci,0,900,900,False,M2,cold"]
    block = rebuild(lambda path: header + "\n".join(rows) + "\n")
    lines = [line for line in block.splitlines() if line.startswith("- ")]
    # M1's newer run (31.0 min, ccc) replaces its older one; M2's reproduce run stays beside it, after it by date
    assert [line.split("commit ")[1] for line in lines] == ["ccc, on M1", "bbb, on M2", "ddd, on M2"]
    assert "31.0 min" in lines[0] and "11.0 min" in lines[1] and "15.0 min" in lines[2]
    # the installer's cache where the record has it (a run before the column: nothing said)
    assert "cache warm" in lines[0] and "cache" not in lines[1] and "cache cold" in lines[2]
