"""The scale effect (concrete.size) and how the levels take it: each mechanism is its published relation at the
level's rate and calibre; without the effect the closed form is scale-free (geometrically similar shots reach the
same depth over calibre, dimensional analysis), with it a larger calibre goes more calibres deep."""
import numpy as np
import pytest

from penetration.analytic.dop import penetration_depth
from penetration.analytic.resistance import Target, strength_factor
from penetration.concrete import scale
from penetration.concrete.size import SIZE_MECHANISMS, SizeEffect, resistance_factor
from penetration.errors import ParameterError
from penetration.nose.geometry import Ogive
from penetration.nose.nstar import nstar
from penetration.shots.ladder import Context, UserShot, run

FC, RHO = 40e6, 2300.0


def similar_shot(d, v=450.0):
    """CRH 3, 8 calibres long at the DO1 projectile's density ratio: mass as d^3."""
    return UserShot(Ogive(3.0, d / 2), 81.1 * (d / 0.14) ** 3, v, FC, RHO)


@pytest.mark.parametrize("name", sorted(SIZE_MECHANISMS))
def test_each_mechanism_is_its_published_relation(name):
    e = SizeEffect(mechanisms=(name,), beyond="extrapolate", aggregate=0.016)
    d, v = np.array([0.0269, 0.0762, 0.14]), np.array([600.0, 300.0, 835.0])
    rate = v / d   # 2.2e4, 3.9e3, 6.0e3 1/s: MC2010's cube-root branch (above 30 1/s), extrapolated beyond 300 1/s
    expected = {"rate": 0.012 * (rate / 30e-6) ** (1 / 3),                # fib MC2010 Eq 5.1-50
                "fracture": (1 + d / (25.0 * 0.016)) ** -0.5}[name]       # Bazant, D0 = lambda0 d_a
    np.testing.assert_allclose(resistance_factor(e, d, v), expected, rtol=1e-14)


def test_the_factor_is_the_product_of_the_mechanisms_and_one_without_the_effect():
    e = SizeEffect(mechanisms=("rate", "fracture"))
    both = resistance_factor(e, 0.076, 300.0)
    assert both == pytest.approx(resistance_factor(e, 0.076, 300.0, ["rate"]) * resistance_factor(e, 0.076, 300.0,
                                                                                                  ["fracture"]))
    assert resistance_factor(None, 0.076, 300.0) == 1.0


def test_without_the_effect_the_closed_form_is_scale_free():
    ctx = Context()
    x = [run(similar_shot(d), "analytic", ctx).depth_m / d for d in (0.01, 0.05, 0.25)]
    np.testing.assert_allclose(x, x[0], rtol=1e-12)


@pytest.mark.parametrize("mechanisms", [("fracture",), ("rate",), ("rate", "fracture")])
def test_with_the_effect_a_larger_calibre_goes_more_calibres_deep(mechanisms):
    ctx = Context(size=SizeEffect(mechanisms=mechanisms, beyond="extrapolate"))
    x = [run(similar_shot(d), "analytic", ctx).depth_m / d for d in (0.01, 0.05, 0.25)]
    assert np.all(np.diff(x) > 0)


def test_the_analytic_level_is_eq9_with_the_scaled_s():
    """Eq 9 with S times the calibration factor and the effect's factor, computed here directly."""
    shot = similar_shot(0.0762, 312.5)
    e = SizeEffect(mechanisms=("rate", "fracture"), beyond="cap", aggregate=0.008)
    ctx = Context(size=e, strength_factor_scale=0.7)
    S = strength_factor(FC) * 0.7 * resistance_factor(e, 0.0762, 312.5)
    expected = penetration_depth(shot.mass, shot.nose.radius, nstar(shot.nose), Target(RHO, FC, S), 312.5)
    assert run(shot, "analytic", ctx).depth_m == pytest.approx(float(expected), rel=1e-12)
    assert run(shot, "trajectory", ctx).depth_m == pytest.approx(float(expected), rel=1e-6)


