"""The diff of the paper's numbers against ours, row by row.

Each row compares one number the paper states with ours, checks the paper against its own numbers, or shows a
number that rests on something the paper does not state. Its status says which, and what a row that holds is
worth: only ``reproduced`` is a computed depth, deceleration, share or contrast within tolerance with nothing
fitted (STATUS_MEANINGS has every status).
"""
from __future__ import annotations

import collections
import itertools
from dataclasses import dataclass

from scipy.interpolate import PchipInterpolator

from ..studies import chaos, grid
from .reference import TABLE3_NOSES, UNITS, VELOCITIES, Ref

COLUMNS = ("item", "quantity", "case", "paper", "ours", "rel_err", "tol", "status")
# each status and what it says, in the order the counts are shown
STATUS_MEANINGS = {
    "reproduced": "a computed number (depth, deceleration, share, contrast) within the stated tolerance, nothing fitted",
    "predicted": "the paper's measured shot (DO1) within tolerance, from a level whose one factor was fitted on other "
                 "shots (the laboratory series), never on it",
    "geometry": "an exact result of the nose's shape (N*, mass, a shape rate) within tolerance",
    "ordering": "a sign, ordering or axis bound the paper states, which ours satisfies (no magnitude compared)",
    "paper-consistent": "the paper checked against its own numbers, which agree (nothing of ours involved)",
    "agrees-after-calibration": "within tolerance, but a calibration on the DO1 shot produced the agreement: not a "
                                "reproduction",
    "deviates": "ours is outside the tolerance, or the sign or ordering fails",
    "undecided": "a value known only within an interval (such as an FE result extrapolated to zero element size) "
                 "that holds both the paper's value and values outside the tolerance",
    "paper-inconsistent": "the paper contradicts itself there",
    "not-derivable": "the paper does not give what the value needs",
}
STATUSES = tuple(STATUS_MEANINGS)
# the statuses of a row that holds: a rebuild must keep them (tasks.reference.reproduction_problems)
AGREES = ("reproduced", "predicted", "geometry", "ordering", "paper-consistent", "agrees-after-calibration")


@dataclass(frozen=True)
class Row:
    item: str
    quantity: str
    case: str
    paper: float
    ours: float
    rel_err: float
    tol: float
    status: str

    def __post_init__(self):
        if any("," in t for t in (self.item, self.quantity, self.case)):
            raise ValueError(f"diff labels may not contain commas: {self.quantity!r} / {self.case!r}")
        if self.status not in STATUSES:
            raise ValueError(f"unknown status {self.status!r}")


def _rel(paper, ours):
    return abs(ours - paper) / abs(paper) if paper != 0 else abs(ours - paper)


def holds(relation, paper, ours, tol):
    """Whether ours satisfies the paper's statement ``ours <relation> paper``."""
    if relation == "eq":
        return _rel(paper, ours) <= tol
    return {"le": ours <= paper, "ge": ours >= paper, "lt": ours < paper, "gt": ours > paper}[relation]


def agreement(ok: bool, calibrated: bool, kind: str = "reproduced") -> str:
    """Status of a comparison: ``kind`` (reproduced, geometry or ordering) when it holds from the stated inputs,
    agrees-after-calibration when it holds after a calibration, deviates when it fails."""
    if not ok:
        return "deviates"
    return "agrees-after-calibration" if calibrated else kind


def compare(ref: Ref, ours: float, case: str | None = None, quantity: str | None = None, calibrated=False,
            kind="reproduced") -> Row:
    """Our value (in the reference's units) against the paper's.

    ``calibrated``: ours comes from a model with a parameter calibrated on a measured shot, so agreement is reported
    as such, never as reproduction. ``kind``: the status when it holds with nothing calibrated: ``reproduced`` (a
    computed number, also against a bound the paper states for it), ``geometry`` (an exact result of the nose's
    shape) or ``ordering`` (a sign, or a value inside a figure's axis range).
    """
    ok = holds(ref.relation, ref.value, ours, ref.tol)
    return Row(ref.item, quantity or ref.quantity, case or ref.case, ref.value, ours,
               _rel(ref.value, ours), ref.tol, agreement(ok, calibrated, kind))


def unstated(ref: Ref, ours: float, case: str | None = None) -> Row:
    """A value that rests on an inference of data the paper leaves out."""
    return Row(ref.item, ref.quantity, case or ref.case, ref.value, ours, _rel(ref.value, ours), ref.tol,
               "not-derivable")


def consistency(ref: Ref, recomputed: float, tol: float, case: str | None = None, quantity: str | None = None) -> Row:
    """The paper's number against its own arithmetic from other stated numbers."""
    err = _rel(ref.value, recomputed)
    return Row(ref.item, quantity or ref.quantity, case or ref.case, ref.value, recomputed, err, tol,
               "paper-consistent" if err <= tol else "paper-inconsistent")


