"""Outputs of the finite-element level: Table 3's fe column, Figs 12-15, nose contrasts, DO1 fields, mesh study.

Every task reads the per-shot results of ``tasks.fe`` (JSON summaries and
binned histories) and writes under figures/fe/{profile}/.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import yaml

from ..io import committed_study, load_json, task, write_csv, write_json
from ..reference import TABLE3_NOSES, UNITS, load_reference
import matplotlib.pyplot as plt

from .common import PAPER_STYLE, color, do1_histories, figure, save

G0 = UNITS["g"]
LABELS = {"double_ogive": "double ogive", "crh45": "CRH 4.5", "crh3": "CRH 3", "minimum_nstar": "minimum N*"}


def _shots(paths):
    """Summaries of the shots (JSON paths) as a frame, with the histories path of each."""
    rows = [load_json(p) | {"json": str(p)} for p in paths]
    return pd.DataFrame(rows)


def _histories(json_path):
    return pd.read_csv(json_path.replace(".json", "_histories.csv"))


@task
def fe_table3(inputs, outputs, params):
    """Table 3 at the FE level: depth per cell, deviation from the paper's simulation, the nose ratios.

    Each cell carries its distance from the DO1 calibration (inputs.cal): whether its nose is the calibration
    shot's (the scene's nose inferred as the shot's) and its velocity minus the shot's. A cell of the calibrated
    nose near the shot's velocity agrees largely by construction.
    """
    refs = load_reference(inputs.reference)
    shots = _shots(inputs.shots)
    cal = load_json(inputs.cal)["data"]
    noses = yaml.safe_load(Path(inputs.scene).read_text())["noses"]
    calibrated = {n for n, spec in noses.items() if spec.get("inferred") == cal["nose"]}
    rows = []
    for _, s in shots.sort_values(["velocity", "nose"]).iterrows():
        v = int(round(s.velocity))
        paper = refs[f"table3.sim.{v}.{s.nose}"].si
        rows.append({"velocity_ms": v, "nose": s.nose, "fe_m": s.depth_m, "paper_sim_m": paper,
                     "rel_dev_fe_vs_paper_sim_pct": 100 * (s.depth_m / paper - 1),
                     "within_5pct_goal": abs(s.depth_m / paper - 1) <= 0.05,
                     "calibration_nose": s.nose in calibrated, "velocity_minus_calibration_ms": v - cal["vs"],
                     "time_to_rest_s": s.time_to_rest_s,
                     "peak_deceleration_m_s2": s.peak_deceleration_m_s2, "eroded_mass_kg": s.eroded_mass_kg,
                     "tunnel_eroded_share": s.tunnel_eroded_share,
                     "energy_error_max": s.energy_error_max,
                     "hourglass_over_internal": s.hourglass_over_internal, "element_steps": s.element_steps, "failure_strain": s.failure_strain, "element_size_m": s.element_size})
    t = pd.DataFrame(rows)
    ratios = []
    for v, g in t.groupby("velocity_ms"):
        d = g.set_index("nose")
        for name, num, den in (("DO/CRH 4.5", "double_ogive", "crh45"), ("CRH 4.5/CRH 3", "crh45", "crh3"),
                               ("DO/CRH 3", "double_ogive", "crh3")):
            ours, paper = d.fe_m[num] / d.fe_m[den], d.paper_sim_m[num] / d.paper_sim_m[den]
            ratios.append({"velocity_ms": v, "contrast": name, "fe_ratio": ours, "paper_sim_ratio": paper,
                           "difference_points": 100 * (ours - paper), "within_2_points_goal": abs(ours - paper) <= 0.02,
                           "fe_gain_m": d.fe_m[num] - d.fe_m[den], "paper_sim_gain_m": d.paper_sim_m[num] - d.paper_sim_m[den]})
    write_csv(t, outputs.csv)
    write_csv(pd.DataFrame(ratios), outputs.ratios)


@task
def fe_fig12(inputs, outputs, params):
    """Fig 12 at the FE level: DO1 velocity and Pd/d against time, with the experiment."""
    refs = load_reference(inputs.reference)
    s = load_json(inputs.shot)
    h = _histories(inputs.shot)
    d = refs["table2.diameter"].si
    data = pd.DataFrame({"t_ms": h.t * 1e3, "velocity": h.velocity, "pd_over_d": h.depth / d})
    write_csv(data, outputs.csv)
    fig = do1_histories(data.t_ms, data.pd_over_d, data.velocity, refs, "FE level",
                        f"Fig 12 (FE): DO1, fs = {s['failure_strain']:.3g} calibrated on this shot, "
                        f"h = {s['element_size'] * 1e3:.3g} mm", (0, max(18, data.t_ms.max() * 1.05)))
    save(fig, outputs.png, params.dpi)


@task
def fe_fig13(inputs, outputs, params):
    """Fig 13 at the FE level: the three projectiles (rigid analytic surfaces) over the target mesh near the nose."""
    d = pd.read_csv(inputs.meshes)
    h = float(d.element_size_m.iloc[0])
    mr, mz = d[d.kind == "mesh_r"].r, d[d.kind == "mesh_z"].z
    fig, axes = figure(3, 3.0, 4.6)
    rows = []
    for ax, (name, o) in zip(axes, d[d.kind == "outline"].groupby("nose", sort=False)):
        for rr in mr[mr <= 0.3]:
            ax.plot([rr, rr], [0, 0.45], color="0.75", lw=0.4)
        for zz in mz[mz <= 0.45]:
            ax.plot([0, 0.3], [zz, zz], color="0.75", lw=0.4)
        ax.fill_betweenx(o.z, 0, o.r, color=color(name), alpha=0.5)
        ax.plot(o.r, o.z, color=color(name))
        ax.set(xlim=(0, 0.3), ylim=(-0.5, 0.45), aspect="equal", xlabel="r (m)", title=LABELS[name])
        ax.invert_yaxis()
        rows.append({"nose": name, "nose_length_m": o.nose_length_m.iloc[0], "element_size_m": h,
                     "elements_across_radius": o.r.max() / h, "target_elements": int(d.target_elements.iloc[0])})
    axes[0].set_ylabel("z (m), target below 0 (tip at the surface)")
    fig.suptitle(f"Fig 13 (FE): rigid projectiles over the target mesh ({params.profile} profile, h = {h * 1e3:.3g} mm)",
                 fontsize=9)
    write_csv(pd.DataFrame(rows), outputs.csv)
    save(fig, outputs.png, params.dpi)


@task
def fe_fig14(inputs, outputs, params):
    """Fig 14 at the FE level: filtered deceleration histories (declared filter) and the peak against the cut-off."""
    refs = load_reference(inputs.reference)
    shots = _shots(inputs.shots)
    vs = sorted(shots.velocity.unique())
    fig, axes = figure(len(vs), 3.6, 3.6)
    rows, peaks = [], []
    for ax, v in zip(axes, vs):
        for _, s in shots[shots.velocity == v].iterrows():
            h = _histories(s.json)
            g_ = h.deceleration / G0
            # the resistance acts only while the projectile moves: the trace drops to zero at rest
            ax.plot(np.append(h.t * 1e3, s.time_to_rest_s * 1e3), np.append(g_, 0.0), color=color(s.nose), lw=1,
                    label=LABELS[s.nose])
            rows += [{"velocity": v, "nose": s.nose, "t_ms": a, "deceleration_g": b}
                     for a, b in zip(h.t.to_numpy()[::10] * 1e3, g_.to_numpy()[::10])]
            for fc, peak in s.peak_deceleration_by_cutoff.items():
                peaks.append({"velocity": v, "nose": s.nose, "cutoff_hz": float(fc), "peak_g": peak / G0})
            peaks.append({"velocity": v, "nose": s.nose, "cutoff_hz": math.inf,
                          "peak_g": s.peak_deceleration_unfiltered_bins / G0})
        gmax, tmax = refs[f"fig14.g_axis_max.{v:.0f}"].value, refs[f"fig14.t_axis_max.{v:.0f}"].value
        ax.plot([0, tmax, tmax], [gmax, gmax, 0], color="black", lw=0.8, ls=":", label="paper's axes")
        ax.set(xlabel="t (ms)", title=f"{v:.0f} m/s", ylim=(0, None))
        ax.legend(fontsize=6)
    axes[0].set_ylabel(f"deceleration (g), low-pass {shots.cutoff_hz.iloc[0] / 1e3:g} kHz")
    write_csv(pd.DataFrame(rows), outputs.csv)
    save(fig, outputs.png, params.dpi)
    p = pd.DataFrame(peaks)
    write_csv(p, outputs.cutoff_csv)
    fig, (ax,) = figure(1, 5.6, 4.0)
    for (v, nose), g_ in p[np.isfinite(p.cutoff_hz)].groupby(["velocity", "nose"]):
        ax.plot(g_.cutoff_hz / 1e3, g_.peak_g, color=color(nose), marker="o", ms=3, lw=0.8,
                alpha=0.4 + 0.6 * (v - min(vs)) / max(1, max(vs) - min(vs)), label=f"{LABELS[nose]} {v:.0f} m/s")
    ax.axvline(shots.cutoff_hz.iloc[0] / 1e3, color="black", lw=0.8, ls="--", label="declared cut-off")
    ax.set(xscale="log", xlabel="low-pass cut-off (kHz)", ylabel="peak deceleration (g)",
           title="Peak deceleration against the filter's cut-off (FE level)")
    ax.legend(fontsize=5, ncol=2)
    save(fig, outputs.cutoff_png, params.dpi)


@task
def fe_fig15(inputs, outputs, params):
    """Fig 15 at the FE level: Pd/d against striking velocity for four noses, with the paper's simulated points."""
    refs = load_reference(inputs.reference)
    shots = _shots(inputs.shots)
    d = refs["table2.diameter"].si
    data = shots[["nose", "velocity", "depth_m"]].assign(pd_over_d=shots.depth_m / d).sort_values(["nose", "velocity"])
    write_csv(data, outputs.csv)
    fig, (ax,) = figure(1, 6.2, 4.4)
    for nose, g in data.groupby("nose"):
        ax.plot(g.velocity, g.pd_over_d, color=color(nose), marker="o", ms=3, label=f"{LABELS[nose]} (ours, FE)")
    for nose in TABLE3_NOSES:
        pts = [(v, refs[f"table3.sim.{v}.{nose}"].si / d) for v in (500, 800, 1000, 1200)]
        ax.plot(*zip(*pts), **{**PAPER_STYLE, "color": color(nose)}, label=f"{LABELS[nose]} (paper's simulation, Table 3)")
    ax.plot([refs["table2.velocity"].si], [refs["table2.dop"].si / d], marker="*", ms=10, color="black", ls="none",
            label="experiment DO1")
    lim = committed_study(params.limit)
    for k, (nose, g) in enumerate(lim.groupby("nose")):
        ax.errorbar(g.velocity_ms + 12 * (k - 1), g.depth_at_zero_size_m / d,
                    yerr=[(g.depth_at_zero_size_m - g.interval_low_m) / d, (g.interval_high_m - g.depth_at_zero_size_m) / d],
                    fmt="s", ms=3, mfc="white", color=color(nose), capsize=2, lw=0.8,
                    label=f"{LABELS[nose]}: at zero element size, {100 * g.confidence.iloc[0]:.0f} % interval (a study)")
    ax.set(xlabel="striking velocity (m/s)", ylabel="Pd/d", xlim=(400, 1400), ylim=(0, 90),
           title=f"Fig 15 (FE level, {params.profile} mesh): failure strain calibrated on DO1")
    ax.legend(fontsize=6)
    save(fig, outputs.png, params.dpi)