def test_the_simulation_levels_carry_the_rate_mechanism_in_their_material():
    """The cavity and fe levels take MC2010's factor at each point's rate (the material's rate law), the cavity level
    the fracture factor on its strength scale."""
    from penetration.shots.ladder import cavity_material, fe_material
    shot = similar_shot(0.05)
    e = SizeEffect(mechanisms=("rate", "fracture"), beyond="cap", aggregate=0.01)
    ctx = Context(size=e, strength_scale=0.8)
    m = cavity_material(shot, ctx)
    assert m.rate_law == "mc2010_cap"
    plain = cavity_material(shot, Context(strength_scale=0.8))
    assert plain.rate_law == "hjc"
    assert m.strength_scale == pytest.approx(plain.strength_scale * float(scale.size_effect_factor(0.05, 0.25)))
    assert fe_material(shot, Context(size=SizeEffect(mechanisms=("rate",)))).rate_law == "mc2010_extrapolate"


def test_the_crack_band_dissipates_the_fracture_energy_whatever_the_element_size():
    """Linear softening from f_t to zero at the crack band's strain over a band of one element: h f_t eps / 2 = G_F
    for every h (Bazant & Oh 1983); only the fracture mechanism changes EFMIN."""
    from penetration.concrete.hjc import HJC
    from penetration.concrete.size import crack_band_strain, regularised
    m = HJC()
    for h in (0.001, 0.00875, 0.05):
        eps = crack_band_strain(m, h)
        assert h * m.T * eps / 2 == pytest.approx(float(scale.fracture_energy_mc2010(m.fc)), rel=1e-12)
    assert regularised(m, SizeEffect(mechanisms=("fracture",)), 0.00875).efmin == crack_band_strain(m, 0.00875)
    assert regularised(m, SizeEffect(mechanisms=("rate",)), 0.00875) is m
    assert regularised(m, None, 0.00875) is m
    with pytest.raises(ParameterError, match="element_size"):
        crack_band_strain(m, 0.0)


@pytest.mark.parametrize("fields, name", [({"mechanisms": ("size",)}, "mechanisms"), ({"mechanisms": ()}, "mechanisms"),
                                          ({"beyond": "clip"}, "beyond"), ({"aggregate": 0.5}, "aggregate"),
                                          ({"lambda0": 0.0}, "lambda0")])
def test_bad_settings_name_the_field(fields, name):
    with pytest.raises(ParameterError, match=name):
        SizeEffect(**fields)


def test_split_summary_reads_each_series_fit_and_pools_the_held_out_errors():
    import pandas as pd
    from penetration.studies.scale import VARIANT, split_summary
    v = {c: "" for c in VARIANT}
    v["variant"] = "none"
    fits = pd.DataFrame([{"level": "analytic", **v, "parameter": "s_scale", "fold": f, "fit_series": s, "value": x}
                         for f, s, x in (("all", "a;b", 0.9), ("series:a", "b", 1.0), ("series:b", "a", 0.5))])
    preds = pd.DataFrame([{"level": "analytic", "variant": "none", "fold": f"series:{s}", "series": s, "rel_error": e}
                          for s, e in (("a", 0.1), ("a", -0.3), ("b", 0.2), ("b", 0.0))] +
                         [{"level": "analytic", "variant": "none", "fold": "fc_group:a:x", "series": "a", "rel_error": 9.0}])
    do1 = pd.DataFrame([{"level": "analytic", "variant": "none", "dop_pred_m": 4.0, "rel_error": 4.0 / 5.1 - 1}])
    row = split_summary(fits, preds, do1, ["a", "b"]).iloc[0]
    assert row.value_a == 0.5 and row.value_b == 1.0 and row.split_ratio == 2.0
    assert row.loso_shots == 4 and row.loso_median_abs_rel_err == pytest.approx(0.15)
    assert row.mean_rel_err_a == pytest.approx(-0.1) and row.do1_pred_m == 4.0