def _decimals(x: float) -> int:
    s = repr(float(x)).rstrip("0")
    return len(s.split(".")[1]) if "." in s else 0


def printed_interval(fn, refs):
    """Range of fn over the rounding intervals of the referenced values.

    Each input is known to +-half a unit of its last printed digit (three
    decimals for Table 3's DOPs); the range of fn over those corners bounds
    what the paper's own arithmetic can give.
    """
    halves = [0.5 * 10.0 ** -max(_decimals(r.value), 3) for r in refs]
    vals = [fn(*[r.value + s * h for r, s, h in zip(refs, signs, halves)])
            for signs in itertools.product((-1, 1), repeat=len(refs))]
    return min(vals), max(vals)


def arithmetic_check(ref: Ref, fn, inputs, case=None, quantity=None) -> Row:
    """Paper cell against fn(inputs) with printing uncertainty on both sides."""
    lo, hi = printed_interval(fn, inputs)
    mid = 0.5 * (lo + hi)
    slack = 0.5 * (hi - lo) + 0.5 * 10.0 ** -_decimals(ref.value)
    tol = slack / abs(ref.value) if ref.value else slack
    ok = lo - 0.5 * 10.0 ** -_decimals(ref.value) <= ref.value <= hi + 0.5 * 10.0 ** -_decimals(ref.value)
    return Row(ref.item, quantity or ref.quantity, case or ref.case, ref.value, mid, _rel(ref.value, mid), tol,
               "paper-consistent" if ok else "paper-inconsistent")


# ------------------------------------------------------------- diff builders
def table1_rows(refs):
    """Table 1 against itself: bulk modulus, Young's modulus, reference rate."""
    R = refs
    ke = R["table1.pc"].si / R["table1.muc"].si
    g = R["table1.K"].si
    e_implied = 9 * ke * g / (3 * ke + g)
    return [
        consistency(R["table1.K"], ke / 1e9, 0.005, quantity="K (as elastic bulk modulus pc/muc)"),
        consistency(R["table1.E"], e_implied / 1e9, 0.005, quantity="E (from Ke = pc/muc and G = K column)"),
        consistency(R["table1.eps0_printed"], R["table1.eps0_text"].value, 0.0, quantity="eps0 (Table 1 vs text)"),
    ]


def table3_rows(refs):
    """Table 3's derived columns against its own DOP columns."""
    R, rows = refs, []
    for v in VELOCITIES:
        for nose in TABLE3_NOSES:
            sim, calc = R[f"table3.sim.{v}.{nose}"], R[f"table3.calc.{v}.{nose}"]
            cell = R[f"table3.reldev.{v}.{nose}"]
            checks = [arithmetic_check(cell, lambda s, c: 100 * abs(s - c) / base(s, c), [sim, calc],
                                       case=f"{v} {nose} (|sim-calc|/{name})")
                      for name, base in (("sim", lambda s, c: s), ("calc", lambda s, c: c))]
            good = [r for r in checks if r.status == "paper-consistent"]
            rows.append(good[0] if good else min(checks, key=lambda r: r.rel_err))
        for nose in ("double_ogive", "crh45"):
            cell = R[f"table3.inc_crh3.{v}.{nose}"]
            rows.append(arithmetic_check(cell, lambda a, b: 100 * (a / b - 1),
                                         [R[f"table3.sim.{v}.{nose}"], R[f"table3.sim.{v}.crh3"]],
                                         case=f"{v} {nose} (simulation column)"))
        cell = R[f"table3.inc_equiv.{v}.double_ogive"]
        rows.append(arithmetic_check(cell, lambda a, b: 100 * (a / b - 1),
                                     [R[f"table3.sim.{v}.double_ogive"], R[f"table3.sim.{v}.crh45"]],
                                     case=f"{v} double_ogive (simulation column)"))
    rows.append(table3_sim_at_shot(R))
    gain = lambda a, b: a - b
    rows.append(arithmetic_check(R["text.gain_1200_crh45"], gain,
                                 [R["table3.sim.1200.double_ogive"], R["table3.sim.1200.crh45"]], case="1200 (Table 3 simulation)"))
    rows.append(arithmetic_check(R["text.gain_1200_crh3"], gain,
                                 [R["table3.sim.1200.double_ogive"], R["table3.sim.1200.crh3"]], case="1200 (Table 3 simulation)"))
    for key, other in (("text.gain_pct_crh3", "inc_crh3"), ("text.gain_pct_crh45", "inc_equiv")):
        ref = R[key]
        least = min(R[f"table3.{other}.{v}.double_ogive"].value for v in VELOCITIES)
        ok = holds(ref.relation, ref.value, least, ref.tol)
        rows.append(Row(ref.item, ref.quantity, "smallest Table 3 increment (claim read as a lower bound)", ref.value,
                        least, _rel(ref.value, least), ref.tol, "paper-consistent" if ok else "paper-inconsistent"))
    return rows