@task
def fe_do1_fields(inputs, outputs, params):
    """DO1 at rest: crater and tunnel profile, damage and eroded elements (initial positions), eroded mass."""
    s = load_json(inputs.shot)
    f = pd.read_csv(inputs.fields)
    d = 0.14
    live = f[f.state.isin((1, 4))]  # material present (4: retired behind the moving window, fields as at retirement)
    rows = []
    for z0, g in f.groupby(f.z0.round(6)):
        lv = g[g.state.isin((1, 4))]
        rows.append({"z0": z0, "tunnel_radius_m": lv.r.min() if len(lv) else math.nan,
                     "eroded_to_radius0_m": g[g.state == 0].r0.max() if (g.state == 0).any() else 0.0})
    prof = pd.DataFrame(rows)
    write_csv(prof, outputs.csv)
    fig, axes = figure(3, 3.4, 6.0)
    ax = axes[0]
    ax.plot(prof.tunnel_radius_m / d, prof.z0 / d, color="tab:green", label="tunnel wall now (live material)")
    ax.plot(prof.eroded_to_radius0_m / d, prof.z0 / d, color="tab:red", lw=0.8, label="eroded out to (initial r)")
    ax.axvline(0.5, color="black", ls=":", lw=0.8, label="shank radius")
    ax.set(xlabel="r/d", ylabel="z/d (initial depth)", xlim=(0, 3), title="crater and tunnel")
    ax.invert_yaxis()
    ax.legend(fontsize=6)
    for ax, key, title, bar in ((axes[1], "damage", "HJC damage D", "D (1)"),
                                (axes[2], "eps_p", "equivalent plastic strain", "eps_p (1; top: the failure strain)")):
        sc = ax.scatter(live.r0 / d, live.z0 / d, c=live[key], s=1.5, cmap="viridis", vmin=0,
                        vmax=1.0 if key == "damage" else max(1e-9, s["failure_strain"] or 1.0), rasterized=True)
        er = f[f.state == 0]
        ax.scatter(er.r0 / d, er.z0 / d, color="tab:red", s=1.0, label=f"eroded ({s['eroded_mass_kg']:.0f} kg)", rasterized=True)
        ax.set(xlabel="r0/d", xlim=(0, 4), title=title)
        ax.invert_yaxis()
        ax.legend(fontsize=6, loc="lower right")
        fig.colorbar(sc, ax=ax, shrink=0.6).set_label(bar, fontsize=8)
    fig.subplots_adjust(wspace=0.45)
    fig.suptitle(f"DO1 at rest (FE level, depth {s['depth_m']:.2f} m): fields at the initial element positions "
                 f"(rows behind the moving window as they left it)", fontsize=9)
    save(fig, outputs.png, params.dpi)


