"""What several stages' tasks read: scenes resolved against the result files of a rule's inputs."""
from __future__ import annotations

from ..io import load_json, read_inference
from ..scenes import read_scene, resolve, scene_name

CALIBRATIONS = ("do1", "table3_calc")
PLAIN = ("analytic", "trajectory")  # the levels of workflow/scenes/*.yaml
CAVITY = ("cavity",)  # workflow/scenes/cavity/*.yaml


def projectile(refs, ids):
    """Steel density and DO1 shank radius (SI) from the reference ids of the config's ``projectile``."""
    return refs[ids["density"]].si, 0.5 * refs[ids["diameter"]].si


def scene_from_inputs(inputs, levels, placeholder_diameter=None):
    """The rule's scene (``inputs.scene``) resolved with the inferred noses, calibrations and diameter it names.

    ``levels``: the model levels the calling rule runs; a scene of another level is refused.
    ``placeholder_diameter`` stands in for the inferred 450 kg diameter in the
    rule that infers it (only the scale-free N* of its noses is used there).
    """
    noses = {"table4_do1": read_inference(inputs.do1)["nose"], "fig4_design": read_inference(inputs.fig4)["nose"]}
    cal = {k: load_json(getattr(inputs, f"cal_{k}")) for k in CALIBRATIONS if hasattr(inputs, f"cal_{k}")}
    diam = {"diameter_450kg": {"diameter": placeholder_diameter}} if placeholder_diameter else {}
    if hasattr(inputs, "diameter"):
        diam["diameter_450kg"] = load_json(inputs.diameter)
    return resolve(scene_name(inputs.scene), read_scene(inputs.scene, inputs.schema, levels), noses, cal, diam)