def table3_sim_at_shot(R):
    """Table 3's simulated double-ogive row at the DO1 shot's velocity against the shot.

    Fig 12 and the text (l.248-251) say the simulation matches the 5.1 m
    shot; Table 3 runs the same projectile at 500-1200 m/s. A monotone cubic
    through its four simulated depths gives the paper's own simulated depth
    at 835 m/s, judged at the shot's tolerance.
    """
    shot, vs = R["table2.dop"], R["table2.velocity"]
    row = PchipInterpolator(VELOCITIES, [R[f"table3.sim.{v}.double_ogive"].value for v in VELOCITIES])
    return consistency(shot, float(row(vs.value)), shot.tol, quantity="dop_simulation_interpolated",
                       case=f"DO1 at {vs.value:g} m/s: Table 3 simulation row (PCHIP in v) vs the shot Fig 12 matches")


def table4_rows(refs, ours):
    """Table 4, Fig 16 legend and the mass claims of the text.

    ``ours`` maps 'nstar.<nose>' and 'mass.<nose>' to our values (SI) for
    noses cone, minimum_nstar, double_ogive, crh45.
    """
    R, rows = refs, []
    key = {"cone": "cone", "jones": "minimum_nstar", "double_ogive": "double_ogive", "crh45": "crh45"}
    for short, nose in key.items():
        inferred = nose == "double_ogive"
        for item in ("table4", "fig16"):
            ref = R[f"{item}.nstar.{short}"]
            rows.append(unstated(ref, ours[f"nstar.{nose}"]) if inferred else
                        compare(ref, ours[f"nstar.{nose}"], kind="geometry"))
        ref = R[f"table4.mass.{short}"]
        rows.append(unstated(ref, ours[f"mass.{nose}"]) if inferred else compare(ref, ours[f"mass.{nose}"], kind="geometry"))
        ratio = ours[f"mass.{nose}"] / ours["mass.crh45"]
        ref = R[f"table4.ratio.{short}"]
        rows.append(unstated(ref, ratio) if inferred else compare(ref, ratio, kind="geometry"))
        if short != "crh45":
            rows.append(arithmetic_check(ref, lambda m, m45: m / m45, [R[f"table4.mass.{short}"], R["table4.mass.crh45"]],
                                         case=f"{nose} (paper masses)"))
    rows.append(consistency(R["table4.nstar.cone"], R["fig16.nstar.cone"].value, R["table4.nstar.cone"].tol,
                            case="cone (Table 4 vs Fig 16 legend)"))
    for ref_id, other in (("text.mass_gain_cone", "cone"), ("text.mass_gain_jones", "jones")):
        rows.append(arithmetic_check(R[ref_id], lambda m, mo: 100 * (m / mo - 1),
                                     [R["table4.mass.double_ogive"], R[f"table4.mass.{other}"]], case="paper masses"))
        rows.append(unstated(R[ref_id], 100 * (ours["mass.double_ogive"] / ours[f"mass.{key[other]}"] - 1),
                             case="our masses (inferred double ogive)"))
    return rows


def fig03_rows(refs, bands):
    """Fig 3 statements against the CRH 3 shape rate under each k convention.

    ``bands`` maps convention -> dict(lo, hi, peak_x, peak_k), and
    'adopted' names the convention used downstream.
    """
    R, adopted = refs, bands["adopted"]
    b = bands[adopted]
    rows = [compare(R["fig03.k_peak_x"], b["peak_x"], kind="geometry"),
            compare(R["fig03.middle_max"], b["hi"] - b["lo"], case=f"crh3 (k as {adopted})", kind="geometry"),
            compare(R["fig03.k_axis_max"], b["peak_k"], case=f"crh3 (k as {adopted})", quantity="k_peak <= axis max",
                    kind="ordering"),
            compare(R["fig03.nstar_axis_max"], bands["nstar_crh3"], quantity="N* of CRH 3 <= axis max", kind="ordering")]
    ref, peak = R["fig03.k_axis_max"], bands["dN/d(x/b)"]["peak_k"]
    rows.append(Row(ref.item, "k_peak <= axis max", "crh3 (k as labelled: dN*/d(x/b))", ref.value, peak,
                    _rel(ref.value, peak), 0.0, "ordering" if peak <= ref.value else "paper-inconsistent"))
    return rows


def fig05_rows(refs, ours):
    """Fig 5 claim: at the CRH 5 length the double ogive has the smallest N*."""
    R = refs
    return [compare(R["fig05.do_below_crh5"], ours["nstar.fig4_double_ogive"] - ours["nstar.fig4_crh5"], kind="ordering"),
            compare(R["fig05.do_below_crh3"], ours["nstar.fig4_double_ogive"] - ours["nstar.fig4_crh3"], kind="ordering")]