@task
def fe_mesh_study(inputs, outputs, params):
    """Failure strain calibrated on DO1 at three element sizes: fs, depth, peak deceleration, wall time per size."""
    rows = []
    for p in inputs.calibrations:
        c = load_json(p)
        best = min(c["runs"], key=lambda r: abs(r["depth_m"] - c["data"]["measured_depth"]))
        rows.append({"element_size_m": c["element_size"], "elements_across_radius": c["elements_across_radius"],
                     "failure_strain": c["fs"], "depth_m": best["depth_m"], "residual_m": c["residual_m"],
                     "peak_deceleration_m_s2": best.get("peak_deceleration_m_s2", math.nan),
                     "wall_time_per_run_s": best["wall_time_s"], "runs": len(c["runs"]),
                     "calibration_wall_time_s": c["wall_time_s"], "converged": c["converged"]})
    t = pd.DataFrame(rows).sort_values("element_size_m", ascending=False)
    write_csv(t, outputs.csv)
    fig, axes = figure(2, 3.8, 3.4)
    axes[0].plot(t.elements_across_radius, t.failure_strain, marker="o", color="tab:green", label="ours (2-D, calibrated on DO1)")
    axes[0].axhline(0.38, color="black", ls="--", lw=0.8, label="paper's fs (its 3-D mesh)")
    axes[0].set(xlabel="elements across the shank radius", ylabel="failure strain fs", title="calibrated fs per mesh")
    axes[0].legend(fontsize=6)
    axes[1].plot(t.elements_across_radius, t.wall_time_per_run_s, marker="o", color="tab:blue")
    axes[1].set(xlabel="elements across the shank radius", ylabel="wall time of one DO1 run (s)", yscale="log",
                title="cost per DO1 run")
    save(fig, outputs.png, params.dpi)


