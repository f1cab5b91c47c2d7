"""Tasks of the reference stage: the diff against the paper and the reproduction check.

The reproduction check compares every committed output CSV listed under
``outputs`` in workflow/check.yaml with the one the pipeline just made. Each column
is compared with the tolerance of its precision class: a value passes when
|now - committed| <= factor * (atol + rtol |committed| + scale max|committed column|),
where (rtol, atol, scale) is what the producer of the column guarantees
(its ``precision``) and ``factor`` the margin. A class with ``decades``
compares orders of magnitude instead (error estimates of accuracy studies):
|log10((|now| + F atol)/(|committed| + F atol))| <= F decades, F the factor.
Text columns must match.

A file's spec may also give, for outputs of the chaotic finite-element level:
``rows``, classes for the cells of the rows whose committed values match
(``{where: {column: value}, columns: {column: class}}``); ``verdicts``, boolean
columns that state whether a compared value met a goal, checked against the
values now in the file rather than against the committed booleans (a value
within its tolerance of the goal's edge may cross it); and ``ensembles``,
means of realisations compared by their standard errors:
|now - committed| <= sigmas x sqrt(std_now^2 / n_now + std_committed^2 / n_committed)
plus the class tolerance.
"""
from __future__ import annotations

import dataclasses
import io as stdio
import subprocess

import numpy as np
import pandas as pd

from ..paper import claims as claim_rows, diff as diff_rows, reference
from ..paper.verdict import FREE, verdict_diff_rows
from ..pipeline.io import committed_studies, committed_study, load_json, task, write_csv, write_text


def _bands_dict(path, noses_table):
    table = pd.read_csv(path)
    out = {r.convention: {"lo": r.lo, "hi": r.hi, "peak_x": r.peak_x_over_b, "peak_k": r.peak_k}
           for r in table.itertuples()}
    out["adopted"] = table.loc[table.adopted, "convention"].iloc[0]
    out["nstar_crh3"] = float(noses_table.set_index("name").loc["fig4_crh3", "nstar"])
    return out


def _model_rows(refs, inputs):
    """Diff rows of the DOP and simulation stages: Table 3, DO1, Figs 1, 8, 9, 15."""
    fit = load_json(inputs.fit_calc)
    cal = load_json(inputs.cal_do1)
    do1 = pd.read_csv(inputs.do1_scene).iloc[0]
    sec = pd.read_csv(inputs.sec22)
    sec = sec[sec.radius_case == "chosen"]
    sec22 = {(r.nose, r.velocity): {"peak": r.peak_deceleration_m_s2, "dop": r.trajectory_dop, "duration": r.duration}
             for r in sec.itertuples()}
    d_do1 = 2 * cal["data"]["radius"]
    calibrated_pd = (cal["data"]["measured_depth"] + cal["residual_m"]) / d_do1
    table3 = pd.read_csv(inputs.table3).to_dict("records")
    return (diff_rows.table3_model_rows(refs, table3, fit["cells"])
            + diff_rows.experiment_rows(refs, do1.trajectory_dop, cal["S"])
            + diff_rows.ordering_rows(refs, sec22)
            + diff_rows.fig01_rows(refs, pd.read_csv(inputs.shares).to_dict("records"))
            + diff_rows.fig15_rows(refs, pd.read_csv(inputs.fig15).to_dict("records"), do1.trajectory_dop / d_do1,
                                   calibrated_pd)
            + diff_rows.cavity_rows(refs, table3, pd.read_csv(inputs.cavity_table3).to_dict("records"),
                                    float(pd.read_csv(inputs.cavity_do1).cavity_dop.iloc[0]),
                                    load_json(inputs.cal_cavity)["strength_scale"])
            + diff_rows.contrast_rows(refs, pd.read_csv(inputs.contrasts).to_dict("records")))


class _Tracking(dict):
    """Dict that remembers which keys were read (to list pending references)."""

    def __init__(self, *a):
        super().__init__(*a)
        self.used = set()

    def __getitem__(self, key):
        self.used.add(key)
        return super().__getitem__(key)


