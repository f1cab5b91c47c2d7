"""Command line: ``python -m penetration nstar KIND key=value ... [--json]``.

Prints N*, nose length and nose volume (SI). Errors name the key and the
allowed range on stderr and exit with status 2.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .geometry import NOSES, ParameterError, make_nose
from .nstar import nstar

KEYS_HELP = {
    "ogive": "psi=CRH radius=a [tip_radius=r]",
    "cone": "radius=a length=b [tip_radius=r]",
    "flat": "radius=a",
    "double_ogive": "radius=a S1= S2= a1= a2= [alpha=rad] [tip_length=m]",
    "minimum_nstar": "radius=a length=b",
    "table": "path=FILE.csv (columns x,y in metres)",
}


def _parser():
    p = argparse.ArgumentParser(prog="python -m penetration",
                                description="Penetration of double-ogive-nose projectiles (Liu, Pi & Huang 2015).")
    sub = p.add_subparsers(dest="command", required=True)
    n = sub.add_parser("nstar", help="nose shape factor N* (Eq 5), length and volume of a nose",
                       epilog="kinds: " + "; ".join(f"{k}: {v}" for k, v in KEYS_HELP.items()))
    n.add_argument("kind", help=f"one of {sorted(NOSES)}")
    n.add_argument("params", nargs="*", metavar="key=value", help="nose parameters in SI units")
    n.add_argument("--json", action="store_true", help="print one JSON object")
    pr = sub.add_parser("predict", help="closed-form DOP (Eq 9) for a CSV of shots")
    pr.add_argument("shots", help="CSV in the schema of experiments-dev.csv (other columns are passed through)")
    pr.add_argument("--model", choices=["analytic"], default="analytic", help="model level (analytic: Eq 9)")
    pr.add_argument("--strength-law", choices=["li_chen", "forrestal"], default="li_chen",
                    help="published S(fc) relation (default li_chen: S = 72 fc^-0.5)")
    pr.add_argument("--out", required=True, help="output CSV: the input rows that could be predicted, plus dop_pred_m")
    return p


def _keywords(pairs):
    out = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            raise ParameterError("argument", pair, pair, "key=value")
        if key in out:
            raise ParameterError("argument", key, value, f"each key once ({key}={out[key]} is given already)")
        out[key] = value
    return out


def _predict(args) -> int:
    """Predict the shots of a CSV file; nothing is written unless at least one row could be predicted."""
    from .io import read_rows, write_rows
    from .shots import output_fields, predict_rows
    src, out = Path(args.shots), Path(args.out)
    if out.is_dir():
        return _fail(f"--out {args.out} is a directory; allowed: the path of a CSV file to write")
    if out.exists() and src.exists() and out.resolve() == src.resolve():
        return _fail(f"--out {args.out} is the shots file itself; allowed: a different path (the input is never overwritten)")
    try:
        fields, rows = read_rows(src)
    except (OSError, ValueError) as err:
        return _fail(f"cannot read shots file {args.shots}: {getattr(err, 'strerror', None) or err}")
    good, problems = predict_rows(rows, args.strength_law)
    for p in problems:
        print(f"skipped {p}", file=sys.stderr)
    if not good:
        return _fail(f"no shot in {args.shots} could be predicted ({len(rows)} rows); nothing written")
    try:
        write_rows(out, output_fields(fields), good)
    except OSError as err:
        name = str(err.filename or "")
        where = "" if name in ("", str(out)) else f" (directory {out.parent})" if name.endswith(".tmp") else f" ({name})"
        return _fail(f"cannot write --out {args.out}: {err.strerror or err}{where}")
    print(f"predicted {len(good)} shots, skipped {len(problems)}; wrote {args.out}", file=sys.stderr)
    return 0


def _fail(message) -> int:
    print(f"error: {message}", file=sys.stderr)
    return 2


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    if args.command == "predict":
        return _predict(args)
    try:
        nose = make_nose(args.kind, **_keywords(args.params))
        result = {"nstar": nstar(nose), "length": nose.length, "volume": nose.volume()}
    except (ParameterError, OSError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(result))
    else:
        print(f"N*      {result['nstar']:.10g}\nlength  {result['length']:.10g} m\nvolume  {result['volume']:.10g} m^3")
    return 0
