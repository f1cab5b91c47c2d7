"""Drawings of the finite-element level: Figs 12-15, the DO1 fields, and the drawings of its tables and studies.

The figure tasks here read the per-shot results of ``tasks.fe`` (JSON summaries, binned histories and fields) and
draw; the tables and studies are computed by ``penetration.studies.fe_results`` in the tasks ``tasks.fe_tables`` and
``tasks.fe_studies``, which call the drawing functions here (``*_figure``) with the frames they wrote.
"""
from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..paper.reference import TABLE3_NOSES, UNITS, load_reference
from ..pipeline.io import committed_study, load_json, task, write_csv
from .common import PAPER_STYLE, color, do1_histories, figure, save

G0 = UNITS["g"]
LABELS = {"double_ogive": "double ogive", "crh45": "CRH 4.5", "crh3": "CRH 3", "minimum_nstar": "minimum N*"}


def shots_frame(paths):
    """Summaries of the shots (JSON paths) as a frame, with the path of each."""
    rows = [load_json(p) | {"json": str(p)} for p in paths]
    return pd.DataFrame(rows)


def _histories(json_path):
    return pd.read_csv(json_path.replace(".json", "_histories.csv"))


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
    shots = shots_frame(inputs.shots)
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
    shots = shots_frame(inputs.shots)
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


def mesh_study_figure(t, path, dpi):
    """The DO1 calibration per mesh (t: fe_mesh_study rows): fs and the wall time of one run against the elements
    across the shank radius."""
    fig, axes = figure(2, 3.8, 3.4)
    axes[0].plot(t.elements_across_radius, t.failure_strain, marker="o", color="tab:green", label="ours (2-D, calibrated on DO1)")
    axes[0].axhline(0.38, color="black", ls="--", lw=0.8, label="paper's fs (its 3-D mesh)")
    axes[0].set(xlabel="elements across the shank radius", ylabel="failure strain fs", title="calibrated fs per mesh")
    axes[0].legend(fontsize=6)
    axes[1].plot(t.elements_across_radius, t.wall_time_per_run_s, marker="o", color="tab:blue")
    axes[1].set(xlabel="elements across the shank radius", ylabel="wall time of one DO1 run (s)", yscale="log",
                title="cost per DO1 run")
    save(fig, path, dpi)


def contrasts_figure(t, paper, refs, path, dpi):
    """The nose contrasts over Fig 15's sweep (t: contrasts.csv rows), beside the paper's simulated ones (paper: the
    same columns) and the gains its text states: ratios in per cent and gains in metres."""
    fig, axes = figure(2, 3.9, 3.4)
    for name, g in t.groupby("contrast", sort=False):
        axes[0].plot(g.velocity, 100 * (g.ratio - 1), marker="o", ms=3, label=name)
        axes[1].plot(g.velocity, g.gain_m, marker="o", ms=3, label=name)
    colors = {name: line.get_color() for name, line in zip(t.contrast.unique(), axes[0].get_lines())}
    for name, g in paper.groupby("contrast", sort=False):
        axes[0].plot(g.velocity, 100 * (g.ratio - 1), **{**PAPER_STYLE, "color": colors[name]},
                     label=f"{name} (paper's simulation)")
        axes[1].plot(g.velocity, g.gain_m, **{**PAPER_STYLE, "color": colors[name]})
    for key, name in (("text.gain_1200_crh45", "DO/CRH 4.5"), ("text.gain_1200_crh3", "DO/CRH 3")):
        axes[1].plot([1200], [refs[key].si], marker="*", ms=9, ls="none", color=colors[name],
                     label=f"text: {refs[key].value} m ({name}, 1200 m/s)")
    axes[0].axhline(10, color="black", ls=":", lw=0.8, label="text: +10 % over CRH 3")
    axes[0].axhline(5, color="black", ls="--", lw=0.8, label="text: +5 % over CRH 4.5")
    axes[0].set(xlabel="striking velocity (m/s)", ylabel="depth gain (%)", title="FE level: depth gain of one nose over another")
    axes[1].set(xlabel="striking velocity (m/s)", ylabel="depth gain (m)", title="the same in metres")
    for ax in axes:
        ax.legend(fontsize=6)
    save(fig, path, dpi)