@task
def fe_summary(inputs, outputs, params):
    """Audit and checks over every FE shot of a profile: energy errors, hourglass share, nose pressure, rear face;
    the DO1 shot's wall time goes to a timing file of its own (it changes from run to run, the summary does not)."""
    shots = _shots(inputs.shots)
    do1, block = load_json(inputs.do1), load_json(inputs.block)
    cal = load_json(inputs.cal)
    out = {"profile": params.profile, "element_size_m": cal["element_size"], "failure_strain": cal["fs"],
           "calibration_residual_m": cal["residual_m"], "shots": int(len(shots)),
           "energy_error_max": float(shots.energy_error_max.abs().max()),
           "hourglass_over_internal_max": float(shots.hourglass_over_internal.max()),
           "momentum_error_max": float(shots.momentum_error_final.abs().max()),
           "nose_pressure": load_json(inputs.pressure),
           "do1_depth_semi_infinite_m": do1["depth_m"], "do1_depth_block_m": block["depth_m"],
           "rear_face_effect_m": block["depth_m"] - do1["depth_m"],
           "do1_eroded_mass_kg": do1["eroded_mass_kg"], "do1_tunnel_eroded_share": do1["tunnel_eroded_share"],
           "do1_element_steps": do1["element_steps"],
           "do1_status": do1["status"], "block_status": block["status"]}
    write_json(out, outputs.json)
    # (no time per element-step: element_steps counts every element of the mesh at every step, and the moving
    # window computes only those near the nose; workflow/benchmarks/fe_speed.py times the step itself)
    write_json({"profile": params.profile, "element_size_m": cal["element_size"], "do1_wall_time_s": do1["wall_time_s"],
                "do1_steps": do1["steps"], "do1_mesh_elements": do1["elements"]}, outputs.timing)


@task
def fe_diff(inputs, outputs, params):
    """The FE level's rows of the diff (Table 3 cells and increments, 1200 m/s gains, Fig 14, DO1, fs) and a summary."""
    from .. import diff as D
    refs = load_reference(inputs.reference)
    t3 = pd.read_csv(inputs.table3).to_dict("records")
    ratios = pd.read_csv(inputs.ratios).to_dict("records")
    do1, cal = load_json(inputs.do1), load_json(inputs.cal)
    rows = D.fe_rows(refs, t3, ratios, do1["depth_m"], cal["fs"], cal["element_size"])
    rows += D.fe_limit_rows(refs, committed_study(params.limit).to_dict("records"))
    frame = pd.DataFrame([r.__dict__ for r in rows], columns=list(D.COLUMNS))
    write_csv(frame, outputs.csv)
    counts = ", ".join(f"{s} {int((frame.status == s).sum())}" for s in D.STATUSES)
    lines = [f"# FE level ({params.profile} profile, h = {cal['element_size'] * 1e3:.3g} mm, fs = {cal['fs']:.4g} "
             f"calibrated on DO1)", "", f"Status counts: {counts}", "",
             "| item | quantity | case | paper | ours | status |", "|---|---|---|---|---|---|"]
    lines += [f"| {r.item} | {r.quantity} | {r.case} | {r.paper:.4g} | {r.ours:.4g} | {r.status} |" for r in rows]
    from ..io import write_text
    write_text(outputs.summary, "\n".join(lines) + "\n")