CONTRAST_COLUMNS = (("paper_sim", "paper sim."), ("paper_calc", "paper calc."), ("analytic", "Eq 9 (S cal.)"),
                    ("analytic_stated_S", "Eq 9 (stated S)"), ("trajectory", "trajectory"), ("cavity", "cavity"))


def contrast_summary(table, velocities=(500.0, 1200.0)) -> list:
    """Markdown lines: the nose-shape contrasts at the given velocities, every source side by side.

    table: rows of ``figures/nose_contrasts_table.csv`` (ratio and gain per source). The cavity level's calibration
    variants are a study of their own (figures/cavity_variant_contrasts.csv, `make studies`).
    """
    head = " | ".join(label for _, label in CONTRAST_COLUMNS)
    lines = ["## Nose-shape contrasts: the paper's conclusions (figures/nose_contrasts_table.csv)", "",
             "Depth ratios; every level except the stated-S Eq 9 is calibrated on DO1, so these contrasts, not the "
             "absolute depths, are what a calibration cannot set. Their range over the cavity level's calibration "
             "variants is the study figures/cavity_variant_contrasts.csv.", "",
             f"| contrast | v (m/s) | {head} |", "|---|---|" + "---|" * len(CONTRAST_COLUMNS)]
    for r in table:
        if r["velocity"] in velocities:
            cells = " | ".join(f"{r[f'{k}_ratio']:.3f}" for k, _ in CONTRAST_COLUMNS)
            lines.append(f"| {r['contrast']} | {r['velocity']:.0f} | {cells} |")
    return lines + [""]


def summary(rows, findings, pending, contrasts=()) -> str:
    """Markdown summary: counts per status, the nose contrasts, worst deviations, findings."""
    lines = ["# Reproduction diff", "", "| status | rows | meaning |", "|---|---|---|"]
    for s in STATUSES:
        lines.append(f"| {s} | {sum(r.status == s for r in rows)} | {STATUS_MEANINGS[s]} |")
    if len(contrasts):
        lines += [""] + contrast_summary(contrasts)
    lines += ["", "## Largest relative errors among compared values (equalities with a tolerance)", "",
              "| item | quantity | case | paper | ours | rel_err | tol | status |", "|---|---|---|---|---|---|---|---|"]
    worst = sorted((r for r in rows if r.status in AGREES + ("deviates",) and r.tol > 0),
                   key=lambda r: -r.rel_err)[:10]
    lines += [f"| {r.item} | {r.quantity} | {r.case} | {r.paper:.6g} | {r.ours:.6g} | {r.rel_err:.3g} | {r.tol:.3g} | {r.status} |"
              for r in worst]
    lines += ["", "## Where the paper contradicts itself (from the arithmetic)", ""]
    lines += [f"- {r.item} {r.quantity} [{r.case}]: paper {r.paper:.6g}, its own numbers give {r.ours:.6g}"
              for r in rows if r.status == "paper-inconsistent"]
    lines += ["", "## Findings recorded by hand (workflow/reference/findings.csv)", ""]
    lines += [f"- **{f['id']}** ({f['kind']}, {f['where']}): {f['what']}. Decision: {f['decision']}." for f in findings]
    lines += ["", "## Reference values not compared yet (later stages)", "", ", ".join(pending) or "none", ""]
    return "\n".join(lines)


def _row(ref, quantity, case, ours, status):
    return Row(ref.item, quantity, case, ref.value, ours, _rel(ref.value, ours), ref.tol, status)


def table3_model_rows(refs, table3, fit_rows):
    """Table 3's calculated DOPs against ours; the text's 1200 m/s gains.

    table3: rows with velocity_ms, nose, analytic_m (S calibrated on DO1),
    analytic_stated_S_m; fit_rows: cells of the fit to this column.
    """
    R, rows = refs, []
    for r in table3:
        ref = R[f"table3.calc.{r['velocity_ms']}.{r['nose']}"]
        rows.append(compare(ref, r["analytic_m"], case=f"{ref.case} (Eq 9; S calibrated on DO1)", calibrated=True))
        rows.append(compare(ref, r["analytic_stated_S_m"], case=f"{ref.case} (Eq 9; S = 72 fc^-0.5)"))
    for c in fit_rows:
        ref = R[c["id"]]
        rows.append(unstated(ref, c["depth"] * (1 + c["relative_residual"]), case=f"{ref.case} (S fitted to this column)"))
    by = {(r["velocity_ms"], r["nose"]): r["analytic_m"] for r in table3}
    for key, other in (("text.gain_1200_crh45", "crh45"), ("text.gain_1200_crh3", "crh3")):
        rows.append(compare(R[key], by[(1200, "double_ogive")] - by[(1200, other)],
                            case="1200 (ours: Eq 9 calibrated on DO1; paper's from simulation)", calibrated=True))
    return rows