def contrast_convergence_figure(t, ens, contrasts, path, dpi):
    """The contrasts against the mesh (t: contrast_convergence.csv rows), one panel per contrast, beside the interval
    of the erosion chaos at the ensemble's mesh (ens: contrast_ensemble.csv rows) and the paper's ratios."""
    across = {round(h, 12): a for h, a in zip(t.element_size_m, t.elements_across_radius)}
    fig, axes = figure(3, 3.6, 3.6)
    ticks = sorted(t.elements_across_radius.unique())
    for ax, name in zip(axes, contrasts):
        g = t[t.contrast == name]
        for k, (v, gv) in enumerate(g.groupby("velocity_ms")):
            c = f"C{k}"
            ax.plot(gv.elements_across_radius, 100 * (gv.fe_ratio - 1), marker="o", ms=3, color=c, label=f"{v} m/s (ours)")
            e = ens[(ens.contrast == name) & (ens.velocity_ms == v)].iloc[0]
            lo, hi = 100 * (e.interval_low - 1), 100 * (e.interval_high - 1)
            ax.errorbar([across[round(e.element_size_m, 12)] + 0.15 * (k - 1.5)], [(lo + hi) / 2], yerr=[(hi - lo) / 2],
                        fmt="none", color=c, capsize=2, lw=1,
                        label=f"{100 * e.confidence:.0f} % interval of the mean over {e.realisations} realisations"
                        if k == 0 and name == contrasts[0] else None)
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
    save(fig, path, dpi)


def contrast_ensemble_figure(t, members, contrasts, confidence, path, dpi):
    """The contrasts over realisations of the erosion chaos (t: contrast_ensemble.csv rows; members: contrast,
    velocity_ms, member, ratio of each realisation), one panel per contrast, with the paper's ratios."""
    fig, axes = figure(3, 3.6, 3.6)
    for ax, name in zip(axes, contrasts):
        g = t[t.contrast == name]
        for k, r in enumerate(g.itertuples()):
            x = members[(members.contrast == name) & (members.velocity_ms == r.velocity_ms)].ratio.to_numpy()
            ax.plot(np.full(x.size, k - 0.12), 100 * (x - 1), "o", ms=3, color="tab:blue", alpha=0.6,
                    label="realisations (ours)" if k == 0 else None)
            ax.errorbar([k + 0.05], [100 * (r.mean_ratio - 1)],
                        yerr=[[100 * (r.mean_ratio - r.interval_low)], [100 * (r.interval_high - r.mean_ratio)]],
                        fmt="s", ms=4, color="tab:blue", capsize=3,
                        label=f"mean, {100 * confidence:.0f} % interval (ours)" if k == 0 else None)
            ax.plot([k + 0.25], [100 * (r.paper_sim_ratio - 1)], **PAPER_STYLE, label="paper's simulation" if k == 0 else None)
        ax.axhline(0, color="black", lw=0.5)
        ax.set_xticks(range(len(g)), [f"{v}" for v in g.velocity_ms])
        ax.set(xlabel="striking velocity (m/s)", ylabel="depth gain (%)", title=f"{name}: FE level, full mesh")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7, bbox_to_anchor=(0.5, -0.02))
    n = int(t.realisations.iloc[0])
    fig.suptitle(f"Nose contrasts of Table 3 at the FE level over {n} realisations of the erosion chaos "
                 f"(element size {1e3 * t.element_size_m.iloc[0]:.3g} mm)", fontsize=9)
    fig.subplots_adjust(bottom=0.25, wspace=0.3, top=0.84)
    save(fig, path, dpi)


def contrast_band_figure(t, m, bands, contrasts, confidence, path, dpi):
    """The bands' contrasts (t: contrast_band.csv rows, m: contrast_band_meshes.csv rows; ``contrasts``: their names,
    one panel each), two panels a row, fonts readable at page width."""
    plt.rcParams.update({"font.size": 10, "axes.grid": True, "grid.alpha": 0.3})
    fig, grid = plt.subplots(2, 2, figsize=(9.6, 8.2))
    axes = grid.ravel()
    across = {b: float(t[t.band == b].centre_elements_across.iloc[0]) for b in bands}
    width = 0.7 / len(bands)
    for ax, name in zip(axes, contrasts):
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
