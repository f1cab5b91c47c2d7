"""The scale effect as a scene's effect (``size: {variant: NAME}``): the scene tasks apply the variant's published
relations with the factor the scale effect's study fitted with it on the laboratory shots, a scene without it stays
scale-free, and a task that would ignore it, or a scene that would drop part of it, is refused."""
import dataclasses
import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
import yaml

from penetration.analytic.dop import penetration_depth
from penetration.analytic.resistance import Target, strength_factor
from penetration.concrete import material as concrete
from penetration.nose.geometry import Ogive
from penetration.nose.nstar import nstar
from penetration.paper import reference
from penetration.pipeline import dispatch
from penetration.pipeline.dispatch import study_input
from penetration.pipeline.config import element_sizes
from penetration.pipeline.io import nose_record
from penetration.pipeline.scenes import SceneError, read_scene, resolve

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "src/penetration"
SCHEMA = str(ROOT / "workflow/schemas/scene.schema.json")
CFG = yaml.safe_load((ROOT / "workflow/config.yaml").read_text())
element_sizes(CFG, 0.07)  # the fe profiles' element sizes at DO1's shank radius (as the Snakefile does)
SIZE_PARAMS = {"variants": CFG["scale_effect"]["variants"], "law": CFG["validation"]["strength_law"],
               "fe_profile": CFG["scale_effect"]["fe_profile"],
               "calibration": study_input(str(ROOT / "figures/scale/calibration_analytic.csv"))}


def synthetic_calibration(tmp_path, level, variant, value):
    """A calibration table of the scale effect's study with one row (fold all) at ``level``."""
    path = tmp_path / f"calibration_{level}.csv"
    pd.DataFrame([{"level": level, "fold": "all", "variant": variant, "value": value}]).to_csv(path, index=False)
    return {**SIZE_PARAMS, "calibration": study_input(str(path))}


def published_factor(velocity, diameter, aggregate=0.016, lambda0=25.0):
    """MC2010's compressive factor at V/d on its cube-root branch (Eq 5.1-50, eps0 = 30e-6 1/s; V/d is above the
    30 1/s where that branch starts for every case here) times Bazant's (1 + d/D0)^(-1/2), D0 = lambda0 d_a."""
    rate = velocity / diameter
    assert rate > 30.0
    return 0.012 * (rate / 30e-6) ** (1.0 / 3.0) / math.sqrt(1.0 + diameter / (lambda0 * aggregate))


def scene_inputs(tmp_path, data, name="sized"):
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump(data))
    for key in ("do1", "fig4"):
        (tmp_path / f"{key}.json").write_text(json.dumps({"nose": nose_record(Ogive(3.0, 0.07))}))
    return SimpleNamespace(reference=CFG["reference"], scene=str(path), schema=SCHEMA, do1=str(tmp_path / "do1.json"),
                           fig4=str(tmp_path / "fig4.json"))


def plain_scene(radius, mass, size=True, level="trajectory", variant="rate_fracture"):
    effects = ["crater", "static", "inertial"] + (["size"] if size else [])
    data = {"description": "a CRH 3 shot with the scale effect", "projectile": {"mass": mass, "radius": radius},
            "noses": {"crh3": {"kind": "ogive", "psi": 3.0}},
            "target": {"rho": 2440.0, "fc": 48.0e6, "strength": {"law": "li_chen"}}, "velocities": [500.0, 1000.0],
            "level": level, "effects": effects}
    if size:
        data["size"] = {"variant": variant}
    return data


def run_scene(tmp_path, data, name="sized"):
    out = tmp_path / name
    out.mkdir()
    outputs = SimpleNamespace(dop=str(out / "dop.csv"), histories=str(out / "histories.csv"))
    size = SIZE_PARAMS if "size" in data["effects"] else None
    dispatch.run("scene", str(PKG / "tasks/trajectory.py"), scene_inputs(out, data, name), outputs,
                 SimpleNamespace(rtol=CFG["trajectory"]["rtol"], size=size))
    return pd.read_csv(outputs.dop)


def committed_factor(level, variant):
    t = pd.read_csv(ROOT / f"figures/scale/calibration_{level}.csv")
    return float(t[(t.variant == variant) & (t.fold == "all")].value.iloc[0])


