"""Validation per level: every level's predicted depth of the development shots against the measured one.

Nothing is fitted to these shots: the analytic and trajectory levels take S
from a published S(fc) law, the cavity and fe levels carry their DO1
calibrations over (strength scale; failure strain on the mesh scaled to the
shot) with the HJC set scaled to each shot's fc.
"""
from __future__ import annotations

import matplotlib
import numpy as np
import pandas as pd

from ..io import task, write_csv
from .common import figure, save

LEVELS = ("analytic", "trajectory", "cavity", "fe")
KEYS = ["shot_id", "mass_kg", "diameter_m", "nose_shape", "crh", "fc_MPa", "velocity_ms", "dop_m"]
TITLES = {"analytic": "analytic (Eq 9, S from {law})", "trajectory": "trajectory (S from {law})",
          "cavity": "cavity (HJC scaled to fc, DO1 strength scale)", "fe": "fe ({profile} mesh, DO1 failure strain)"}


def _read(inputs):
    frames = {"analytic": pd.read_csv(inputs.analytic), "trajectory": pd.read_csv(inputs.trajectory),
              "cavity": pd.read_csv(inputs.cavity), "fe": pd.read_csv(inputs.fe)}
    base = frames["analytic"][KEYS].copy()
    for level, f in frames.items():
        if list(f.shot_id) != list(base.shot_id):
            raise ValueError(f"the {level} predictions do not list the shots of the analytic ones")
        base[f"dop_{level}_m"] = f.dop_pred_m.to_numpy()
        base[f"rel_err_{level}"] = f.dop_pred_m.to_numpy() / base.dop_m.to_numpy() - 1
    return base, frames


@task
def validation_levels(inputs, outputs, params):
    shots, frames = _read(inputs)
    write_csv(shots, outputs.csv)
    rows, timing = [], []
    for level in LEVELS:
        err = shots[f"rel_err_{level}"].to_numpy()
        rows.append({"level": level, "shots": len(err), "median_abs_rel_err": float(np.median(np.abs(err))),
                     "p90_abs_rel_err": float(np.percentile(np.abs(err), 90)), "mean_rel_err": float(np.mean(err)),
                     "within_10pct": int(np.sum(np.abs(err) < 0.1))})
        if "wall_time_s" in frames[level]:
            w = frames[level].wall_time_s.to_numpy()
            timing.append({"level": level, "profile": params.profile, "shots": len(w), "total_wall_time_s": float(w.sum()),
                           "median_wall_time_per_shot_s": float(np.median(w)), "max_wall_time_per_shot_s": float(w.max())})
    summary = pd.DataFrame(rows)
    write_csv(summary, outputs.summary)
    write_csv(pd.DataFrame(timing), outputs.timing)
    validation_figure(shots, summary, outputs.png, params.dpi, params.law, params.profile)


def validation_figure(shots, summary, path, dpi, law, profile):
    """Predicted against measured depth at each level (shots: the rows of validation_levels.csv)."""
    fig, axes = figure(4, 3.6, 3.9)
    top = 1.1 * max(shots.dop_m.max(), max(shots[f"dop_{lv}_m"].max() for lv in LEVELS))
    line = np.array([0, top])
    # one marker per projectile series (by calibre: its masses differ only by the shots' own scatter), colour by fc,
    # the main driver of the errors
    series = [f"{1e3 * d:.1f} mm, {shots.mass_kg[shots.diameter_m == d].min():.3g}-"
              f"{shots.mass_kg[shots.diameter_m == d].max():.3g} kg" for d in shots.diameter_m]
    norm = matplotlib.colors.Normalize(shots.fc_MPa.min(), shots.fc_MPa.max())
    for ax, level, s in zip(axes, LEVELS, summary.itertuples()):
        ax.fill_between(line, 0.8 * line, 1.2 * line, color="0.85", label="+-20 %")
        ax.plot(line, line, "k-", lw=0.8)
        for (name, g), mk in zip(shots.assign(series=series).groupby("series"), "os^dv<>ph*"):
            sc = ax.scatter(g.dop_m, g[f"dop_{level}_m"], c=g.fc_MPa, cmap="viridis", norm=norm, marker=mk, s=18,
                            edgecolors="black", linewidths=0.3, label=name)
        ax.text(0.04, 0.96, f"median |error| {100 * s.median_abs_rel_err:.1f} %\n90th pct |error| "
                f"{100 * s.p90_abs_rel_err:.1f} %\nmean error {100 * s.mean_rel_err:+.1f} %", transform=ax.transAxes,
                va="top", fontsize=7)
        ax.set(xlabel="measured DOP (m)", ylabel="predicted DOP (m)" if level == "analytic" else None, xlim=(0, top),
               ylim=(0, top), aspect="equal", title=TITLES[level].format(law=law, profile=profile))
        ax.title.set_fontsize(8)
    axes[-1].legend(loc="lower right", fontsize=6)
    fig.colorbar(sc, ax=list(axes), shrink=0.7, pad=0.01).set_label("target strength fc (MPa)", fontsize=8)
    fig.suptitle(f"{len(shots)} development shots at every level (nothing fitted to them)", fontsize=9)
    save(fig, path, dpi)