@task
def diff(inputs, outputs, params):
    """figures/diff.csv and its human-readable summary."""
    refs = _Tracking(reference.load_reference(inputs.reference))
    table = pd.read_csv(inputs.noses)
    by = table.set_index("name")
    ours = {f"nstar.{n}": float(by.loc[n, "nstar"]) for n in by.index}
    ours.update({f"mass.{n}": float(by.loc[n, "mass"]) for n in by.index})
    verdict = pd.read_csv(inputs.verdict)
    chaos = committed_studies(params.erosion_free)   # the erosion-free grid study, velocity by velocity
    free = [] if chaos is None else chaos.to_dict("records")
    rows = (diff_rows.table1_rows(refs) + diff_rows.table3_rows(refs) + diff_rows.table4_rows(refs, ours)
            + diff_rows.fig03_rows(refs, _bands_dict(inputs.bands, table)) + diff_rows.fig05_rows(refs, ours)
            + _model_rows(refs, inputs)
            + diff_rows.erosion_free_rows(refs, verdict[verdict.model == FREE].to_dict("records"))
            + diff_rows.erosion_free_depth_rows(refs, free,
                                                committed_study(params.erosion_free_calibrated).to_dict("records"))
            + verdict_diff_rows(verdict)
            + diff_rows.scale_do1_rows(refs, {level: committed_study(spec).to_dict("records")
                                              for level, spec in params.scale_do1.items() if spec["sha256"] != "missing"}))
    frame = pd.DataFrame([dataclasses.asdict(r) for r in rows], columns=diff_rows.COLUMNS)
    write_csv(frame, outputs.diff)
    findings = pd.read_csv(inputs.findings).to_dict("records")
    pending = sorted(set(refs) - refs.used)
    contrasts = pd.read_csv(inputs.contrast_table).to_dict("records")
    write_text(outputs.summary, diff_rows.summary(rows, findings, pending, contrasts))


def _one_row(path):
    """The one row of a committed calibration record (its fitted value, the data, the residual)."""
    table = pd.read_csv(path)
    if len(table) != 1:
        raise ValueError(f"{path}: a DO1 calibration record has one row, found {len(table)}")
    return table.iloc[0]


@task
def claims(inputs, outputs, params):
    """figures/fe/{profile}/claims.csv: every claim of the paper judged at every level (paper.claims), the one
    place a claim's verdict is computed; the report lays it out."""
    fe_calibration, cavity_calibration = (_one_row(path) for path in (inputs.fe_calibration, inputs.cavity_calibration))
    evidence = claim_rows.Evidence(
        paper=pd.read_csv(inputs.reference).set_index("id"), contrasts=pd.read_csv(inputs.contrasts),
        diff=pd.read_csv(inputs.diff), fe_diff=pd.read_csv(inputs.fe_diff), band=committed_study(params.band),
        extrapolation=committed_study(params.extrapolation), validation=committed_study(params.validation),
        cavity_scale=float(cavity_calibration.value), fe_calibration=fe_calibration,
        erosion_free=pd.read_csv(inputs.verdict))
    write_csv(pd.DataFrame(claim_rows.claim_rows(evidence), columns=claim_rows.COLUMNS), outputs.csv)


# --------------------------------------------------------- reproduction check
def column_tolerances(spec, precision, factor, columns):
    """Column -> (rtol, atol, scale, decades), times the factor, for one output from its spec in ``check.outputs``.

    ``spec`` is a precision class name, or {"default": class, "columns": {column: class}}.
    """
    if isinstance(spec, str):
        spec = {"default": spec}
    stray = sorted(set(spec.get("columns", {})) - set(columns))
    if stray:
        raise KeyError(f"check.outputs names columns {stray} that the file lacks; its columns: {list(columns)}")
    named = {c: spec.get("columns", {}).get(c, spec["default"]) for c in columns}
    unknown = sorted({n for n in list(named.values()) + [spec["default"]] if n not in precision})
    if unknown:
        raise KeyError(f"check.outputs names precision classes {unknown}; defined: {sorted(precision)}")
    keys = ("rtol", "atol", "scale", "decades")
    return {c: tuple(factor * precision[n].get(k, 0.0) for k in keys) for c, n in named.items()}


