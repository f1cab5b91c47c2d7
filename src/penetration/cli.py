"""Command line: ``python -m penetration nstar KIND key=value ... [--json]``.

Prints N*, nose length and nose volume (SI). Errors name the key and the
allowed range on stderr and exit with status 2.
"""
from __future__ import annotations

import argparse
import json
import sys

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
    return p


def _keywords(pairs):
    out = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            raise ParameterError("argument", pair, pair, "key=value")
        out[key] = value
    return out


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
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
