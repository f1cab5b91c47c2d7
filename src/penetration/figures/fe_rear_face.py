"""Drawing of the rear-face study (tasks.fe_rear_face): depths along the chain of targets, each change's effect."""
from __future__ import annotations

import math

import numpy as np

import matplotlib.pyplot as plt

from .common import save

STATUS = (("rest", "at rest", dict(marker="o", ms=4)),
          ("end_time", "still moving at the end time", dict(marker="^", ms=5, mfc="none")),
          ("perforated", "tail out of the target", dict(marker="x", ms=6, mew=1.5)))


def _label(r):
    bottom = "deep" if math.isnan(r.bottom_depth_m) else f"{r.bottom_depth_m:g} m"
    short = {"non_reflecting": "absorbing", "free": "free"}
    return f"R {r.radius_m:.3g} m\nsides {short[r.lateral]}\nbottom {bottom},\n{short[r.bottom]}"


def rear_face_figure(m, t, e, path, dpi):
    """Left: each target's realisations, mean and standard deviation, the measured depth and the 5.4 m rear face.
    Right: each single change's effect on the mean depth with its interval, and the whole difference."""
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3})
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7.2, 8.4), gridspec_kw={"height_ratios": [3, 2]})
    seen = set()
    for k, r in t.iterrows():
        g = m[m.scene == r.scene]
        for status, text, style in STATUS:
            h = g[g.status == status]
            if len(h):
                ax.plot(k + 0.04 * (h.member.to_numpy() - g.member.max() / 2), h.depth_m, ls="none", color="tab:blue",
                        label=text if text not in seen else None, **style)
                seen.add(text)
        ax.errorbar([k + 0.3], [r.mean_m], yerr=[r.std_m], fmt="_", ms=12, color="black", capsize=3,
                    label="mean and standard deviation" if k == 0 else None)
        if not math.isnan(r.bottom_depth_m):
            ax.plot([k - 0.35, k + 0.45], [r.bottom_depth_m] * 2, color="tab:red", lw=1.5,
                    label="the target's bottom (rear face)" if "bottom" not in seen else None)
            seen.add("bottom")
    ax.axhline(t.measured_depth_m.iloc[0], color="black", lw=1, ls=":",
               label=f"measured DO1 depth ({t.measured_depth_m.iloc[0]:g} m, the calibration's target)")
    ax.set_xticks(range(len(t)), [_label(r) for r in t.itertuples()], fontsize=7.5)
    ax.set(ylabel="depth of the tip at the end (m)", xlim=(-0.6, len(t) - 0.4),
           title=f"DO1 at 835 m/s, element size {1e3 * t.element_size_m.iloc[0]:.3g} mm, "
                 f"{int(t.realisations.iloc[0])} realisations each")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    y = np.arange(len(e))
    for k, r in enumerate(e.itertuples()):
        c = "tab:blue" if r.single_change else "black"
        bx.errorbar([100 * r.effect_m], [k], xerr=[[100 * (r.effect_m - r.interval_low_m)], [100 * (r.interval_high_m - r.effect_m)]],
                    fmt="s", ms=5, color=c, capsize=3)
    bx.axvline(0, color="black", lw=0.6)
    bx.set_yticks(y, [r.changes if r.single_change else "all of them (semi-infinite to block)" for r in e.itertuples()],
                  fontsize=8)
    bx.invert_yaxis()
    bx.set(xlabel="effect on the mean depth (cm)",
           title=f"Each change, one at a time ({100 * e.confidence.iloc[0]:.0f} % Welch interval)")
    fig.subplots_adjust(hspace=0.45)
    save(fig, path, dpi)
