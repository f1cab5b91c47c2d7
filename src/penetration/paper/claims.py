"""The paper's claims judged at each level of this replication: a verdict word and the one number that decides it.

Pure: the result tables in (``Evidence``: frames and records the task reads), rows out. Computed once, by the task
``tasks.reference.claims``, into ``figures/fe/{profile}/claims.csv``, which the report lays out; nothing else judges a
claim. Each claim row: ``claim_id``, the claim as the report states it, the level (a rung of ``levels.LADDER``, or
``erosion_free`` for the erosion-free FE target's rankings), the ``verdict``, its ``evidence`` (as the report states
it) and the one ``value`` that decides it where a single number does (a depth ratio, a depth in m, a relative
deceleration margin, a median error; else empty).

Verdicts: holds; weaker (deeper, by less than claimed); fails; matches or misses (depth ratios within GOAL_POINTS of
the paper's simulated ones; the DO1 depth within the paper's tolerance); fitted to it (a calibration, not a test);
cannot decide (the level's uncertainty spans the claim); good or poor (a level's out-of-sample median depth error
within VALIDATION_GOAL); "—" (the level does not compute it).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..levels import LEVELS
from .diff import above_one
from .verdict import FREE

GOAL_POINTS = 2  # a depth ratio within 2 points of the paper's simulated one: the criterion of the conclusions
VALIDATION_GOAL = 0.10  # a level predicts well when its median depth error is within 10 % (the summary's within_10pct)
LEAST_GAIN = {"DO/CRH 4.5": "text.gain_pct_crh45", "DO/CRH 3": "text.gain_pct_crh3"}  # claimed least gains (%)
GAIN_1200 = {"DO/CRH 4.5": "text.gain_1200_crh45", "DO/CRH 3": "text.gain_1200_crh3"}  # claimed gains (m)
PEAKS = {"trajectory": ("fig08", ""), "cavity": ("fig14", "(cavity level)"), "fe": ("fig14", "(FE level)")}
COLUMNS = ["claim_id", "claim", "level", "verdict", "evidence", "value"]
NAN = float("nan")


@dataclass(frozen=True)
class Evidence:
    """What the claims are judged on (frames as read from the outputs): the paper's values (reference CSV, by id),
    the nose contrasts of every level, the diff and the FE diff, the eroding FE contrasts' bands and extrapolation to
    zero element size (None: not built), each level's out-of-sample validation (its primary rows), the cavity and FE
    DO1 calibrations, the verdict table (the erosion-free target's contrasts at zero element size)."""
    paper: object            # the reference CSV indexed by id (value, tol, case)
    contrasts: object        # figures/nose_contrasts_table.csv
    diff: object             # figures/diff.csv
    fe_diff: object          # figures/fe/{profile}/diff.csv
    band: object             # figures/fe/contrast_band.csv
    extrapolation: object    # figures/fe/contrast_extrapolation.csv, or None
    validation: object       # figures/fe/{profile}/validation_levels_summary.csv
    cavity_scale: float      # the cavity level's DO1 strength scale
    fe_calibration: object   # figures/fe/{profile}/calibration_fe_do1.csv, its one row
    erosion_free: object     # figures/verdict.csv (its erosion-free rows are read)


def pct(ratio):
    return f"{100 * (ratio - 1):+.1f} %"


def only(frame, pick):
    """The one row of a diff picked by the boolean ``pick`` (an output whose rows changed fails here)."""
    rows = frame[pick]
    if len(rows) != 1:
        raise ValueError(f"{len(rows)} rows where a claim reads one: {rows.case.tolist()}")
    return rows.iloc[0]


def users_validation(summary):
    """Each level's validation row at the calibration users get (laboratory where the level has it), and the cavity
    level's row with the DO1 calibration."""
    primary = summary[summary.primary.astype(bool)]
    laboratory = set(primary.level[primary.calibration == "laboratory"])
    users = primary[(primary.calibration == "laboratory") | ~primary.level.isin(laboratory)].set_index("level")
    return users, primary[(primary.level == "cavity") & (primary.calibration == "do1")].iloc[0]


def mesh_spread(band, contrast, velocities=None):
    """The widest spread of a contrast over meshes of nearly one size (points) and its band row."""
    rows = band[(band.contrast == contrast) & (band.velocity_ms.isin(velocities) if velocities else True)]
    row = rows.loc[(rows.max_ratio - rows.min_ratio).idxmax()]
    return 100 * (row.max_ratio - row.min_ratio), row


def least_gain(ev, level, contrast):
    """'At least g % deeper at every velocity': the level's smallest depth ratio over Table 3's velocities."""
    claimed = 1 + float(ev.paper.value[LEAST_GAIN[contrast]]) / 100
    if level == "fe":
        return _fe_least_gain(ev, contrast, claimed)
    rows = ev.contrasts[ev.contrasts.contrast == contrast]
    low = rows.loc[rows[f"{level}_ratio"].idxmin()]
    ratio = low[f"{level}_ratio"]
    return (("holds" if ratio >= claimed else "weaker" if ratio > 1 else "fails"), f"{pct(ratio)} at {low.velocity:.0f} m/s",
            float(ratio))


def _fe_least_gain(ev, contrast, claimed):
    """The same claim from the zero-size intervals (or, without them, the spread of one mesh size: no verdict)."""
    if ev.extrapolation is None:
        return "cannot decide", f"meshes of one size spread it over {mesh_spread(ev.band, contrast)[0]:.0f} pts", NAN
    rows = ev.extrapolation[ev.extrapolation.contrast == contrast]
    straddle = rows[(rows.interval_low < claimed) & (rows.interval_high >= claimed)]
    if (rows.interval_low >= claimed).all():
        word, row = "holds", rows.loc[rows.interval_low.idxmin()]
    elif (rows.interval_high < claimed).any():
        row = rows.loc[rows.interval_high.idxmin()]
        word = "weaker" if row.interval_high > 1 else "fails"
    else:
        word, row = "cannot decide", straddle.loc[(straddle.interval_high - straddle.interval_low).idxmax()]
    return (word, f"{pct(row.interval_low)} to {pct(row.interval_high)} at zero element size ({row.velocity_ms:.0f} m/s)",
            NAN)


def gain_velocity(ev):
    return int(ev.paper.case["text.gain_1200_crh45"])


def gains_at_v(ev, level):
    """The claimed gains in metres at the claim's velocity: the level's depth ratios within GOAL_POINTS of the
    paper's."""
    v = gain_velocity(ev)
    if level == "fe":
        return _fe_gains_at_v(ev, v)
    nc = ev.contrasts
    rows = nc[(nc.velocity == v) & nc.contrast.isin(list(GAIN_1200))].set_index("contrast").loc[list(GAIN_1200)]
    off = 100 * (rows[f"{level}_ratio"] - rows.paper_sim_ratio).abs()
    return (("matches" if (off <= GOAL_POINTS).all() else "misses"),
            " and ".join(f"{g:+.2f} m" for g in rows[f"{level}_gain_m"]), NAN)


def _fe_gains_at_v(ev, v):
    if ev.extrapolation is None:
        spread = max(mesh_spread(ev.band, c, [v])[0] for c in GAIN_1200)
        return "cannot decide", f"meshes of one size spread them over up to {spread:.0f} pts", NAN
    rows = ev.extrapolation[(ev.extrapolation.velocity_ms == v)].set_index("contrast").loc[list(GAIN_1200)]
    half = 50 * (rows.interval_high - rows.interval_low)
    word = ("misses" if not rows.paper_inside_interval.astype(bool).all()
            else "matches" if (half <= GOAL_POINTS).all() else "cannot decide")
    return word, "zero-size intervals " + " and ".join(f"±{h:.0f} pts" for h in half), NAN


def do1_depth(ev, level):
    """The DO1 depth of Eq 9 or the trajectory with the paper's own S, and its deviation from the shot."""
    diff = ev.diff
    row = (only(diff, (diff.item == "fig15") & (diff.quantity == "pd_over_d") & diff.case.str.contains("S = 72"))
           if level == "analytic" else only(diff, (diff.item == "table2") & diff.case.str.contains("trajectory; S = 72")))
    measured = float(ev.paper.value["table2.dop"])
    depth = float(row.ours) / float(row.paper) * measured
    return depth, depth / measured - 1


def do1(ev, level):
    """The DO1 shot: the depth with the paper's own S (Eq 9, trajectory) or the parameter fitted to it."""
    if level == "cavity":
        return "fitted to it", f"strength × {ev.cavity_scale:.2f}", ev.cavity_scale
    if level == "fe":
        fit = ev.fe_calibration
        return "fitted to it", f"fs = {fit.value:.2f} at {1e3 * fit.element_size_m:.2f} mm", float(fit.value)
    depth, dev = do1_depth(ev, level)
    return (("matches" if abs(dev) <= float(ev.paper.tol["table2.dop"]) else "misses"),
            f"{depth:.2f} m ({100 * dev:+.0f} %) with the paper's S", depth)


def peak_margin(ev, level):
    """The double ogive's peak deceleration relative to the other noses', its largest (least negative) value."""
    frame, (item, tag) = (ev.fe_diff if level == "fe" else ev.diff), PEAKS[level]
    rows = frame[(frame.item == item) & frame.quantity.str.startswith("peak_deceleration_double_ogive_minus")
                 & frame.case.str.contains(tag, regex=False)]
    return rows.ours.astype(float).max()


def smaller_peak(ev, level):
    if level not in PEAKS:
        return "—", "no deceleration history", NAN
    worst = peak_margin(ev, level)
    word = ("holds" if worst < 0 else "fails") + (" on one mesh" if level == "fe" else "")
    return (word, f"{-100 * worst:.1f} % lower at least" if worst < 0 else f"{100 * worst:+.1f} % higher at worst",
            float(worst))


def predicts(ev, level):
    err = users_validation(ev.validation)[0].median_abs_rel_err[level]
    return ("good" if err <= VALIDATION_GOAL else "poor"), f"median error {100 * err:.1f} %", float(err)


def claims(ev):
    """(claim_id, the claim as stated, its judge(ev, level)) for each claim of the bottom line, in order."""
    value = lambda key: float(ev.paper.value[key])
    nc = ev.contrasts
    v_lo, v_hi = nc.velocity.min(), nc.velocity.max()
    shots = users_validation(ev.validation)[0].shots["analytic"]
    return [
        ("least_gain_crh45", f"The double ogive goes at least {value('text.gain_pct_crh45'):g} % deeper than the CRH "
         f"4.5 ogive of the same nose length, at every velocity ({v_lo}–{v_hi} m/s)",
         lambda ev, lv: least_gain(ev, lv, "DO/CRH 4.5")),
        ("least_gain_crh3", f"… and at least {value('text.gain_pct_crh3'):g} % deeper than the CRH 3 ogive",
         lambda ev, lv: least_gain(ev, lv, "DO/CRH 3")),
        ("gains_at_v", f"At {gain_velocity(ev)} m/s it goes {value('text.gain_1200_crh45'):.2f} m deeper than the CRH "
         f"4.5 ogive and {value('text.gain_1200_crh3'):.2f} m deeper than the CRH 3 ogive", gains_at_v),
        ("do1", f"Theory and simulation match the DO1 shot, {value('table2.dop'):g} m at "
         f"{value('table2.velocity'):g} m/s", do1),
        ("smaller_peak", "The double ogive has the smallest peak deceleration (Figs 8 and 14)", smaller_peak),
        ("predicts", f"<i>Ours, not the paper's:</i> each level predicts the {shots} published shots it was not "
         f"fitted to (median depth error within {100 * VALIDATION_GOAL:.0f} %)", predicts),
    ]


def contrast_ranking(rows):
    """The paper's ranking (the ratio above 1) of one contrast over its velocities on the erosion-free target, from
    the verdict table's erosion-free rows (value +- uncertainty at zero element size, one row per velocity the study
    runs; diff.above_one at each): holds or fails where every velocity's does, else undecided. Returns (the word, the
    phrase the report states: each velocity's value +- uncertainty, that the study found no limit where it did not,
    pending where it has not run)."""
    words, parts = set(), []
    for _, r in rows.sort_values("velocity_ms").iterrows():
        value, u, limit = float(r.value), float(r.uncertainty), str(r.limit) == "True"
        words.add(above_one(value, u, limit))
        parts.append(f"{float(r.velocity_ms):g} m/s " + (f"{value:.3f} ± {u:.3f}" + ("" if limit else " (no limit)")
                                                         if value == value else "pending"))
    word = words.pop() if len(words) == 1 else "undecided"
    return word, f"{word if word != 'undecided' else 'is undecided'} ({'; '.join(parts)} at zero element size)"


def claim_rows(ev):
    """Every claim at every level (the bottom line), then the paper's ranking of each contrast on the erosion-free
    target: rows of COLUMNS."""
    rows = [{"claim_id": cid, "claim": claim, "level": level,
             **dict(zip(("verdict", "evidence", "value"), judge(ev, level)))}
            for cid, claim, judge in claims(ev) for level in LEVELS]
    free = ev.erosion_free
    for contrast, g in free[free.model == FREE].groupby("contrast", sort=False):
        word, phrase = contrast_ranking(g)
        rows.append({"claim_id": f"ranking {contrast}", "claim": f"{contrast} above 1 (the paper's ranking)",
                     "level": "erosion_free", "verdict": word, "evidence": phrase, "value": NAN})
    return rows