def experiment_rows(refs, do1_stated, do1_calibrated_S):
    """DO1 (Table 2): our DOP with the stated S, and the calibration that fits it."""
    ref = refs["table2.dop"]
    return [compare(ref, do1_stated, case="DO1 (trajectory; S = 72 fc^-0.5)"),
            _row(ref, "dop", f"DO1 (S calibrated to it: S = {do1_calibrated_S:.4g})", ref.value, "not-derivable")]


def scale_do1_rows(refs, tables):
    """DO1 as a test instead of a calibration: its depth predicted at each level with and without each variant of the
    scale effect (``tables``: level -> the rows of figures/scale/do1_LEVEL.csv), the level's one factor fitted on
    the laboratory shots with the variant; DO1 is in no fit, so a depth within tolerance is ``predicted``."""
    ref = refs["table2.dop"]
    rows = []
    for level, table in tables.items():
        for r in table:
            ours = float(r["dop_pred_m"])
            effect = "without the scale effect" if r["variant"] == "none" else f"with the scale effect {r['variant']}"
            case = (f"DO1 predicted at the {level} level {effect} ({r['parameter']} {float(r['value']):.4g} fitted on "
                    "the laboratory shots; DO1 in no fit)")
            ok = holds(ref.relation, ref.value, ours, ref.tol)
            rows.append(Row(ref.item, ref.quantity, case, ref.value, ours, _rel(ref.value, ours), ref.tol,
                            "predicted" if ok else "deviates"))
    return rows


def ordering_rows(refs, sec22):
    """Figs 8-9 statements: peak decelerations and depths of the three noses.

    sec22: dict (nose, velocity) -> dict(peak, dop, duration) at the chosen diameter.
    """
    R, rows = refs, []
    vel = sorted({v for _, v in sec22})
    for ref_id, a, b, q in (("fig08.peak_do_below_crh3", "double_ogive", "crh3", "peak"),
                            ("fig08.peak_do_below_crh5", "double_ogive", "crh5", "peak"),
                            ("fig08.peak_crh3_above_crh5", "crh3", "crh5", "peak"),
                            ("fig09.do_deepest_crh3", "double_ogive", "crh3", "dop"),
                            ("fig09.do_deepest_crh5", "double_ogive", "crh5", "dop")):
        ref = R[ref_id]
        for v in vel:
            diff = sec22[(a, v)][q] - sec22[(b, v)][q]
            scale = sec22[(b, v)][q]
            rows.append(_row(ref, ref.quantity + " (relative)", f"{v:.0f} m/s", diff / scale,
                             agreement(holds(ref.relation, 0.0, diff, 0.0), False, "ordering")))
    for v in vel:
        ref = R[f"fig09.t_axis_max.{v:.0f}"]
        longest = max(sec22[(n, w)]["duration"] for n, w in sec22 if w == v) * 1e3
        rows.append(compare(ref, longest, case=f"{v:.0f} m/s: longest penetration time (ms)", kind="ordering"))
    return rows


def fig01_rows(refs, shares):
    """Fig 1 statements; shares: list of dicts fc, velocity, static_share, inertial_share."""
    R = refs
    by_fc = collections.defaultdict(dict)
    for s in shares:
        by_fc[s["fc"]][s["velocity"]] = s
    fcs = sorted(by_fc)
    grow_fc = min(by_fc[b][v]["static_share"] - by_fc[a][v]["static_share"]
                  for a, b in zip(fcs, fcs[1:]) for v in by_fc[a] if v > 0)
    grow_v = min(by_fc[f][w]["inertial_share"] - by_fc[f][v]["inertial_share"]
                 for f in fcs for v, w in zip(sorted(by_fc[f]), sorted(by_fc[f])[1:]))
    al = R["fig01.aluminium"]
    return [_row(al, al.quantity, al.case, float("nan"), "not-derivable"),
            _row(R["fig01.static_grows_with_fc"], "least increase of the static share between strengths",
                 "v > 0", grow_fc, agreement(grow_fc > 0, False, "ordering")),
            _row(R["fig01.inertial_grows_with_v"], "least increase of the inertial share between velocities",
                 "all strengths", grow_v, agreement(grow_v > 0, False, "ordering"))]