def test_a_scene_with_the_size_effect_takes_the_published_factors_at_each_shot(tmp_path):
    """Eq 9 at S x (the study's factor fitted with the variant on the laboratory shots) x (MC2010's factor at V/d) x
    (Bazant's factor at d), and the trajectory of the same three effects lands on it: the effect enters the closed
    form and the trajectory alike, velocity by velocity."""
    table = run_scene(tmp_path, plain_scene(0.07, 81.1))
    S0 = float(strength_factor(48.0e6, "li_chen")) * committed_factor("analytic", "rate_fracture")
    for row in table.itertuples():
        k = published_factor(row.velocity, 0.14)
        assert row.size_factor == pytest.approx(k, rel=1e-9)
        assert row.size_calibration == committed_factor("analytic", "rate_fracture")
        want = float(penetration_depth(81.1, 0.07, nstar(Ogive(3.0, 0.07)), Target(2440.0, 48.0e6, S0 * k),
                                       row.velocity))
        assert row.dop == pytest.approx(want, rel=1e-12)
        assert row.trajectory_dop == pytest.approx(want, rel=1e-4)


def test_the_size_effect_breaks_geometric_similarity_the_way_the_literature_says(tmp_path):
    """Without the effect two geometrically similar shots (calibre x5, mass x125) reach the same depth over calibre
    at equal velocity; with it the larger calibre penetrates deeper relative to its size (x/d grows with d, as in
    the empirical formulas fitted on large calibres)."""
    small, large = (0.014, 81.1 / 125.0), (0.07, 81.1)
    free = [run_scene(tmp_path, plain_scene(r, m, size=False), f"free{i}") for i, (r, m) in enumerate((small, large))]
    np.testing.assert_allclose(free[0].dop_over_d, free[1].dop_over_d, rtol=1e-12)
    sized = [run_scene(tmp_path, plain_scene(r, m), f"sized{i}") for i, (r, m) in enumerate((small, large))]
    assert np.all(sized[1].dop_over_d.to_numpy() > 1.05 * sized[0].dop_over_d.to_numpy())


def test_a_task_that_would_ignore_the_size_effect_refuses_the_scene(tmp_path):
    from penetration.tasks.common import scene_from_inputs
    inputs = scene_inputs(tmp_path, plain_scene(0.07, 81.1))
    with pytest.raises(SceneError, match="size is listed.*allowed"):
        scene_from_inputs(inputs, ("analytic", "trajectory"))
    assert scene_from_inputs(inputs, ("analytic", "trajectory"), size=SIZE_PARAMS).size.mechanisms == ("rate", "fracture")


@pytest.mark.parametrize("changes,needle", [
    ({"effects": ["crater", "static", "inertial"]}, "size is set"),
    ({"size": None}, "size: {variant: NAME}"),
    ({"size": {"mechanisms": ["rate"]}}, "Additional properties"),
])
def test_size_settings_out_of_place_are_refused_naming_the_field(tmp_path, changes, needle):
    data = {k: v for k, v in {**plain_scene(0.07, 81.1), **changes}.items() if v is not None}
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(ValueError) as err:
        read_scene(path, SCHEMA, ("analytic", "trajectory"))
    assert needle in str(err.value) and "allowed" in str(err.value)


@pytest.mark.parametrize("changes,needle", [
    ({"size": {"variant": "tides"}}, "one of"),
    ({"size": {"variant": "none"}}, "drop effect size"),
    ({"target": {"rho": 2440.0, "fc": 48.0e6, "strength": {"value": 6.0}}}, "{law: li_chen}"),
])
def test_a_variant_the_study_cannot_give_this_scene_is_refused(tmp_path, changes, needle):
    from penetration.tasks.common import scene_from_inputs
    inputs = scene_inputs(tmp_path, {**plain_scene(0.07, 81.1), **changes})
    with pytest.raises(SceneError, match="allowed") as err:
        scene_from_inputs(inputs, ("analytic", "trajectory"), size=SIZE_PARAMS)
    assert needle in str(err.value)


def fe_scene(size, effects=("strain_rate", "damage", "strength_cap")):
    data = {"description": "an fe shot", "projectile": {"mass": 81.1, "radius": 0.07},
            "noses": {"crh3": {"kind": "ogive", "psi": 3.0}},
            "target": {"rho": 2440.0, "fc": 48.0e6}, "velocities": [800.0], "level": "fe",
            "effects": ["erosion", *effects] + (["size"] if size else []), "fe": {"erosion_strain": "calibrated"}}
    if size:
        data["size"] = {"variant": "rate_fracture"}
    return data


def fe_sized_scene(tmp_path, size, effects=("strain_rate", "damage", "strength_cap")):
    from penetration.pipeline.io import committed_study
    from penetration.pipeline.scenes import sized
    path = tmp_path / f"fe_{size}.yaml"
    path.write_text(yaml.safe_dump(fe_scene(size, effects)))
    sc = resolve(f"fe_{size}", read_scene(path, SCHEMA, ("fe",)), {}, {}, {})
    if not size:
        return sc
    params = synthetic_calibration(tmp_path, "fe", "rate_fracture", 1.7)
    return sized(sc, {**params, "calibration": committed_study(params["calibration"]).to_dict("records")})


