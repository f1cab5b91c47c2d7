"""Task of the nose-shape contrasts: depth ratios and gains between noses at every model level.

The paper's conclusions are contrasts between noses (the double ogive
against CRH 4.5, its equivalent nose of the same length, and against
CRH 3), not absolute depths. This task gathers them from the paper's two
Table 3 columns and from every level of ours, at Table 3's velocities and
over Fig 15's sweep. The cavity level's calibration variants are a study of their own
(figures/cavity_variant_contrasts.csv, written with figures/cavity_table3_sensitivity.csv).
"""
from __future__ import annotations

import pandas as pd

from ..analytic.trajectory import assemble, integrate
from ..nose.nstar import nstar
from ..pipeline.io import committed_studies, committed_study, task, write_csv, write_text
from .common import PLAIN, scene_from_inputs

# (name, numerator nose, denominator nose): the paper's claims and the CRH contrast
CONTRASTS = (("DO/CRH 4.5", "double_ogive", "crh45"), ("DO/CRH 3", "double_ogive", "crh3"),
             ("CRH 4.5/CRH 3", "crh45", "crh3"))


def contrast_rows(depths, level, variant, source):
    """Rows of every contrast at every velocity; ``depths``: {(nose, velocity): depth in m}."""
    rows = []
    for v in sorted({v for _, v in depths}):
        for name, a, b in CONTRASTS:
            if (a, v) in depths and (b, v) in depths:
                da, db = depths[(a, v)], depths[(b, v)]
                rows.append({"level": level, "variant": variant, "source": source, "velocity": v, "contrast": name,
                             "ratio": da / db, "gain_m": da - db})
    return rows


@task
def nose_contrasts_data(inputs, outputs, params):
    """Contrasts of the paper's columns, Eq 9 (calibrated and stated S), the trajectory engine and the cavity level."""
    t3 = pd.read_csv(inputs.table3)
    col = lambda c: {(r.nose, float(r.velocity_ms)): getattr(r, c) for r in t3.itertuples()}
    rows = (contrast_rows(col("paper_sim_m"), "paper", "simulation (LS-DYNA, fs calibrated on DO1)", "table3")
            + contrast_rows(col("paper_calc_m"), "paper", "calculation (Eq 9)", "table3")
            + contrast_rows(col("analytic_m"), "analytic", "Eq 9, S calibrated on DO1", "table3")
            + contrast_rows(col("analytic_stated_S_m"), "analytic", "Eq 9, S = 72 fc^-0.5", "table3")
            + contrast_rows(col("cavity_m"), "cavity", "strength scale calibrated on DO1", "table3"))
    fig15 = pd.read_csv(inputs.fig15)
    rows += contrast_rows({(r.nose, r.velocity): r.dop for r in fig15.itertuples()}, "analytic",
                          "Eq 9, S calibrated on DO1", "fig15")
    sc = scene_from_inputs(inputs, PLAIN)
    engine = {}
    for name, nose in sc.noses.items():
        n = nstar(nose)
        for v in sc.velocities:
            tr = integrate(assemble(sc.effects, nose, n, sc.mass, sc.target, v), sc.mass, v, rtol=params.rtol)
            engine[(name, float(v))] = tr.depth
    rows += contrast_rows(engine, "trajectory", "Eq 7/8 integrated, S calibrated on DO1", "fig15")
    cav = pd.read_csv(inputs.cavity_fig15)
    rows += contrast_rows({(r.nose, r.velocity): r.cavity_dop for r in cav.itertuples()}, "cavity",
                          "strength scale calibrated on DO1", "fig15")
    write_csv(pd.DataFrame(rows), outputs.csv)


@task
def cavity_variant_contrasts(inputs, outputs, params):
    """The study of the cavity level's calibration variants, as contrasts: every contrast of Table 3 under each
    variant (rows of results/cavity/calibration_variants.csv) and, per (contrast, velocity), their range."""
    variants = pd.read_csv(inputs.variants)
    rows = []
    for name, g in variants.groupby("variant", sort=False):
        rows += contrast_rows({(r.nose, r.velocity): r.cavity_m for r in g.itertuples()}, "cavity variant",
                              f"{name} ({g.calibrated.iloc[0]} calibrated on DO1)", "table3")
    rng = pd.DataFrame(rows).groupby(["contrast", "velocity"], sort=False).agg(
        variants=("ratio", "size"), min_ratio=("ratio", "min"), max_ratio=("ratio", "max"),
        min_gain_m=("gain_m", "min"), max_gain_m=("gain_m", "max")).reset_index()
    write_csv(rng, outputs.csv)


@task
def verdict(inputs, outputs, params):
    """The verdict on the paper's nose contrasts, one table (paper.verdict), from the nose-contrast table of the
    paper's build and the studies' committed outputs (params: path and digest; a missing one gives pending rows: the
    chaos and unstated-input studies come one velocity and target at a time)."""
    from ..paper.verdict import verdict_rows

    sensitivity = committed_study(params.sensitivity)   # a missing one says how to build it
    table = verdict_rows(pd.read_csv(inputs.table), sensitivity, committed_studies([params.eroding]),
                         committed_studies(params.chaos), committed_studies(params.unstated), params.provenance,
                         tuple(float(v) for v in params.free_velocities))
    write_csv(table, outputs.csv)
    # the same table and paragraph as the README's generated block, for the report (which imports no package code)
    from ..pipeline.docs import verdict as verdict_block
    with open(outputs.csv) as f:
        text = f.read()
    write_text(outputs.md, verdict_block(lambda _path: text))
