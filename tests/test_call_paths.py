"""The way an FE shot takes through the package's folders, read off the call stack at the moment the solver is
called (the solver replaced by a probe that records the stack and stops the shot): a user's shot from the command
line passes through each folder once and never through the pipeline's tasks; a pipeline shot from its rule enters
``tasks/`` once."""
import inspect
import json
from pathlib import Path
from types import SimpleNamespace

import pytest
import yaml

import penetration.fe.shot as fe_shot
from penetration import cli
from penetration.nose.geometry import Ogive
from penetration.pipeline import dispatch
from penetration.pipeline.config import element_sizes
from penetration.pipeline.io import nose_record

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "src" / "penetration"
SHOT = ("ogive", "crh=3", "diameter_m=0.0269", "mass_kg=0.9", "length_m=0.2424", "velocity_ms=800", "fc_MPa=35",
        "target_density_kgm3=2300")


class Reached(Exception):
    """The probe's stop: the solver was reached."""


def folders(frames):
    """The package folders of a call stack, outermost first, a run of frames in one folder counted once ("top" for
    the modules at the top of the package)."""
    seen = []
    for frame in reversed(frames):
        path = Path(frame.filename).resolve()
        if PKG not in path.parents:
            continue
        parts = path.relative_to(PKG).parts
        folder = parts[0] if len(parts) > 1 else "top"
        if not seen or seen[-1] != folder:
            seen.append(folder)
    return seen


@pytest.fixture
def probe(monkeypatch):
    """Replace the solver's run as fe.shot calls it: record the folders on the stack, then stop."""
    found = []

    def run(*args, **kwargs):
        found.append(folders(inspect.stack()))
        raise Reached

    monkeypatch.setattr(fe_shot, "run", run)
    return found


def test_the_probe_reads_the_folders_in_order():
    fake = [SimpleNamespace(filename=str(p)) for p in (PKG / "fe/solver.py", PKG / "fe/shot.py", PKG / "tasks/fe.py",
                                                     PKG / "tasks/fe.py", PKG / "cli.py", ROOT / "tests/x.py")]
    assert folders(fake) == ["top", "tasks", "fe"]


def test_a_users_fe_shot_passes_each_folder_once_outside_the_tasks(probe, capsys):
    with pytest.raises(Reached):
        cli.main(["dop", *SHOT, "--model", "fe", "--failure-strain", "1.0", "--profile", "ci",
                  "--root", str(ROOT)])
    assert probe, "the solver was not reached"
    path = probe[0]
    assert "tasks" not in path and len(path) == len(set(path)), path
    assert path[0] == "top" and path[-1] == "fe", path


def test_a_pipeline_fe_shot_enters_the_tasks_once(probe, tmp_path, monkeypatch):
    """The rule fe_shot's job (workflow/rules/fe.smk) as run_task.py calls it, on a scene without a calibration."""
    monkeypatch.chdir(ROOT)
    cfg = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
    element_sizes(cfg, 0.5 * 0.0269)
    for name in ("do1", "fig4"):
        (tmp_path / f"{name}.json").write_text(json.dumps({"nose": nose_record(Ogive(3.0, 0.0134))}))
    scene = "workflow/scenes/fe/table3_erosion_free.yaml"
    inputs = SimpleNamespace(reference=cfg["reference"], scene=scene, schema="workflow/schemas/scene.schema.json",
                             do1=str(tmp_path / "do1.json"), fig4=str(tmp_path / "fig4.json"))
    outputs = SimpleNamespace(**{k: str(tmp_path / f"{k}.out") for k in ("json", "histories", "fields", "audit")})
    params = SimpleNamespace(cfg=cfg["fe"], hjc=cfg["concrete"], profile="ci", nose="crh3", velocity="500")
    with pytest.raises(Reached):
        dispatch.run("fe_shot", str(PKG / "tasks/fe.py"), inputs, outputs, params)
    path = probe[0]
    assert path.count("tasks") == 1 and len(path) == len(set(path)), path
    assert path[-1] == "fe", path