def cell_tolerances(spec, precision, factor, committed: pd.DataFrame):
    """column_tolerances, with the classes of ``spec["rows"]`` in the rows whose committed values match: column ->
    (rtol, atol, scale, decades), each an array over the rows."""
    cols = column_tolerances(spec, precision, factor, committed.columns)
    n = len(committed)
    out = {c: tuple(np.full(n, v) for v in t) for c, t in cols.items()}
    for rule in (spec.get("rows", []) if isinstance(spec, dict) else []):
        where = rule["where"]
        stray = sorted((set(where) | set(rule["columns"])) - set(committed.columns))
        if stray:
            raise KeyError(f"check.outputs rows name columns {stray} that the file lacks; its columns: {list(committed.columns)}")
        hit = np.ones(n, bool)
        for col, value in where.items():
            hit &= (committed[col].astype(float).to_numpy() == float(value)) if pd.api.types.is_numeric_dtype(committed[col]) \
                else (committed[col].astype(str).to_numpy() == str(value))
        for col, t in column_tolerances({"default": next(iter(rule["columns"].values())), "columns": rule["columns"]},
                                        precision, factor, list(rule["columns"])).items():
            for arr, v in zip(out[col], t):
                arr[hit] = v
    return out


def frames_differ(new: pd.DataFrame, old: pd.DataFrame, tolerances, verdicts=None, ensembles=None, sigmas=4.0):
    """Reason why two CSV tables differ beyond the per-column tolerances (the first such cell of every column that
    has one), or None. ``tolerances``: column -> (rtol, atol, scale, decades), scalars or arrays over the rows;
    ``verdicts``: boolean column -> {"of": [columns], "abs_at_most": number or column} (true where every |value| is
    at most the bound) or {"of": column, "between": [low column, high column]}, checked on the new frame;
    ``ensembles``: mean column -> {"std": column, "n": column}, the mean's allowed gap widened by ``sigmas`` standard
    errors of the difference of the two means."""
    if list(new.columns) != list(old.columns):
        return f"columns changed: {list(old.columns)} -> {list(new.columns)}"
    if len(new) != len(old):
        return f"row count changed: {len(old)} -> {len(new)}"
    verdicts, ensembles = verdicts or {}, ensembles or {}
    stray = sorted((set(verdicts) | set(ensembles)) - set(new.columns))
    if stray:
        raise KeyError(f"check.outputs verdicts or ensembles name columns {stray} that the file lacks")
    reasons = []
    for col in new.columns:
        a, b = new[col], old[col]
        if col in verdicts:
            want = _verdict(new, verdicts[col])
            got = a.astype(str).str.lower().to_numpy() == "true"
            if (got != want).any():
                i = int(np.argmax(got != want))
                reasons.append(f"column {col} row {i + 2}: says {a.iloc[i]!r}, but its values now give {bool(want[i])}")
        elif pd.api.types.is_numeric_dtype(a) and pd.api.types.is_numeric_dtype(b):
            rtol, atol, scale, decades = tolerances[col]
            x, y = a.to_numpy(float), b.to_numpy(float)
            with np.errstate(invalid="ignore", divide="ignore"):
                gap, allowed, what = _gap(x, y, rtol, atol, scale, decades)
                if col in ensembles:
                    e = ensembles[col]
                    se = np.sqrt(new[e["std"]].to_numpy(float) ** 2 / new[e["n"]].to_numpy(float)
                                 + old[e["std"]].to_numpy(float) ** 2 / old[e["n"]].to_numpy(float))
                    allowed = allowed + sigmas * np.nan_to_num(se)
            # a committed inf or nan must come back as it was
            same = np.where(np.isfinite(y), (gap <= allowed) | (x == y), (x == y) | (np.isnan(x) & np.isnan(y)))
            if not same.all():
                i = int(np.argmax(~same))
                reasons.append(f"column {col} row {i + 2}: committed {y[i]!r}, now {x[i]!r} "
                               f"({what[i]} {gap[i]:.3g} > allowed {allowed[i]:.3g})")
        elif not a.astype(str).equals(b.astype(str)):
            i = int(np.argmax((a.astype(str) != b.astype(str)).to_numpy()))
            reasons.append(f"column {col} row {i + 2}: committed {b.iloc[i]!r}, now {a.iloc[i]!r}")
    return "; ".join(reasons) or None


def compare(new: pd.DataFrame, old: pd.DataFrame, spec, check):
    """frames_differ under one file's spec in ``check.outputs`` (its classes, rows, verdicts and ensembles) and the
    check section's precision classes, factor and sigmas."""
    if list(new.columns) != list(old.columns) or len(new) != len(old):
        tol = {}  # frames_differ reports the changed shape before it looks at a tolerance
    else:
        tol = cell_tolerances(spec, check["precision"], check["factor"], old)
    extra = spec if isinstance(spec, dict) else {}
    return frames_differ(new, old, tol, extra.get("verdicts"), extra.get("ensembles"), check.get("sigmas", 4.0))