def fig15_rows(refs, fig15, do1_pd_stated, do1_pd_calibrated):
    """Fig 15: ordering at 1200 m/s and the DO1 experiment point."""
    R = refs
    at = {(r["nose"], r["velocity"]): r for r in fig15}
    diff = at[("minimum_nstar", 1200.0)]["dop"] - at[("double_ogive", 1200.0)]["dop"]
    ref = R["fig15.minimum_nstar_deepest"]
    ex = R["fig15.do1_experiment"]
    return [_row(ref, ref.quantity, ref.case + " (Eq 9; S calibrated on DO1)", diff, agreement(diff > 0, True)),
            compare(ex, do1_pd_stated, case="DO1 835 m/s (ours; S = 72 fc^-0.5)"),
            _row(ex, ex.quantity, "DO1 835 m/s (ours; S calibrated to it)", do1_pd_calibrated, "not-derivable")]


def level_rows(refs, cells, shots, level, calibration):
    """A simulation level against Table 3's simulation column, the 1200 m/s gains and Fig 14's claims and axes.

    cells: rows (velocity_ms, nose, depth); shots: rows (nose, velocity,
    peak_deceleration_m_s2, duration); ``level``: its label in the cases
    ("cavity level"); ``calibration``: what was calibrated on DO1.
    """
    R, rows = refs, []
    for r in cells:
        ref = R[f"table3.sim.{r['velocity_ms']}.{r['nose']}"]
        rows.append(compare(ref, r["depth"], case=f"{ref.case} ({level}; {calibration})", calibrated=True))
    by = {(r["velocity_ms"], r["nose"]): r["depth"] for r in cells}
    for key, other in (("text.gain_1200_crh45", "crh45"), ("text.gain_1200_crh3", "crh3")):
        rows.append(compare(R[key], by[(1200, "double_ogive")] - by[(1200, other)], case=f"1200 (ours: {level})",
                            calibrated=True))
    at = {(c["nose"], c["velocity"]): c for c in shots}
    velocities = sorted({c["velocity"] for c in shots})
    for ref_id, other, q in (("fig14.peak_do_below_crh3", "crh3", "peak_deceleration_m_s2"),
                             ("fig14.peak_do_below_crh45", "crh45", "peak_deceleration_m_s2"),
                             ("fig14.pulse_do_longer_crh3", "crh3", "duration"),
                             ("fig14.pulse_do_longer_crh45", "crh45", "duration")):
        ref = R[ref_id]
        for v in velocities:
            diff = at[("double_ogive", v)][q] - at[(other, v)][q]
            rows.append(_row(ref, ref.quantity + " (relative)", f"{v:.0f} m/s ({level})", diff / at[(other, v)][q],
                             agreement(holds(ref.relation, 0.0, diff, 0.0), True)))
    for v in velocities:
        at_v = [c for c in shots if c["velocity"] == v]
        peak = max(at_v, key=lambda c: c["peak_deceleration_m_s2"])
        longest = max(c["duration"] for c in at_v)
        ref = R[f"fig14.g_axis_max.{v:.0f}"]
        rows.append(compare(ref, peak["peak_deceleration_m_s2"] / UNITS[ref.unit],
                            case=f"{v:.0f} m/s: largest peak (g; {peak['nose']}; {level})", calibrated=True))
        for kind in ("t_axis_max", "t_axis_last"):
            ref = R[f"fig14.{kind}.{v:.0f}"]
            rows.append(compare(ref, longest / UNITS[ref.unit], case=f"{v:.0f} m/s: longest time to rest (ms; {level})",
                                calibrated=True))
    return rows


def cavity_rows(refs, table3, cavity, do1_depth, scale):
    """Cavity level: Table 3's simulation column, the 1200 m/s gains, Fig 14, Fig 12.

    table3: rows with velocity_ms, nose, cavity_m; cavity: rows of the cavity
    Table 3 scene (nose, velocity, peak_deceleration_m_s2, duration).
    """
    R = refs
    rows = level_rows(refs, [{**r, "depth": r["cavity_m"]} for r in table3], cavity, "cavity level",
                      "strength scale calibrated on DO1")
    ref = R["table2.dop"]
    rows.append(_row(ref, "dop", f"DO1 (cavity level; strength scale {scale:.4g} calibrated to it)", do1_depth,
                     "not-derivable"))
    return rows