@task
def fe_contrasts(inputs, outputs, params):
    """Nose contrasts at the FE level over Fig 15's sweep: depth ratios and gains of each pair of noses."""
    shots = _shots(inputs.shots)
    d = shots.pivot_table(index="velocity", columns="nose", values="depth_m")
    rows = []
    for name, num, den in (("DO/CRH 4.5", "double_ogive", "crh45"), ("DO/CRH 3", "double_ogive", "crh3"),
                           ("CRH 4.5/CRH 3", "crh45", "crh3"), ("minimum N*/DO", "minimum_nstar", "double_ogive")):
        for v, row in d.iterrows():
            rows.append({"contrast": name, "velocity": v, "ratio": row[num] / row[den], "gain_m": row[num] - row[den]})
    t = pd.DataFrame(rows)
    write_csv(t, outputs.csv)
    fig, axes = figure(2, 3.9, 3.4)
    for name, g in t.groupby("contrast", sort=False):
        axes[0].plot(g.velocity, 100 * (g.ratio - 1), marker="o", ms=3, label=name)
        axes[1].plot(g.velocity, g.gain_m, marker="o", ms=3, label=name)
    refs = load_reference(inputs.reference)
    colors = {name: line.get_color() for name, line in zip(t.contrast.unique(), axes[0].get_lines())}
    for name, num, den in (("DO/CRH 4.5", "double_ogive", "crh45"), ("DO/CRH 3", "double_ogive", "crh3"),
                           ("CRH 4.5/CRH 3", "crh45", "crh3")):
        pts = [(v, refs[f"table3.sim.{v}.{num}"].si, refs[f"table3.sim.{v}.{den}"].si) for v in (500, 800, 1000, 1200)]
        axes[0].plot([p[0] for p in pts], [100 * (p[1] / p[2] - 1) for p in pts], **{**PAPER_STYLE, "color": colors[name]},
                     label=f"{name} (paper's simulation)")
        axes[1].plot([p[0] for p in pts], [p[1] - p[2] for p in pts], **{**PAPER_STYLE, "color": colors[name]})
    for key, name in (("text.gain_1200_crh45", "DO/CRH 4.5"), ("text.gain_1200_crh3", "DO/CRH 3")):
        axes[1].plot([1200], [refs[key].si], marker="*", ms=9, ls="none", color=colors[name],
                     label=f"text: {refs[key].value} m ({name}, 1200 m/s)")
    axes[0].axhline(10, color="black", ls=":", lw=0.8, label="text: +10 % over CRH 3")
    axes[0].axhline(5, color="black", ls="--", lw=0.8, label="text: +5 % over CRH 4.5")
    axes[0].set(xlabel="striking velocity (m/s)", ylabel="depth gain (%)", title="FE level: depth gain of one nose over another")
    axes[1].set(xlabel="striking velocity (m/s)", ylabel="depth gain (m)", title="the same in metres")
    for ax in axes:
        ax.legend(fontsize=6)
    save(fig, outputs.png, params.dpi)


CONVERGENCE_NOSES = {"DO/CRH 4.5": ("double_ogive", "crh45"), "CRH 4.5/CRH 3": ("crh45", "crh3"),
                     "DO/CRH 3": ("double_ogive", "crh3")}


def _profile_table3(ratios_path, table_path, cal_path):
    """A mesh profile's DO1 calibration, Table 3 and nose contrasts (those of CONVERGENCE_NOSES), checked to belong
    to one mesh."""
    cal = load_json(cal_path)
    t3 = pd.read_csv(table_path)
    if not all(math.isclose(h, cal["element_size"], rel_tol=1e-9) for h in t3.element_size_m):
        raise ValueError(f"{table_path}: element sizes {sorted(set(t3.element_size_m))}; allowed: the calibration's "
                         f"{cal['element_size']} m ({cal_path})")
    ratios = pd.read_csv(ratios_path)
    return cal, t3, ratios[ratios.contrast.isin(list(CONVERGENCE_NOSES))]