def test_an_fe_scene_with_the_size_effect_gets_its_failure_strain_the_rate_law_and_the_crack_band(tmp_path):
    """The failure strain the study fitted with the variant (here a synthetic 1.7), MC2010's rate law in the material
    and EFMIN = 2 G_F / (T h), G_F = 73 fcm^0.18 N/m (MC2010 Eq 5.1-9), at the study's mesh; without the effect,
    Table 1's material untouched; at another mesh than the study's, refused."""
    from penetration.fe.level import scene_spec
    refs = reference.load_reference(ROOT / CFG["reference"])
    cal = {"element_size": CFG["fe"]["profiles"]["ci"]["element_size"], "fs": 1.2}
    specs, notes = {}, {}
    for size in (False, True):
        sc = fe_sized_scene(tmp_path, size)
        specs[size], notes[size] = scene_spec(sc, "crh3", 800.0, refs, CFG["concrete"], CFG["fe"], "ci", 3.0, cal)
    assert notes[False]["failure_strain"] == 1.2 and notes[True]["failure_strain"] == 1.7
    assert "with the scale effect" in notes[True]["failure_strain_provenance"]
    with pytest.raises(ValueError, match="allowed.*the ci profile"):
        scene_spec(fe_sized_scene(tmp_path, True), "crh3", 800.0, refs, CFG["concrete"], CFG["fe"], "full", 3.0, cal)
    plain, sized = specs[False].material, specs[True].material
    h = specs[True].settings.element_size
    assert h == pytest.approx(0.07 / CFG["fe"]["profiles"]["ci"]["elements_across"])
    assert plain.rate_law == "hjc" and sized.rate_law == "mc2010_extrapolate"
    assert sized.efmin == pytest.approx(2.0 * 73.0 * 48.0 ** 0.18 / (sized.T * h), rel=1e-12)
    assert dataclasses.replace(sized, rate_law="hjc", efmin=plain.efmin) == plain


def test_a_scene_that_would_drop_the_rate_mechanism_is_refused(tmp_path):
    """HJC carries MC2010's factor in its strain-rate term: a cavity or fe scene with a rate variant but without the
    strain_rate effect would silently run without it."""
    with pytest.raises(SceneError, match="without strain_rate; allowed: list strain_rate"):
        fe_sized_scene(tmp_path, True, effects=("damage", "strength_cap"))


def test_a_cavity_scene_with_the_size_effect_builds_its_table_from_the_sized_material(tmp_path, monkeypatch):
    """The cavity scene's own sigma_n table is built from Table 1's concrete at the strength scale the study fitted
    with the variant (a synthetic 0.8 here, in place of DO1's) times Bazant's factor at the scene's calibre, with
    MC2010's rate law (the sigma_n solve itself is tested elsewhere)."""
    import penetration.tasks.cavity as tasks_cavity

    class Reached(Exception):
        pass

    seen = {}

    def capture(material, *args, **kw):
        seen["material"] = material
        raise Reached

    monkeypatch.setattr(tasks_cavity, "sigma_table", capture)
    data = {**{k: v for k, v in fe_scene(True).items() if k != "fe"}, "level": "cavity",
            "effects": ["cavity", "strain_rate", "damage", "strength_cap", "size"],
            "target": {"rho": 2440.0, "fc": 48.0e6, "strength": {"law": "li_chen"}}}
    inputs = scene_inputs(tmp_path, data)
    (tmp_path / "cal.json").write_text(json.dumps({"strength_scale": 0.5}))   # DO1's: not used with the effect
    inputs.cal = str(tmp_path / "cal.json")
    params = SimpleNamespace(cfg=CFG["cavity"], hjc=CFG["concrete"], rtol=CFG["cavity"]["rtol"],
                             size=synthetic_calibration(tmp_path, "cavity", "rate_fracture", 0.8))
    with pytest.raises(Reached):
        dispatch.run("scene_cavity", str(PKG / "tasks/cavity.py"), inputs, SimpleNamespace(), params)
    refs = reference.load_reference(ROOT / CFG["reference"])
    k = 1.0 / math.sqrt(1.0 + 0.14 / (25.0 * 0.016))
    want = dataclasses.replace(concrete.configured(refs, CFG["concrete"], strength_scale=0.8 * k),
                               rate_law="mc2010_extrapolate")
    assert seen["material"] == want
