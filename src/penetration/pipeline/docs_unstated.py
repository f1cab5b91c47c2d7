"""The generated block of the unstated inputs (docs/findings.md): from figures/fe/unstated_{target}_v{v}.csv."""
from __future__ import annotations

import math

from .docs_read import number as _num, rows_if_any as _rows

TARGETS = {"eroding": "eroding target (failure strain calibrated on DO1 without friction, full mesh)",
           "erosion_free": "erosion-free target (8.192 elements across)"}


def unstated_inputs(read) -> str:
    """Per target, velocity and contrast: the baseline's mean ± s.e. and each unstated setting's change in points
    (± its s.e., marked where Student's t resolves it), with the members that came to rest; the paper's value."""
    import yaml

    cfg = yaml.safe_load(read("workflow/config.yaml"))["fe_realisations"]
    lines, missing = [], []
    for target in cfg["unstated"]:
        for v in cfg["velocities"]:
            rows = _rows(read, f"figures/fe/unstated_{target}_v{v:g}.csv")
            if not rows:
                missing.append(f"{target} at {v:g} m/s")
                continue
            settings = [(r["input"], r["setting"]) for r in rows if r["baseline"] != "True"]
            settings = list(dict.fromkeys(settings))
            lines.append(f"\n{TARGETS.get(target, target)}, {v:g} m/s:\n")
            lines.append("| contrast | paper | baseline | " + " | ".join(f"{i} {s}" for i, s in settings) + " |")
            lines.append("|---|---|---|" + "---|" * len(settings))
            for contrast in dict.fromkeys(r["contrast"] for r in rows):
                mine = [r for r in rows if r["contrast"] == contrast]
                base = next(r for r in mine if r["baseline"] == "True")
                cells = []
                for name, setting in settings:
                    r = next((x for x in mine if (x["input"], x["setting"]) == (name, setting)), None)
                    if r is None or not (math.isfinite(_num(r["change_points"]))
                                         and math.isfinite(_num(r["change_se_points"]))):
                        rest = f"{r['realisations']} of {r['runs']} at rest" if r is not None else "not run"
                        cells.append(f"— ({rest})")
                        continue
                    mark = "**" if r["change_resolved"] == "True" else ""
                    cells.append(f"{mark}{_num(r['change_points']):+.1f} ± {_num(r['change_se_points']):.1f}{mark}")
                lines.append(f"| {contrast} | {_num(base['paper_sim_ratio']):.3f} | {_num(base['ratio']):.3f} ± "
                             f"{_num(base['ratio_se']):.3f} | " + " | ".join(cells) + " |")
    tail = ("\nChanges in points of the contrast from the baseline (the means of the realisations, ± the standard error "
            "of the difference); bold where the change exceeds Student's t at 95 % times its standard error; '— (n of m "
            "at rest)': too few of the setting's members came to rest within the run to give a contrast with its "
            "standard error.")
    if missing:
        tail += " Not yet run: " + ", ".join(missing) + "."
    return "\n".join(lines).lstrip("\n") + "\n" + tail + "\n"


BLOCKS = {"unstated_inputs": unstated_inputs}


def table3_window(read) -> str:
    """The moving window against the whole domain on the eroding target at Table 3's fastest shots (study
    fe_table3_window): each shot's difference of the mean depths with its interval and verdict."""
    import yaml

    parts, missing = [], []
    for shot in yaml.safe_load(read("workflow/config.yaml"))["fe_realisations"]["window"]["shots"]:
        rows = _rows(read, f"figures/fe/full/window_table3_{shot}_summary.csv")
        if not rows:
            missing.append(shot)
            continue
        r = rows[0]
        nose, v = shot.rsplit("_", 1)
        parts.append(f"{nose} at {v} m/s {_num(r['difference_pct']):+.2f} % ({100 * _num(r['confidence']):.0f} % "
                     f"interval {_num(r['interval_low_pct']):+.2f} to {_num(r['interval_high_pct']):+.2f} %, "
                     f"{'within' if r['within_goal'] == 'True' else 'not within'} +-{_num(r['goal_pct']):g} %; "
                     f"{r['realisations']} realisations each)")
    text = ("On the eroding target at Table 3's fastest shots (study `fe_table3_window`, "
            "`figures/fe/full/window_table3_*_summary.csv`), the window against the whole domain: "
            + ("; ".join(parts) if parts else "none run yet") + ".")
    if missing:
        text += " Not yet run: " + ", ".join(missing) + "."
    return text + "\n"


BLOCKS["table3_window"] = table3_window


def do1_window(read) -> str:
    """The moving window against the whole domain on DO1 (study fe_window): the mean depths, their difference with
    its interval and verdict, and the same test on the first half of the realisations alone."""
    summary = _rows(read, "figures/fe/full/window_summary.csv")
    if not summary:
        return "The DO1 window study (`fe_window`) has not run yet.\n"
    r = summary[0]
    n = int(r["realisations"])
    verdict = "it passes" if r["within_goal"] == "True" else "it does not pass"
    text = (f"The window's mean depth over {n} realisations is {_num(r['mean_window_m']):.3f} m against the whole "
            f"domain's {_num(r['mean_whole_m']):.3f} m, {_num(r['difference_pct']):+.2f} % "
            f"({100 * _num(r['confidence']):.0f} % interval {_num(r['interval_low_pct']):+.2f} to "
            f"{_num(r['interval_high_pct']):+.2f} %): {verdict}")
    runs = _rows(read, "figures/fe/full/window.csv")
    half = n // 2
    if runs and half >= 2:
        import pandas as pd

        from ..studies.fe_results import window_summary

        frame = pd.DataFrame(runs).astype({"member": int, "depth_m": float})
        h = window_summary(frame[frame.member < half], _num(r["confidence"]), _num(r["goal_pct"]))
        text += (f"; the first {half} realisations of each alone give {h['difference_pct']:+.2f} % "
                 f"({h['interval_low_pct']:+.2f} to {h['interval_high_pct']:+.2f} %, "
                 f"{'within' if h['within_goal'] else 'not within'} +-{_num(r['goal_pct']):g} %)")
    return text + " (`figures/fe/full/window_summary.csv`, `window.csv`).\n"


BLOCKS["do1_window"] = do1_window