@task
def fe_contrast_convergence(inputs, outputs, params):
    """The FE nose contrasts of Table 3 at several meshes (each with its own DO1 calibration): converged or not,
    beside the interval of the erosion chaos at the mesh of the ensemble (fe_contrast_ensemble)."""
    rows = []
    across = {}
    for paths in zip(inputs.ratios, inputs.tables, inputs.calibrations):
        cal, t3, ratios = _profile_table3(*paths)
        across[round(cal["element_size"], 12)] = cal["elements_across_radius"]
        depth = {(int(r.velocity_ms), r.nose): r.fe_m for r in t3.itertuples()}
        for r in ratios.itertuples():
            num, den = CONVERGENCE_NOSES[r.contrast]
            v = int(r.velocity_ms)
            rows.append({"elements_across_radius": cal["elements_across_radius"], "element_size_m": cal["element_size"],
                         "failure_strain": cal["fs"], "velocity_ms": v, "contrast": r.contrast, "fe_ratio": r.fe_ratio,
                         "paper_sim_ratio": r.paper_sim_ratio, "difference_points": 100 * (r.fe_ratio - r.paper_sim_ratio),
                         "depth_num_m": depth[(v, num)], "depth_den_m": depth[(v, den)]})
    t = pd.DataFrame(rows).sort_values(["contrast", "velocity_ms", "elements_across_radius"])
    write_csv(t, outputs.csv)
    ens = pd.read_csv(inputs.ensemble)
    fig, axes = figure(3, 3.6, 3.6)
    ticks = sorted(t.elements_across_radius.unique())
    for ax, name in zip(axes, CONVERGENCE_NOSES):
        g = t[t.contrast == name]
        for k, (v, gv) in enumerate(g.groupby("velocity_ms")):
            c = f"C{k}"
            ax.plot(gv.elements_across_radius, 100 * (gv.fe_ratio - 1), marker="o", ms=3, color=c, label=f"{v} m/s (ours)")
            e = ens[(ens.contrast == name) & (ens.velocity_ms == v)].iloc[0]
            lo, hi = 100 * (e.interval_low - 1), 100 * (e.interval_high - 1)
            ax.errorbar([across[round(e.element_size_m, 12)] + 0.15 * (k - 1.5)], [(lo + hi) / 2], yerr=[(hi - lo) / 2],
                        fmt="none", color=c, capsize=2, lw=1,
                        label=f"{100 * e.confidence:.0f} % interval of the mean over {e.realisations} realisations"
                        if k == 0 and name == next(iter(CONVERGENCE_NOSES)) else None)
            ax.plot([max(ticks) + 0.6 + 0.25 * k], [100 * (gv.paper_sim_ratio.iloc[0] - 1)], **{**PAPER_STYLE, "color": c},
                    label=f"{v} m/s (paper's simulation)")
        ax.axhline(0, color="black", lw=0.5)
        ax.set(xlabel="elements across the shank radius", ylabel="depth gain (%)",
               title=f"{name}: FE level against mesh", xlim=(min(ticks) - 0.5, max(ticks) + 1.8))
        ax.set_xticks(ticks, [f"{x:.0f}" for x in ticks])
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7, bbox_to_anchor=(0.5, -0.02))
    fig.suptitle(f"Nose contrasts of Table 3 at the FE level, {len(ticks)} meshes, the failure strain calibrated on DO1 "
                 "at each", fontsize=9)
    fig.subplots_adjust(bottom=0.3, wspace=0.3, top=0.82)
    save(fig, outputs.png, params.dpi)


@task
def fe_contrast_ensemble(inputs, outputs, params):
    """Realisations of the erosion chaos at the full mesh: the spread of each Table 3 depth and nose contrast.

    Member 0 is the Table 3 shot; members k >= 1 the same shot struck at
    v (1 + k step). Ratios pair the members of equal k. The interval of a mean
    is Student's t at the configured confidence over the realisations.
    """
    depth, sizes = {}, set()
    for path in [*inputs.shots, *inputs.members]:
        s = load_json(path)
        sizes.add(s["element_size"])
        depth.setdefault((s["nose"], int(round(s["velocity"]))), {})[int(s.get("member", 0))] = s["depth_m"]
    paper = {(r.nose, int(r.velocity_ms)): r.paper_sim_m for r in pd.read_csv(inputs.table).itertuples()}
    drows = []
    for (nose, v), d in sorted(depth.items()):
        x = np.array([d[k] for k in sorted(d)])
        drows.append({"velocity_ms": v, "nose": nose, "realisations": x.size, "depth_member0_m": d[0], "mean_m": x.mean(),
                      "std_m": x.std(ddof=1), "rel_std_pct": 100 * x.std(ddof=1) / x.mean(), "min_m": x.min(),
                      "max_m": x.max(), "paper_sim_m": paper[(nose, v)]})
    if len(sizes) != 1:
        raise ValueError(f"ensemble members at element sizes {sorted(sizes)}; allowed: one mesh")
    write_csv(pd.DataFrame(drows), outputs.depths)
    paper_ratio = {(r.contrast, int(r.velocity_ms)): r.paper_sim_ratio for r in pd.read_csv(inputs.ratios).itertuples()}
    rows, members = [], {}
    for name, (num, den) in CONVERGENCE_NOSES.items():
        for v in sorted({v for _, v in depth}):
            a, b = depth[(num, v)], depth[(den, v)]
            x = np.array([a[k] / b[k] for k in sorted(a) if k in b])
            members[(name, v)] = x
            lo, hi = _t_interval(x, params.confidence)
            p = paper_ratio[(name, v)]
            rows.append({"contrast": name, "velocity_ms": v, "element_size_m": min(sizes), "realisations": x.size,
                         "ratio_member0": x[0],
                         "mean_ratio": x.mean(), "std_ratio": x.std(ddof=1), "min_ratio": x.min(), "max_ratio": x.max(),
                         "interval_low": float(lo), "interval_high": float(hi), "confidence": params.confidence,
                         "paper_sim_ratio": p, "mean_minus_paper_points": 100 * (x.mean() - p),
                         "paper_inside_interval": bool(lo <= p <= hi)})
    t = pd.DataFrame(rows)
    write_csv(t, outputs.csv)
    fig, axes = figure(3, 3.6, 3.6)
    for ax, name in zip(axes, CONVERGENCE_NOSES):
        g = t[t.contrast == name]
        for k, r in enumerate(g.itertuples()):
            x = members[(name, r.velocity_ms)]
            ax.plot(np.full(x.size, k - 0.12), 100 * (x - 1), "o", ms=3, color="tab:blue", alpha=0.6,
                    label="realisations (ours)" if k == 0 else None)
            ax.errorbar([k + 0.05], [100 * (r.mean_ratio - 1)],
                        yerr=[[100 * (r.mean_ratio - r.interval_low)], [100 * (r.interval_high - r.mean_ratio)]],
                        fmt="s", ms=4, color="tab:blue", capsize=3,
                        label=f"mean, {100 * params.confidence:.0f} % interval (ours)" if k == 0 else None)
            ax.plot([k + 0.25], [100 * (r.paper_sim_ratio - 1)], **PAPER_STYLE, label="paper's simulation" if k == 0 else None)
        ax.axhline(0, color="black", lw=0.5)
        ax.set_xticks(range(len(g)), [f"{v}" for v in g.velocity_ms])
        ax.set(xlabel="striking velocity (m/s)", ylabel="depth gain (%)", title=f"{name}: FE level, full mesh")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7, bbox_to_anchor=(0.5, -0.02))
    n = int(t.realisations.iloc[0])
    fig.suptitle(f"Nose contrasts of Table 3 at the FE level over {n} realisations of the erosion chaos "
                 f"(element size {1e3 * min(sizes):.3g} mm)", fontsize=9)
    fig.subplots_adjust(bottom=0.25, wspace=0.3, top=0.84)
    save(fig, outputs.png, params.dpi)