def fe_rows(refs, table3, ratios, do1_depth, fs, element_size):
    """Finite-element level: level_rows, the Table 3 increments (goal: within 2 points), the DO1 calibration, fs.

    table3: rows of figures/fe/{profile}/table3.csv; ratios: rows of its _ratios file.
    """
    level, cal = "FE level", f"fs calibrated on DO1 at h = {element_size * 1e3:.3g} mm"
    cells = [{"velocity_ms": int(r["velocity_ms"]), "nose": r["nose"], "depth": r["fe_m"]} for r in table3]
    shots = [{"nose": r["nose"], "velocity": float(r["velocity_ms"]), "peak_deceleration_m_s2": r["peak_deceleration_m_s2"],
              "duration": r["time_to_rest_s"]} for r in table3]
    rows = level_rows(refs, cells, shots, level, cal)
    for r in ratios:
        prefix, nose = FE_INCREMENTS[r["contrast"]]
        ref = refs[f"{prefix}.{int(r['velocity_ms'])}.{nose}"]
        ours = 100 * (r["fe_ratio"] - 1)
        ok = abs(ours - ref.value) <= 2.0
        rows.append(Row(ref.item, ref.quantity + " (within 2 points)", f"{ref.case} ({level}; {cal})", ref.value, ours,
                        _rel(ref.value, ours), 2.0 / abs(ref.value), agreement(ok, True)))
    ref = refs["table2.dop"]
    rows.append(_row(ref, "dop", f"DO1 ({level}; fs = {fs:.4g} calibrated to it at h = {element_size * 1e3:.3g} mm)",
                     do1_depth, "not-derivable"))
    table3_velocities = {int(r["velocity_ms"]) for r in table3}
    for key, contrast in TEXT_GAINS:
        sel = [r for r in ratios if r["contrast"] == contrast and int(r["velocity_ms"]) in table3_velocities]
        rows.append(text_gain_row(refs[key], sel, "fe_ratio", "velocity_ms", f"{level}; {cal}", calibrated=True))
    rows.append(unstated(refs["table1.fs"], fs, case=f"{level}: failure strain calibrated on DO1 at h = "
                         f"{element_size * 1e3:.3g} mm (the paper's 0.38 belongs to its unstated 3-D mesh)"))
    return rows


FE_INCREMENTS = {"DO/CRH 4.5": ("table3.inc_equiv", "double_ogive"), "DO/CRH 3": ("table3.inc_crh3", "double_ogive"),
                 "CRH 4.5/CRH 3": ("table3.inc_crh3", "crh45")}


def interval_status(paper, low, high, tol, calibrated=True):
    """A value known within [low, high] against the paper's, to an absolute tolerance: agrees when the whole
    interval lies within it, deviates when the interval excludes the paper's value, undecided otherwise."""
    if paper - tol <= low and high <= paper + tol:
        return agreement(True, calibrated)
    return "deviates" if not low <= paper <= high else "undecided"


def fe_limit_rows(refs, limits):
    """The Table 3 increments of the eroding FE level at zero element size (a study: the contrasts of many meshes,
    each calibrated on DO1, fitted against the element size and extrapolated; rows of
    figures/fe/contrast_extrapolation.csv), judged on their intervals by interval_status (goal: 2 points)."""
    rows = []
    for r in limits:
        prefix, nose = FE_INCREMENTS[r["contrast"]]
        ref = refs[f"{prefix}.{int(r['velocity_ms'])}.{nose}"]
        ours, lo, hi = (100 * (float(r[k]) - 1) for k in ("ratio_at_zero_size", "interval_low", "interval_high"))
        case = (f"{ref.case} (FE level at zero element size; a line through {int(r['meshes'])} meshes each calibrated "
                f"on DO1; {100 * float(r['confidence']):.0f} % interval {lo:.1f} to {hi:.1f} points; a study)")
        rows.append(Row(ref.item, ref.quantity + " at zero element size (within 2 points)", case, ref.value, ours,
                        _rel(ref.value, ours), 2.0 / abs(ref.value), interval_status(ref.value, lo, hi, 2.0)))
    return rows


# the text's '+10 % over CRH 3, +5 % over the equivalent nose at the same velocity': reference id, contrast
TEXT_GAINS = (("text.gain_pct_crh3", "DO/CRH 3"), ("text.gain_pct_crh45", "DO/CRH 4.5"))


def text_gain_row(ref, ratios, ratio, velocity, what, calibrated):
    """One of TEXT_GAINS, read as a lower bound over Table 3's velocities: the smallest gain among ratios (rows
    of its contrast, with the ratio and the velocity in the columns so named) against it."""
    least = min(ratios, key=lambda c: c[ratio])
    return compare(ref, 100 * (least[ratio] - 1), calibrated=calibrated,
                   case=f"smallest over 500-1200 m/s ({float(least[velocity]):.0f} m/s; {what})")


# the model levels whose nose contrasts are compared with the text's claims: (level, variant, calibrated)
CONTRAST_LEVELS = (("analytic", "Eq 9, S calibrated on DO1", True), ("analytic", "Eq 9, S = 72 fc^-0.5", False),
                   ("cavity", "strength scale calibrated on DO1", True))


def contrast_rows(refs, contrasts):
    """The text's '+10 % over CRH 3, +5 % over the equivalent nose at the same velocity' at each model level.

    contrasts: rows (level, variant, source, velocity, contrast, ratio, gain_m) of
    the nose-contrast table; the claim is read as a lower bound over Table 3's
    velocities, so ours is the smallest gain over them.
    """
    rows = []
    for key, contrast in TEXT_GAINS:
        for level, variant, calibrated in CONTRAST_LEVELS:
            sel = [c for c in contrasts if c["level"] == level and c["variant"] == variant
                   and c["source"] == "table3" and c["contrast"] == contrast]
            rows.append(text_gain_row(refs[key], sel, "ratio", "velocity", f"{level}: {variant.replace(',', ';')}",
                                      calibrated))
    return rows