def _verdict(frame, rule):
    """The booleans a verdict rule gives on ``frame`` (see frames_differ)."""
    if "between" in rule:
        lo, hi = (frame[c].to_numpy(float) for c in rule["between"])
        v = frame[rule["of"]].to_numpy(float)
        return (lo <= v) & (v <= hi)
    bound = rule["abs_at_most"]
    bound = frame[bound].to_numpy(float) if isinstance(bound, str) else float(bound)
    return np.all([np.abs(frame[c].to_numpy(float)) <= bound for c in rule["of"]], axis=0)


def _gap(x, y, rtol, atol, scale, decades):
    """(gap, allowed gap, what each gap measures) between new values x and committed y; the tolerances are scalars or
    arrays over the rows (a row with decades compares orders of magnitude)."""
    rtol, atol, scale, decades = (np.broadcast_to(np.asarray(t, float), y.shape) for t in (rtol, atol, scale, decades))
    finite = np.isfinite(y)
    big = float(np.max(np.abs(y[finite]))) if finite.any() else 0.0
    log = decades > 0
    gap = np.where(log, np.abs(np.log10((np.abs(x) + atol) / (np.abs(y) + atol))), np.abs(x - y))
    allowed = np.where(log, decades, atol + rtol * np.abs(y) + scale * big)
    return gap, allowed, np.where(log, "decades apart", "|difference|")


def _committed(path):
    """Text of ``path`` at git HEAD, or None when not tracked or no git."""
    try:
        out = subprocess.run(["git", "show", f"HEAD:{path}"], capture_output=True, text=True, check=False)
    except OSError:
        return None
    return out.stdout if out.returncode == 0 else None


def reproduction_problems(outputs, diff_path, check):
    """(problems, number of files compared): drifted output CSVs and diff rows that lost their agreement.

    ``outputs``: the paths to compare (keys of ``check["outputs"]``); ``check``:
    the config's check section (factor, precision classes, outputs); ``diff_path``: None for the studies (no diff).
    """
    problems, compared = [], 0
    for path in outputs:
        text = _committed(path)
        if text is None:
            continue
        compared += 1
        new, old = pd.read_csv(path), pd.read_csv(stdio.StringIO(text))
        why = compare(new, old, check["outputs"][path], check)
        if why:
            problems.append(f"{path}: no longer matches the committed file: {why}")
    old = _committed(diff_path) if diff_path is not None else None
    if old is not None:
        key = ["item", "quantity", "case"]
        was = pd.read_csv(stdio.StringIO(old))
        now = pd.read_csv(diff_path).set_index(key)["status"]
        for r in was[was.status.isin(diff_rows.AGREES)].itertuples():
            status = now.get((r.item, r.quantity, r.case), "missing")
            if status != r.status:
                problems.append(f"{diff_path}: {r.item} / {r.quantity} / {r.case} was {r.status}, now {status}")
    return problems, compared


@task
def reproduce_check(inputs, outputs, params):
    """Fail when a committed output CSV or a reproduced diff row has drifted beyond its tolerance."""
    problems, compared = reproduction_problems(list(params.check["outputs"]), inputs.diff, params.check)
    report = [f"compared {compared} committed CSV files (tolerance factor {params.check['factor']:g} on the "
              f"precision class of each column, workflow/check.yaml, outputs)"]
    if compared == 0:
        report.append("warning: no committed copies found (not a git checkout?); only the current diff was checked")
    now = pd.read_csv(inputs.diff)
    report.append("diff status counts: " + ", ".join(f"{s} {int((now.status == s).sum())}" for s in diff_rows.STATUSES))
    report += problems
    print("\n".join(report))
    if problems:
        raise SystemExit(f"reproduction check failed: {len(problems)} problem(s)")
    write_text(outputs.report, "\n".join(report) + "\n")


@task
def reproduce_check_studies(inputs, outputs, params):
    """Fail when a committed output CSV of the studies has drifted beyond its tolerance."""
    problems, compared = reproduction_problems(list(params.check["outputs"]), None, params.check)
    report = [f"compared {compared} committed CSV files of the studies (tolerance factor {params.check['factor']:g} on "
              f"the precision class of each column, workflow/check.yaml, studies)"] + problems
    print("\n".join(report))
    if problems:
        raise SystemExit(f"reproduction check of the studies failed: {len(problems)} problem(s)")
    write_text(outputs.report, "\n".join(report) + "\n")