def _t_interval(x, confidence):
    """Student-t interval of the mean of the sample x at a two-sided confidence level (the interval does not depend
    on the test's popmean; scipy's round-off does, and 1 is the one the committed intervals were made with)."""
    from scipy import stats
    lo, hi = stats.ttest_1samp(x, 1.0).confidence_interval(confidence)
    return float(lo), float(hi)


def _band_rows(ratios_paths, table_paths, cal_paths, band, confidence):
    """One band's meshes (centre first): per mesh and contrast, and per cell and contrast over the meshes."""
    meshes, cells, ratios = [], {}, {}
    centre = None
    for paths in zip(ratios_paths, table_paths, cal_paths):
        cal, t3, mesh_ratios = _profile_table3(*paths)
        across = cal["elements_across_radius"]
        centre = across if centre is None else centre
        for r in t3.itertuples():
            cells.setdefault((int(r.velocity_ms), r.nose), {"paper": r.paper_sim_m, "x": []})["x"].append(r.fe_m)
        for r in mesh_ratios.itertuples():
            v = int(r.velocity_ms)
            ratios.setdefault((r.contrast, v), {"paper": r.paper_sim_ratio, "x": []})["x"].append(r.fe_ratio)
            meshes.append({"band": band, "centre_elements_across": centre, "elements_across_radius": across,
                           "element_size_m": cal["element_size"], "failure_strain": cal["fs"],
                           "calibration_residual_m": cal["residual_m"], "velocity_ms": v, "contrast": r.contrast,
                           "fe_ratio": r.fe_ratio, "paper_sim_ratio": r.paper_sim_ratio,
                           "difference_points": 100 * (r.fe_ratio - r.paper_sim_ratio),
                           "within_2_points_goal": abs(r.fe_ratio - r.paper_sim_ratio) <= 0.02})
    m = pd.DataFrame(meshes)
    n = m.elements_across_radius.nunique()
    if n < 2:
        raise ValueError(f"band {band}: {n} mesh; allowed: at least 2")
    fs = m.drop_duplicates("elements_across_radius").failure_strain.to_numpy()
    head = {"band": band, "centre_elements_across": centre, "meshes": n}
    drows = []
    for (v, nose), c in sorted(cells.items()):
        x, p = np.array(c["x"]), c["paper"]
        lo, hi = _t_interval(x, confidence)
        drows.append({**head, "velocity_ms": v, "nose": nose, "mean_m": x.mean(), "std_m": x.std(ddof=1),
                      "rel_std_pct": 100 * x.std(ddof=1) / x.mean(), "min_m": x.min(), "max_m": x.max(),
                      "interval_low_m": lo, "interval_high_m": hi, "confidence": confidence, "paper_sim_m": p,
                      "mean_rel_dev_pct": 100 * (x.mean() / p - 1), "within_5pct_goal": abs(x.mean() / p - 1) <= 0.05,
                      "paper_inside_interval": bool(lo <= p <= hi)})
    rows = []
    for name in CONVERGENCE_NOSES:
        for v in sorted(v for c, v in ratios if c == name):
            x, p = np.array(ratios[(name, v)]["x"]), ratios[(name, v)]["paper"]
            lo, hi = _t_interval(x, confidence)
            rows.append({**head, "contrast": name, "velocity_ms": v, "mean_ratio": x.mean(), "std_ratio": x.std(ddof=1),
                         "min_ratio": x.min(), "max_ratio": x.max(), "interval_low": lo, "interval_high": hi,
                         "confidence": confidence, "paper_sim_ratio": p, "mean_minus_paper_points": 100 * (x.mean() - p),
                         "within_2_points_goal": abs(x.mean() - p) <= 0.02, "paper_inside_interval": bool(lo <= p <= hi),
                         "failure_strain_min": fs.min(), "failure_strain_max": fs.max()})
    return m, pd.DataFrame(drows), pd.DataFrame(rows)


