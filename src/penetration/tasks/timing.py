"""Where a rebuild's time goes: every job's recorded wall time (Snakemake's benchmark records), per rule and per stage.

A job's record is the last run of that job (``results/benchmarks/``); a record is attributed to a rule only if
its name matches that rule's benchmark pattern, so records left by renamed or removed rules are left out (records
of a current rule for wildcard values no longer built, such as a removed velocity, are not: they match). The
records of the rules that run after this one (the report, this rule itself) are those of their previous run.
The sums are of job wall times: with two jobs at a time, a rebuild takes less than their sum.

The per-rule file accumulates: a (stage, rule) with no record in this build (a study's, after a rebuild of the
paper alone) keeps its row from the file as it was, so that the records of both targets stay there for the
estimates of time left (``penetration.build``).
"""
from __future__ import annotations

import re
from pathlib import Path

import pandas as pd

from ..pipeline.io import task, write_csv


def _fields(pattern: str):
    """Split a path pattern into (literal, name, constraint) triples: a {name} or {name,regex} wildcard after each
    literal (name None after the last); braces inside a constraint (a{2}) are counted."""
    out, lit, i = [], [], 0
    while i < len(pattern):
        if pattern[i] != "{":
            lit.append(pattern[i])
            i += 1
            continue
        depth, j = 1, i + 1
        while depth and j < len(pattern):
            depth += {"{": 1, "}": -1}.get(pattern[j], 0)
            j += 1
        if depth:
            raise ValueError(f"path pattern {pattern!r}: unbalanced braces")
        name, _, constraint = pattern[i + 1:j - 1].partition(",")
        out.append(("".join(lit), name.strip(), constraint.strip() or None))
        lit, i = [], j
    out.append(("".join(lit), None, None))
    return out


def pattern_regex(pattern: str) -> re.Pattern:
    """Regex of a benchmark path pattern as Snakemake holds it: each wildcard a named group matching its constraint
    ({name,regex}: the rule's and the workflow's wildcard_constraints, which Snakemake writes into the pattern) or
    else at least one character; a repeated one the same text."""
    rx, seen = [], set()
    for literal, name, constraint in _fields(pattern):
        rx.append(re.escape(literal))
        if name is None:
            continue
        if name in seen:
            rx.append(f"(?P={name})")
            continue
        seen.add(name)
        rx.append(f"(?P<{name}>(?:{constraint or '.+?'}))")
    return re.compile("".join(rx) + r"\Z")


def attribute(paths, patterns: dict) -> list[dict]:
    """(rule, wildcards) of each record path; the pattern with the most literal characters wins (``fe_shot_...``
    is not ``fe_...``; a constraint's length does not count); a path no pattern matches is left out."""
    compiled = sorted(((sum(len(lit) for lit, _, _ in _fields(p)), rule, pattern_regex(p)) for rule, p in patterns.items()),
                      reverse=True)
    out = []
    for path in paths:
        for _, rule, rx in compiled:
            m = rx.match(str(path))
            if m:
                out.append({"path": str(path), "rule": rule, **{f"wc_{k}": v for k, v in m.groupdict().items()}})
                break
    return out


@task
def pipeline_timing(inputs, outputs, params):
    """Per rule and per stage (rules file, and mesh profile where the rule has one): jobs and their wall times."""
    patterns, files = dict(params.patterns), dict(params.rule_files)
    rows = []
    for rec in attribute(sorted(Path(params.folder).glob("*.tsv")), patterns):
        b = pd.read_csv(rec["path"], sep="\t")
        stage = files[rec["rule"]] + (f" [{rec['wc_profile']}]" if rec.get("wc_profile") else "")
        rows.append({"rule": rec["rule"], "stage": stage, "wall_s": float(b.s.iloc[0]), "max_rss_mb": float(b.max_rss.iloc[0])})
    if not rows:
        raise RuntimeError(f"no benchmark record under {params.folder} matches a rule's pattern")
    jobs = pd.DataFrame(rows)
    per_rule = (jobs.groupby(["stage", "rule"]).agg(jobs=("wall_s", "size"), wall_total_s=("wall_s", "sum"),
                                                    wall_min_s=("wall_s", "min"), wall_max_s=("wall_s", "max"),
                                                    max_rss_mb=("max_rss_mb", "max")).reset_index())
    per_rule = merge_records(per_rule, Path(outputs.rules), set(patterns))
    per_stage = (per_rule.groupby("stage").agg(jobs=("jobs", "sum"), wall_total_s=("wall_total_s", "sum"),
                                              max_rss_mb=("max_rss_mb", "max")).reset_index())
    per_stage["wall_total_min"] = per_stage.wall_total_s / 60
    write_csv(per_rule, outputs.rules)
    write_csv(per_stage, outputs.stages)
    for r in per_stage.itertuples():
        print(f"{r.stage:28s} {r.jobs:4d} jobs {r.wall_total_min:7.1f} min", flush=True)


def merge_records(new: pd.DataFrame, previous: Path, rules: set) -> pd.DataFrame:
    """``new`` per-rule rows, with the rows of ``previous`` (the file as it was) for the (stage, rule) pairs that have
    no new record, when their rule still exists; sorted by stage and rule."""
    if not previous.is_file():
        return new
    old = pd.read_csv(previous)
    keep = old[old.rule.isin(rules) & ~old.set_index(["stage", "rule"]).index.isin(new.set_index(["stage", "rule"]).index)]
    return pd.concat([keep, new], ignore_index=True).sort_values(["stage", "rule"]).reset_index(drop=True)[list(new.columns)]