def _flag(value) -> bool:
    """A boolean of a study's rows, read alike from its CSV (text) and from Python values."""
    return str(value) == "True"


def _chaos_basis(r) -> str:
    """How the erosion-free study reached one row (studies.chaos.chaos_rows): its meshes and realisations, and
    whether its line holds the means."""
    est, _, limit = chaos.reading(r)
    if est != est:
        return f"no estimate: {r['status']}"
    return (f"a first-order line through {int(float(r['meshes']))} meshes ({int(float(r['realisations_min']))}+ "
            f"realisations each; pilot hole 1/8)" + ("" if limit else f": {r['status']}"))


def erosion_free_depth_rows(refs, chaos_rows, calibrated):
    """Table 3's depths on the erosion-free FE target (a study): with Table 1's HJC as stated, each depth at zero
    element size (rows of figures/fe/erosion_free/chaos_v*.csv, kind depth: the realisations' means on the study's
    meshes, at pilot hole 1/8) judged on estimate +- U against the paper's tolerance (nothing calibrated: an agreement
    is a reproduction; without a limit, undecided); and with one strength scale calibrated on DO1 at one mesh (rows of
    figures/fe/erosion_free/calibrated.csv; agreement there is after calibration)."""
    rows = []
    for r in chaos_rows:
        if r["kind"] != "depth":
            continue
        v, nose = int(float(r["velocity_ms"])), r["quantity"]
        ref = refs[f"table3.sim.{v}.{nose}"]
        est, u, limit = chaos.reading(r)
        case = (f"{ref.case} (erosion-free FE at zero element size: {est:.3f} +- {u:.3f} m by {_chaos_basis(r)}; "
                f"Table 1 HJC as stated; a study)")
        status = (interval_status(ref.value, est - u, est + u, ref.tol * abs(ref.value), False) if limit
                  else "undecided")
        rows.append(Row(ref.item, ref.quantity + " on the erosion-free target", case, ref.value, est,
                        _rel(ref.value, est), ref.tol, status))
    for r in calibrated:
        v, nose = int(r["velocity_ms"]), r["nose"]
        ref = refs[f"table3.sim.{v}.{nose}"]
        case = (f"{ref.case} (erosion-free FE; HJC strength scale {float(r['strength_scale']):.3f} calibrated on DO1 at "
                f"{float(r['elements_across_radius']):g} elements across and pilot hole {float(r['pilot_hole']):g}; "
                f"one mesh; a study)")
        rows.append(compare(ref, float(r["depth_calibrated_m"]), case, ref.quantity + " on the erosion-free target "
                            "calibrated on DO1", calibrated=True))
    return rows


def above_one(value, u, limit) -> str:
    """A contrast's ranking (its ratio above 1) from a value +- u (studies.grid.ranking: holds, fails, or undecided
    where the interval holds 1 or is not finite); undecided where the value is not a limit."""
    return grid.ranking(value, u) if limit else "undecided"


# the diff's status of a contrast's ranking on the erosion-free target (above_one)
RANKING_STATUS = {"holds": "ordering", "fails": "deviates"}


def erosion_free_rows(refs, free):
    """The paper's ranking of each nose contrast (the ratio above 1) on the erosion-free FE target, per velocity the
    study runs: the verdict table's erosion-free rows (``free``: records of figures/verdict.csv for that model; value
    +- uncertainty at zero element size, the chaos, the mesh and a resolved numerical control's change in it),
    ordering where the whole interval lies above 1, deviates where it lies below, undecided otherwise and where the
    study found no limit. The contrast itself against the paper's is the verdict's own row in the diff."""
    rows = []
    for r in free:
        name, v = r["contrast"], int(float(r["velocity_ms"]))
        prefix, nose = FE_INCREMENTS[name]
        ref = refs[f"{prefix}.{v}.{nose}"]
        value, u, limit = float(r["value"]), float(r["uncertainty"]), str(r["limit"]) == "True"
        basis = str(r["uncertainty_basis"]).replace(",", ";")
        rows.append(Row(ref.item, f"{name} above 1 (the paper's ranking) on the erosion-free target",
                        f"{v} m/s ({f'ratio {value:.3f} +- {u:.3f}: ' if value == value else ''}{basis}; the verdict "
                        "table; a study)", 1.0, value,
                        _rel(1.0, value), u, RANKING_STATUS.get(above_one(value, u, limit), "undecided")))
    return rows
