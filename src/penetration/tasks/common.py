"""What several stages' tasks read: scenes resolved against the result files of a rule's inputs, the reference
values of the projectile and the DO1 shot, and the committed rows of the DO1 calibrations."""
from __future__ import annotations

from ..pipeline.io import committed_study, load_json, read_inference
from ..pipeline.scenes import SceneError, read_scene, resolve, scene_name, sized

CALIBRATIONS = ("do1", "table3_calc")
PLAIN = ("analytic", "trajectory")  # the levels of workflow/scenes/*.yaml
CAVITY = ("cavity",)  # workflow/scenes/cavity/*.yaml


def projectile(refs, ids):
    """Steel density and DO1 shank radius (SI) from the reference ids of the config's ``projectile``."""
    return refs[ids["density"]].si, 0.5 * refs[ids["diameter"]].si


def do1_shot(refs, ids):
    """Mass, striking velocity and measured depth of the DO1 shot from the reference ids in ``ids``."""
    return tuple(refs[ids[q]].si for q in ("mass", "velocity", "depth"))


def realisation_factor(member, step, what, step_key, least=1):
    """The factor 1 + member x step on a shot's striking velocity that makes realisation ``member`` of its erosion
    chaos, both checked (``what``, ``step_key``: the names the errors give; ``least``: the first member allowed,
    1 where member 0 is the shot itself)."""
    member, step = int(member), float(step)
    if member < least:
        raise ValueError(f"{what} {member}; allowed: >= {least}" + (" (member 0 is the shot itself)" if least == 1 else ""))
    if not 0.0 < step <= 1e-6:
        raise ValueError(f"{step_key} = {step}; allowed: 0 < velocity_step <= 1e-6 (a realisation of the chaos, not a "
                         "change of the shot)")
    return 1.0 + member * step


def calibration_row(cal: dict, value_key: str, source: str) -> dict:
    """One row of a shipped calibration: the fitted quantity, its value, its data and its residual, and the file it
    comes from (the levels of the command line read these committed rows, so that they run from a fresh clone)."""
    data = cal["data"]
    return {"calibration": cal["calibration"], "fitted_quantity": cal["fitted_quantity"], "parameter": value_key,
            "value": cal[value_key], "residual_m": cal["residual_m"], "relative_residual": cal["relative_residual"],
            "measured_depth_m": data["measured_depth"], "striking_velocity_ms": data["vs"], "mass_kg": data["mass"],
            "nose": data["nose"], "source": source}


def scene_from_inputs(inputs, levels, placeholder_diameter=None, size=None):
    """The rule's scene (``inputs.scene``) resolved with the inferred noses, calibrations and diameter it names.

    ``levels``: the model levels the calling rule runs; a scene of another level is refused. ``size``: the rule's
    size param (dispatch.size_params) where its task applies the scale effect: a scene that lists the effect gets
    its variant and calibration (scenes.sized); a task without it refuses such a scene rather than ignore it.
    ``placeholder_diameter`` stands in for the inferred 450 kg diameter in the
    rule that infers it (only the scale-free N* of its noses is used there).
    """
    noses = {"table4_do1": read_inference(inputs.do1)["nose"], "fig4_design": read_inference(inputs.fig4)["nose"]}
    cal = {k: load_json(getattr(inputs, f"cal_{k}")) for k in CALIBRATIONS if hasattr(inputs, f"cal_{k}")}
    diam = {"diameter_450kg": {"diameter": placeholder_diameter}} if placeholder_diameter else {}
    if hasattr(inputs, "diameter"):
        diam["diameter_450kg"] = load_json(inputs.diameter)
    sc = resolve(scene_name(inputs.scene), read_scene(inputs.scene, inputs.schema, levels), noses, cal, diam)
    if sc.size_variant is None:
        return sc
    if not size:
        raise SceneError(f"{inputs.scene}: effects: size is listed, but this rule's task does not apply the scale "
                         "effect; allowed: drop size, or run the scene through its level's scene rule (scene, "
                         "scene_cavity, fe_shot)")
    return sized(sc, {**size, "calibration": committed_study(size["calibration"]).to_dict("records")})
