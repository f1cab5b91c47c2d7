"""The generated blocks of the scale effect (docs/scale-effect.md, the README): from figures/scale/*.csv."""
from __future__ import annotations

from ..studies.scale import GOALS, goals_met
from .docs_read import rows_if_any

LEVEL_FACTOR = {"analytic": "S factor", "cavity": "strength scale", "fe": "failure strain"}


def _f(x, fmt):
    try:
        return format(float(x), fmt)
    except (TypeError, ValueError):
        return "—"


def scale_effect(read) -> str:
    """Per level and variant of the scale effect: the factor fitted on each series alone and their ratio, the pooled
    leave-one-series-out errors, each series' mean error, DO1's prediction (fold all) and whether the goals hold."""
    import yaml

    levels = yaml.safe_load(read("workflow/config.yaml"))["scale_effect"]["levels"]
    lines = ["| level | variant | mechanisms | factor on 26.9 mm / 76.2 mm | ratio | held-out median / p90 "
             "&#124;error&#124; | mean error 76.2 mm / 26.9 mm | DO1 (5.1 m) | goals met |",
             "|---|---|---|---|---|---|---|---|---|"]
    missing = []
    for level in levels:
        rows = rows_if_any(read, f"figures/scale/validation_{level}.csv")
        if not rows:
            missing.append(level)
            continue
        for r in rows:
            met = goals_met(r).values()
            lines.append(
                f"| {level} | {r['variant']} | {r['mechanisms']}"
                + (f", {r['beyond']}" if r["beyond"] else "")
                + (f", d_a {1e3 * float(r['aggregate_m']):g} mm" if r["aggregate_m"] else "")
                + f" | {_f(r['value_forrestal2003'], '.3g')} / {_f(r['value_forrestal1994'], '.3g')} "
                f"| {_f(r['split_ratio'], '.2f')} | {100 * float(r['loso_median_abs_rel_err']):.1f} / "
                f"{100 * float(r['loso_p90_abs_rel_err']):.1f} % | {100 * float(r['mean_rel_err_forrestal1994']):+.1f} / "
                f"{100 * float(r['mean_rel_err_forrestal2003']):+.1f} % | {float(r['do1_pred_m']):.2f} m "
                f"({100 * float(r['do1_rel_error']):+.1f} %) | {sum(met)} of 4 |")
    tail = (f"\nGoals: held-out median |error| <= {100 * GOALS['loso_median']:.0f} % and 90th percentile <= "
            f"{100 * GOALS['loso_p90']:.0f} % (both series left out in turn, pooled), the two series' factors within a "
            f"ratio of {GOALS['split_ratio']:.2f}, DO1 within {100 * GOALS['do1']:.0f} % of 5.1 m (predicted with the "
            "factor fitted on all 25 laboratory shots; DO1 enters no fit).")
    if missing:
        tail += " Not yet run: " + ", ".join(f"`snakemake -c2 figures/scale/validation_{lv}.csv`" for lv in missing) + "."
    return "\n".join(lines) + "\n" + tail + "\n"


BLOCKS = {"scale_effect": scale_effect}