@task
def fe_contrast_band(inputs, outputs, params):
    """Mesh realisations of Table 3 at the FE level: bands of meshes around a profile (its element size changed by a
    few per cent), each mesh with the failure strain calibrated on DO1 at its own size.

    Where a nose meets the element rows moves a depth by several per cent between meshes of nearly the same size;
    a band samples that, together with the calibration's own scatter. Per band, cell and contrast: the mean over
    the meshes, its Student-t interval at params.confidence, and the paper's simulated value against both.
    params.bands: (centre profile, number of meshes) per band, in the order of the inputs (centre first).
    """
    parts, start = [], 0
    for band, n in params.bands:
        sl = slice(start, start + n)
        parts.append(_band_rows(inputs.ratios[sl], inputs.tables[sl], inputs.calibrations[sl], band, params.confidence))
        start += n
    if start != len(inputs.ratios):
        raise ValueError(f"{len(inputs.ratios)} meshes given; the bands {params.bands} name {start}")
    m = pd.concat([p[0] for p in parts]).sort_values(["centre_elements_across", "contrast", "velocity_ms",
                                                      "elements_across_radius"])
    d = pd.concat([p[1] for p in parts])
    t = pd.concat([p[2] for p in parts])
    write_csv(m, outputs.meshes)
    write_csv(d, outputs.depths)
    write_csv(t, outputs.csv)
    contrast_band_figure(t, m, [b for b, _ in params.bands], params.confidence, outputs.png, params.dpi)


def contrast_band_figure(t, m, bands, confidence, path, dpi):
    """The bands' contrasts (t: contrast_band.csv rows, m: contrast_band_meshes.csv rows), two panels a row, fonts
    readable at page width."""
    plt.rcParams.update({"font.size": 10, "axes.grid": True, "grid.alpha": 0.3})
    fig, grid = plt.subplots(2, 2, figsize=(9.6, 8.2))
    axes = grid.ravel()
    across = {b: float(t[t.band == b].centre_elements_across.iloc[0]) for b in bands}
    width = 0.7 / len(bands)
    for ax, name in zip(axes, CONVERGENCE_NOSES):
        g, gm = t[t.contrast == name], m[m.contrast == name]
        vs = sorted(g.velocity_ms.unique())
        for b_i, b in enumerate(bands):
            x0 = -0.35 + width * b_i
            for k, v in enumerate(vs):
                r = g[(g.band == b) & (g.velocity_ms == v)].iloc[0]
                x = gm[(gm.band == b) & (gm.velocity_ms == v)]
                ax.plot(np.full(len(x), k + x0 + 0.25 * width), 100 * (x.fe_ratio - 1), "o", ms=2.5, color=f"C{b_i}",
                        alpha=0.5, label=f"one mesh, {across[b]:g} across band (ours)" if k == 0 else None)
                ax.errorbar([k + x0 + 0.6 * width], [100 * (r.mean_ratio - 1)],
                            yerr=[[100 * (r.mean_ratio - r.interval_low)], [100 * (r.interval_high - r.mean_ratio)]],
                            fmt="s", ms=4, color=f"C{b_i}", capsize=3,
                            label=f"mean, {100 * confidence:.0f} % interval, {across[b]:g} across (ours)"
                            if k == 0 else None)
        for k, v in enumerate(vs):
            ax.plot([k + 0.4], [100 * (g[g.velocity_ms == v].paper_sim_ratio.iloc[0] - 1)], **PAPER_STYLE,
                    label="paper's simulation" if k == 0 else None)
        ax.axhline(0, color="black", lw=0.5)
        ax.set_xticks(range(len(vs)), [f"{v}" for v in vs])
        ax.set(xlabel="striking velocity (m/s)", ylabel="depth gain (%)", title=name)
    cal = m.drop_duplicates(["band", "elements_across_radius"])
    for b_i, b in enumerate(bands):
        c = cal[cal.band == b]
        axes[3].plot(c.elements_across_radius, c.failure_strain, "o-", ms=4, color=f"C{b_i}",
                     label=f"{across[b]:g} across band")
    axes[3].set(xlabel="elements across the shank radius", ylabel="failure strain calibrated on DO1",
                title="DO1 calibration per mesh")
    axes[3].legend(fontsize=9)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=9, bbox_to_anchor=(0.5, -0.09))
    sizes = ", ".join(f"{across[b]:g} across ({int(t[t.band == b].meshes.iloc[0])} meshes "
                      f"{cal[cal.band == b].elements_across_radius.min():g}-{cal[cal.band == b].elements_across_radius.max():g})"
                      for b in bands)
    fig.suptitle(f"Nose contrasts of Table 3 at the FE level over bands of meshes around\n{sizes},\neach mesh "
                 "calibrated on DO1 (a band's mean measures scatter, not convergence)", fontsize=10)
    fig.subplots_adjust(bottom=0.1, wspace=0.3, hspace=0.35, top=0.86)
    save(fig, path, dpi)
