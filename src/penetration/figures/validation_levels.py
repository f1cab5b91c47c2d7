"""Validation per level: every level's predicted depth of the development shots against the measured one, scored
out of sample (the task: tasks.levels.validation_levels; the scoring: laboratory.summary_rows).

The analytic and trajectory levels take S from a published S(fc) law (fitted by its authors on data that include
Forrestal's series: not a clean out-of-sample score); the cavity and fe levels carry their DO1 calibrations over
(strength scale; failure strain on the mesh scaled to the shot), so every development shot is out of their sample;
the cavity level calibrated on the laboratory shots is scored on the shots its fold held out (leave one series out:
all 25; leave one fc group out inside the 2003 series: 17). Each row gives the residual's slopes, ln(predicted /
measured) against ln fc (over all shots, and inside the series) and against ln calibre, with 90 % intervals; the
calibre is the series (two calibres, one per series), so its slope is the series' offset as much as a size effect.
"""
from __future__ import annotations

import matplotlib
import numpy as np

from .common import figure, save

KEYS = ["shot_id", "mass_kg", "diameter_m", "nose_shape", "crh", "fc_MPa", "velocity_ms", "dop_m"]
TITLES = {"analytic": "analytic (Eq 9, S from {law})", "trajectory": "trajectory (S from {law})",
          "cavity": "cavity (HJC scaled to fc, DO1 strength scale)", "fe": "fe ({profile} mesh, DO1 failure strain)",
          "cavity_laboratory": "cavity (laboratory strength scale,\nleave one series out)",
          "fe_laboratory": "fe ({profile} mesh, laboratory failure\nstrain, leave one series out)"}


def validation_figure(shots, summary, path, dpi, law, profile):
    """Predicted against measured depth at each level (shots: the rows of validation_levels.csv); the cavity level
    twice, with its DO1 calibration and, out of sample, with the laboratory one; the fe level likewise where its
    laboratory calibration exists (the summary's rows by their ``predictions`` key)."""
    rows = summary.set_index("predictions")
    keys = [k for k in ("analytic", "trajectory", "cavity", "cavity_laboratory", "fe", "fe_laboratory") if k in rows.index]
    fig, axes = figure(len(keys), 3.4, 3.9)
    top = 1.1 * max(shots.dop_m.max(), max(shots[f"dop_{k}_m"].max() for k in keys))
    line = np.array([0, top])
    # one marker per projectile series (by calibre: its masses differ only by the shots' own scatter), colour by fc,
    # the main driver of the errors
    series = [f"{1e3 * d:.1f} mm, {shots.mass_kg[shots.diameter_m == d].min():.3g}-"
              f"{shots.mass_kg[shots.diameter_m == d].max():.3g} kg" for d in shots.diameter_m]
    norm = matplotlib.colors.Normalize(shots.fc_MPa.min(), shots.fc_MPa.max())
    for ax, key in zip(axes, keys):
        s = rows.loc[key]
        ax.fill_between(line, 0.8 * line, 1.2 * line, color="0.85", label="+-20 %")
        ax.plot(line, line, "k-", lw=0.8)
        for (name, g), mk in zip(shots.assign(series=series).groupby("series"), "os^dv<>ph*"):
            sc = ax.scatter(g.dop_m, g[f"dop_{key}_m"], c=g.fc_MPa, cmap="viridis", norm=norm, marker=mk, s=18,
                            edgecolors="black", linewidths=0.3, label=name)
        ax.text(0.04, 0.96, f"median |error| {100 * s.median_abs_rel_err:.1f} %\n90th pct |error| "
                f"{100 * s.p90_abs_rel_err:.1f} %\nmean error {100 * s.mean_rel_err:+.1f} %\nslope vs ln fc "
                f"{s.slope_ln_fc_within_series:+.2f} (in series)", transform=ax.transAxes, va="top", fontsize=6.5)
        ax.set(xlabel="measured DOP (m)", ylabel="predicted DOP (m)" if key == "analytic" else None, xlim=(0, top),
               ylim=(0, top), aspect="equal", title=TITLES[key].format(law=law, profile=profile))
        ax.title.set_fontsize(7.5)
    axes[-1].legend(loc="lower right", fontsize=6)
    fig.colorbar(sc, ax=list(axes), shrink=0.7, pad=0.01).set_label("target strength fc (MPa)", fontsize=8)
    fig.suptitle(f"{len(shots)} development shots at every level, each scored out of its calibration's sample",
                 fontsize=9)
    save(fig, path, dpi)