def test_do1_gap_gives_each_step_as_a_ratio_and_a_power_of_calibre():
    """Hand values: a factor 1.0 at 20 mm, 0.5 at 80 mm and 0.25 at 320 mm halves with each fourfold calibre, a power
    -1/2 on both steps; Bazant's law over the same calibres is its closed form (1 + d/D0)^(-1/2) by hand."""
    from penetration.studies.scale import do1_gap
    points = {"b": (0.08, 300.0), "a": (0.02, 600.0), "do1": (0.32, 800.0)}
    effect = SizeEffect(mechanisms=("fracture",), aggregate=0.016, lambda0=25.0)
    bazant = {p: (1 + d / 0.4) ** -0.5 for p, (d, _) in points.items()}
    values = [{"kind": "level", "name": "x", "value_a": 1.0, "value_b": 0.5, "value_do1": 0.25},
              {"kind": "mechanism", "name": "fracture",
               **{f"value_{p}": float(resistance_factor(effect, d, v)) for p, (d, v) in points.items()}}]
    out = do1_gap(values, points).set_index("name")
    assert out.loc["x", "ratio_series"] == pytest.approx(0.5) and out.loc["x", "ratio_do1"] == pytest.approx(0.5)
    assert out.loc["x", "exponent_series"] == pytest.approx(-0.5) and out.loc["x", "exponent_do1"] == pytest.approx(-0.5)
    assert out.loc["x", "series_trend_at_do1"] == pytest.approx(0.25)
    assert out.loc["fracture", "ratio_do1"] == pytest.approx(bazant["do1"] / bazant["b"], rel=1e-12)
    assert out.loc["fracture", "ratio_series"] == pytest.approx(bazant["b"] / bazant["a"], rel=1e-12)
    assert out.loc["x", "calibre_a_m"] == 0.02 and out.loc["x", "velocity_do1_ms"] == 800.0
    with pytest.raises(ValueError, match="two laboratory series"):
        do1_gap(values, {"a": (0.02, 1.0), "do1": (0.32, 1.0)})


def test_the_fe_level_applies_the_crack_band_at_its_scaled_element_size():
    from penetration.concrete.size import crack_band_strain
    from penetration.shots.ladder import fe_material, fe_spec
    shot = UserShot(Ogive(3.0, 0.0269 / 2), 0.9, 600.0, FC, RHO, length=0.2424)
    ctx = Context(size=SizeEffect(mechanisms=("fracture",)), failure_strain=1.6)
    spec, k = fe_spec(shot, ctx)
    assert k == pytest.approx(0.0269 / 2 / 0.07)
    assert spec.material.efmin == crack_band_strain(fe_material(shot, ctx), spec.settings.element_size)
    plain, _ = fe_spec(shot, Context(failure_strain=1.6))
    assert plain.material.efmin == fe_material(shot, ctx).efmin


def test_the_similarity_figures_shots_are_geometrically_similar_to_do1():
    """Each shot of the similarity study has DO1's mass over calibre cubed and its length over calibre (Table 2:
    81.1 kg, 140 mm, 1.13 m), so that at the DO1 calibre it is DO1's projectile with a CRH 3 nose."""
    from pathlib import Path

    import yaml

    from penetration.paper import reference
    from penetration.tasks.scale import similar_shots
    root = Path(__file__).resolve().parents[1]
    cfg = yaml.safe_load((root / "workflow/config.yaml").read_text())
    spec = {**cfg["scale_effect"]["similarity"], "calibres": [0.01, 0.14, 0.25]}
    shots = similar_shots(spec, reference.load_reference(root / cfg["reference"]))
    for s, d in zip(shots, spec["calibres"]):
        assert 2 * s.nose.radius == pytest.approx(d, rel=1e-14)
        assert s.mass / d ** 3 == pytest.approx(81.1 / 0.14 ** 3, rel=1e-12)
        assert s.length / d == pytest.approx(1.13 / 0.14, rel=1e-12)
    assert shots[1].mass == pytest.approx(81.1, rel=1e-12) and shots[1].length == pytest.approx(1.13, rel=1e-12)


@pytest.mark.parametrize("level", ["analytic", "cavity", "fe"])
def test_every_committed_fit_of_the_scale_effect_lies_inside_its_grid(level):
    """A least-squares factor found at a grid's end is a bound, not a fit: each committed calibration of the scale
    effect's study (every variant and fold) lies strictly between its grid's first and last values (the config's
    grid for the level and variant)."""
    from pathlib import Path

    import pandas as pd
    import yaml
    root = Path(__file__).resolve().parents[1]
    path = root / f"figures/scale/calibration_{level}.csv"
    if not path.is_file():
        pytest.skip(f"{path.name} not built")
    from penetration.pipeline.config import scale_grid
    cfg = yaml.safe_load((root / "workflow/config.yaml").read_text())
    fits = pd.read_csv(path)
    assert not fits.at_grid_edge.any(), fits[fits.at_grid_edge]
    for variant, g in fits.groupby("variant"):
        grid = scale_grid(cfg, level, variant)
        assert ((g.value > min(grid)) & (g.value < max(grid))).all(), (variant, list(g.value), grid)
