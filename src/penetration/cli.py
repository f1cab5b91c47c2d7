"""Command line: ``python -m penetration nstar|dop|simulate|predict ...``.

``nstar`` prints N*, nose length and nose volume (SI). ``dop`` and
``simulate`` run one shot at any level of the fidelity ladder: a nose of
``nstar``'s kinds (its keys without radius) and the shot keys, which are the
columns of ``predict``'s shots CSV (shots.SHOT_FIELDS, units in the names);
``predict`` runs a CSV of shots. Errors name the key and the allowed range
on stderr and exit with status 2.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import textwrap
import time
from pathlib import Path

from .errors import ParameterError
from .levels import LEVELS
from .nose.geometry import NOSES
from .nose.nstar import nstar
from .nose.solve import solve_nose
from .pipeline.config import ConfigError
from .units import NUMBER_FORM, parse_number

KEYS_HELP = {
    "ogive": "psi=CRH radius=a [tip_radius=r]",
    "cone": "radius=a length=b [tip_radius=r]",
    "flat": "radius=a",
    "double_ogive": "radius=a S1= S2= a1= a2= [alpha=rad] [tip_length=m]",
    "minimum_nstar": "radius=a length=b",
    "table": "path=FILE.csv (columns x,y in metres)",
}
CONSTRAINT_HELP = ("a nose by constraint (every kind but flat and table): leave one key out and give nose_length=m "
                   "(tip to shank) or nstar=N* (Eq 5); that key is solved for (solve=KEY names it where a key with a "
                   "default, e.g. tip_length, is the free one); the smallest root is taken and any other is printed")
# nose keys of dop and simulate: nstar's without radius (the shank radius is diameter_m/2); shots.ladder.nose_keys
SHOT_NOSE_HELP = {
    "ogive": "psi=CRH or crh=CRH (the shots CSV's name) [tip_radius=m]",
    "cone": "length=m (the nose's) [tip_radius=m]",
    "flat": "(no keys)",
    "double_ogive": "S1= S2= a1= a2= (m) [alpha=rad] [tip_length=m]",
    "minimum_nstar": "length=m (the nose's)",
    "table": "path=FILE.csv (columns x,y in metres; the last y is the shank radius, diameter_m may be left out)",
}
LEVEL_CHOICES = list(LEVELS)
LEVELS_EPILOG = (
    "levels: analytic (Eq 9 and its closed-form time and peak deceleration; ns-us per shot), trajectory (rigid-body "
    "ODE, crater + static + inertial; ms), cavity (HJC sigma_n(v) table of the shot's concrete driving the "
    "trajectory; seconds per new concrete, tables cached per concrete and caliber), fe (2-D axisymmetric finite "
    "elements; minutes). S(fc) of the analytic and trajectory levels: --strength-law. The cavity and fe levels take "
    "the concrete of --root's config (Table 1's HJC set with the conventions of its concrete section), scale it to fc "
    "(concrete.HJC_SCALING_RULE) and carry over the calibrations committed under --root: the cavity level's strength "
    "scale fitted on the laboratory shots (figures/calibration_cavity_laboratory.csv; --calibration do1 takes DO1's), "
    "the fe level's failure strain fitted on the laboratory shots at the profile's mesh where that record exists "
    "(figures/fe/PROFILE/calibration_fe_laboratory.csv), else on DO1 (figures/fe/PROFILE/calibration_fe_do1.csv), "
    "--calibration do1 taking DO1's for both, unless --strength-scale "
    "or --failure-strain is given. The fe level prints its estimated cost first and refuses a shot estimated above "
    "--max-minutes. Every answer comes with its level's validated accuracy on the development shots and a warning "
    "for each quantity outside their range. Progress goes to stderr, terminal or not; an interrupted (SIGINT, "
    "SIGTERM) fe or cavity run says where it stopped and, with --out, writes OUT.partial.json.")
# the pipeline directory of the package's own checkout (an editable install), else the current directory
DEFAULT_ROOT = next((str(d) for d in (Path(__file__).resolve().parents[2],) if (d / "workflow/config.yaml").is_file()), ".")
DEFAULT_MAX_MINUTES = 20.0


def _option_number(text):
    """An option's number, in the form of every number of the command line (units.NUMBER_FORM)."""
    try:
        return parse_number(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not allowed: {NUMBER_FORM}") from None


def _level_options(p, model_help):
    p.add_argument("--model", choices=LEVEL_CHOICES, default="analytic", help=model_help)
    p.add_argument("--strength-law", choices=["li_chen", "forrestal"], default="li_chen",
                   help="published S(fc) relation of the analytic and trajectory levels (default li_chen: S = 72 fc^-0.5, "
                        "fc in MPa)")
    p.add_argument("--root", default=DEFAULT_ROOT, help="pipeline directory holding workflow/config.yaml and the "
                   "committed DO1 calibrations under figures/ (default: this package's checkout, "
                   f"{DEFAULT_ROOT})")
    p.add_argument("--max-minutes", type=_option_number, default=DEFAULT_MAX_MINUTES,
                   help=f"fe level: refuse a shot whose estimated cost exceeds this (default {DEFAULT_MAX_MINUTES:g})")
    p.add_argument("--profile", choices=["full", "ci"], default="full",
                   help="FE mesh profile whose calibration the fe level carries over (default full: 8 elements "
                        "across the shank radius)")
    p.add_argument("--calibration", default="laboratory", metavar="laboratory|do1|FILE",
                   help="calibration of the cavity level's strength scale and the fe level's failure strain: "
                        "laboratory (default: fitted on the 25 laboratory shots of workflow/data/experiments-dev.csv, "
                        "figures/calibration_cavity_laboratory.csv and figures/fe/PROFILE/calibration_fe_laboratory.csv; "
                        "a profile without the latter takes DO1's failure strain and says so), do1 (fitted on the "
                        "paper's DO1 shot, figures/calibration_cavity_do1.csv, figures/fe/PROFILE/calibration_fe_do1.csv) "
                        "or a cavity calibration record FILE")
    p.add_argument("--strength-scale", type=_option_number, default=None,
                   help="cavity level: factor on the HJC strength surface instead of the calibration (> 0)")
    p.add_argument("--failure-strain", type=_option_number, default=None,
                   help="fe level: erosion strain instead of the calibration (> 0)")
    p.add_argument("--size", default="auto", metavar="auto|none|VARIANT",
                   help="the scale effect (docs/scale-effect.md): a variant of the config's scale_effect.variants, with "
                        "the level's factor fitted with it on the laboratory shots (figures/scale/calibration_LEVEL.csv), "
                        "none, or auto (the default: the variant that meets every goal of the committed validation at "
                        "the level, figures/scale/validation_LEVEL.csv, else none); the answer's accuracy line says "
                        "which and how it validated")


def _wrap(text, indent=0):
    """``text`` filled to 100 columns; lines after the first indented by ``indent``."""
    return textwrap.fill(text, 100, subsequent_indent=" " * indent, break_on_hyphens=False)


def _shot_keys_help():
    """The shot keys of dop and simulate, from the one table of shot fields (shots.SHOT_FIELDS)."""
    from .shots.fields import SHOT_FIELDS
    lines = []
    for name, f in SHOT_FIELDS.items():
        need = (f"default {f.default:g}" if f.default is not None else "required" if f.required and name != "diameter_m"
                else "required except with a table nose" if name == "diameter_m" else "optional")
        lines.append(_wrap(f"  {name + '=':<22}{f.what}, {f.allowed} ({need})", 24))
    return "\n".join(lines)


def _shot_parser(sub, name, help_text):
    p = sub.add_parser(name, help=help_text, formatter_class=argparse.RawDescriptionHelpFormatter,
                       epilog=_wrap("shot keys (the columns of predict's shots CSV, units in the names; numbers as "
                                    f"{NUMBER_FORM}):") + "\n" + _shot_keys_help()
                       + "\nnose kinds and their keys (as nstar's, without radius: the nose's radius is diameter_m/2):\n"
                       + "\n".join(_wrap(f"  {k}: {v}", 4) for k, v in SHOT_NOSE_HELP.items())
                       + "\n" + _wrap(CONSTRAINT_HELP)
                       + "\n\n" + _wrap(LEVELS_EPILOG))
    p.add_argument("kind", help=f"nose kind, one of {sorted(NOSES)}")
    p.add_argument("params", nargs="*", metavar="key=value", help="shot keys and nose keys (see below)")
    _level_options(p, "level of the fidelity ladder (default analytic)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    return p


def _parser():
    p = argparse.ArgumentParser(prog="python -m penetration",
                                description="Penetration of double-ogive-nose projectiles (Liu, Pi & Huang 2015).")
    sub = p.add_subparsers(dest="command", required=True)
    n = sub.add_parser("nstar", help="nose shape factor N* (Eq 5), length and volume of a nose",
                       epilog=_wrap("kinds: " + "; ".join(f"{k}: {v}" for k, v in KEYS_HELP.items()) + ". "
                                    + CONSTRAINT_HELP))
    n.add_argument("kind", help=f"one of {sorted(NOSES)}")
    n.add_argument("params", nargs="*", metavar="key=value", help="nose parameters in SI units")
    n.add_argument("--json", action="store_true", help="print one JSON object")
    o = sub.add_parser("outline", help="a nose's outline as CSV (columns x, y in metres: a table nose) and a PNG",
                       epilog=_wrap("kinds: " + "; ".join(f"{k}: {v}" for k, v in KEYS_HELP.items()) + ". "
                                    + CONSTRAINT_HELP))
    o.add_argument("kind", help=f"one of {sorted(NOSES)}")
    o.add_argument("params", nargs="*", metavar="key=value", help="nose parameters in SI units")
    o.add_argument("--out", required=True, help="CSV to write (x, y in metres, tip to shank; readable as "
                   "'table path=FILE'); the PNG is written beside it with the suffix .png unless --png is given")
    o.add_argument("--png", default=None, help="PNG to write (default: --out with the suffix .png)")
    o.add_argument("--points", type=int, default=200, help="points per segment of the outline (default 200; 2-10000)")
    _shot_parser(sub, "dop", "depth of penetration, time to rest, peak deceleration and cost of one shot")
    s = _shot_parser(sub, "simulate", "one shot as dop, and its history (time, depth, velocity, deceleration) as CSV")
    s.add_argument("--out", required=True, help="history CSV to write (levels trajectory, cavity, fe): time, depth, "
                   "velocity, deceleration")
    s.add_argument("--fields", default=None, metavar="DIR", help="fe level: write the target's state (damage, plastic "
                   "strain, pressure on the deformed mesh) at --field-times-ms and at the end into DIR, each as a VTK "
                   "file (fields_*.vtu: ParaView, meshio) and a PNG")
    s.add_argument("--field-times-ms", default="", metavar="T1,T2,...", help="fe level: times (ms) of the field "
                   "files besides the end (at most 20)")
    from .shots.fields import columns_help
    pr = sub.add_parser("predict", help="depth of penetration of a CSV of shots at any level",
                        formatter_class=argparse.RawDescriptionHelpFormatter,
                        epilog=_wrap("shots CSV: a header row naming the columns (each once), one shot a row; numbers "
                                     f"as {NUMBER_FORM}; other columns are passed through; a row that fails a check is "
                                     "skipped with the reason. Columns (units in the names; the shot keys of dop and "
                                     "simulate):") + "\n"
                               + "\n".join(_wrap(line, 23) for line in columns_help().splitlines())
                               + "\n\n" + _wrap(LEVELS_EPILOG))
    pr.add_argument("shots", help="CSV in the schema of workflow/data/experiments-dev.csv (columns below)")
    _level_options(pr, "level of the fidelity ladder (default analytic: Eq 9, adds dop_pred_m; the other levels add "
                       "model, dop_pred_m, time_to_rest_pred_s, peak_deceleration_pred_m_s2, wall_time_s)")
    pr.add_argument("--out", required=True, help="output CSV: the input rows that could be predicted, plus the predictions")
    _compare_parser(sub)
    return p


def _compare_parser(sub):
    from .shots.compare import MAX_MEMBERS, SHOT_KEYS
    c = sub.add_parser("compare", help="several noses at one projectile and target: depths and each nose's contrast "
                       "against a reference nose with its uncertainty, per level, as a CSV and a figure",
                       formatter_class=argparse.RawDescriptionHelpFormatter, epilog=_wrap(
                           "example: compare --nose 'crh3=ogive crh=3' --nose 'crh6=ogive crh=6' --nose 'do=double_ogive "
                           "S1=0.05 a1=0.005 a2=0.01 nose_length=0.05995' --nose 'cone=cone length=0.05995' --reference "
                           "crh3 --velocities 400:1000:100 --levels analytic,cavity,fe mass_kg=0.5 diameter_m=0.025 "
                           "length_m=0.2 fc_MPa=40 --out study/. A nose is 'LABEL=KIND key=value ...' with the keys of "
                           "dop's noses (no radius: diameter_m/2), by constraint too (nose_length=, nstar=). Shot keys: "
                           f"{', '.join(SHOT_KEYS)} (as dop's). --study FILE.yaml gives the same as keys noses (label: "
                           "{kind: ..., key: value}), reference, shot, velocities, levels, members, mesh_check, title; "
                           "options given on the command line win. Writes OUT/compare.csv (one row per level, nose and "
                           "velocity: depth, contrast, u_validated, u_calibration, u_chaos, u_mesh, u_combined and the "
                           "parts it holds), OUT/compare.png, OUT/noses.csv and OUT/noses.png. Only the calibrations a "
                           "chosen level needs are read (committed records: nothing is fitted); the command says which.")
                       + "\n\n" + _wrap(LEVELS_EPILOG))
    c.add_argument("params", nargs="*", metavar="key=value", help="shot keys")
    c.add_argument("--study", default=None, help="a study YAML (see below)")
    c.add_argument("--nose", action="append", default=None, metavar="'LABEL=KIND key=value ...'",
                   help="a nose (give 2-12)")
    c.add_argument("--reference", default=None, help="label of the nose the contrasts are taken against (default: "
                   "the first)")
    c.add_argument("--velocities", default=None, help="m/s: a list 400,600,800 or a range 400:1000:100 (stop included "
                   "where the steps reach it)")
    c.add_argument("--levels", default=None, help="comma-separated levels (default analytic)")
    c.add_argument("--members", type=int, default=None, help=f"fe level: realisations at the top velocity for the "
                   f"chaos band (default 2; 2-{MAX_MEMBERS})")
    c.add_argument("--mesh-check", action="store_true", default=None, help="fe level: add the other mesh profile's "
                   "contrast at the top velocity (the full mesh costs about 10-70 times the ci mesh)")
    c.add_argument("--workers", type=int, default=None, help="fe shots run this many at a time (default: the cores)")
    c.add_argument("--out", required=True, help="folder to write the comparison into")
    c.add_argument("--strength-law", choices=["li_chen", "forrestal"], default="li_chen",
                   help="published S(fc) relation of the analytic and trajectory levels (default li_chen)")
    c.add_argument("--root", default=DEFAULT_ROOT, help=f"pipeline directory (default {DEFAULT_ROOT})")
    c.add_argument("--profile", choices=["full", "ci"], default="ci", help="fe mesh profile (default ci: 3 elements "
                   "across the shank radius; full, 8 across, costs about 10-70 times more)")
    c.add_argument("--calibration", default="laboratory", choices=["laboratory", "do1"],
                   help="calibration of the cavity and fe levels (default laboratory); the other one gives the "
                        "contrast's calibration part")
    c.add_argument("--max-minutes", type=_option_number, default=DEFAULT_MAX_MINUTES,
                   help=f"fe level: refuse a shot estimated above this (default {DEFAULT_MAX_MINUTES:g})")


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
    from .pipeline.io import TargetError, check_target, read_rows, write_rows
    from .shots.ladder import output_fields, predict_rows
    src, out = Path(args.shots), Path(args.out)
    try:
        check_target(out)
    except TargetError as err:
        return _fail(f"--out {args.out}: {err}")
    if out.exists() and src.exists() and out.resolve() == src.resolve():
        return _fail(f"--out {args.out} is the shots file itself; allowed: a different path (the input is never overwritten)")
    try:
        fields, rows = read_rows(src)
    except (OSError, ValueError) as err:
        return _fail(f"cannot read shots file {args.shots}: {getattr(err, 'strerror', None) or err}")
    ctx = None
    try:
        ctx = _context(args) if args.model != "analytic" else _sized(args, None)
    except (ParameterError, ConfigError, OSError) as err:
        return _fail(str(err))
    good = []
    _interruptible()
    try:
        good, problems = predict_rows(rows, args.strength_law, args.model, ctx, _progress(f"{args.model}: shot"), good,
                                      base=src.parent)
    except (Interrupted, KeyboardInterrupt) as err:
        where = _partial(out, {"status": "interrupted", "signal": str(err) or "SIGINT", "level": args.model,
                               "rows": len(rows), "predicted": good})
        print(f"interrupted after {len(good)} of {len(rows)} shots" + (f"; partial record {where}" if where else ""),
              file=sys.stderr, flush=True)
        return 130
    for p in problems:
        print(f"skipped {p}", file=sys.stderr)
    _predict_trust(args, good)
    if not good:
        return _fail(f"no shot in {args.shots} could be predicted ({len(rows)} rows); nothing written")
    try:
        write_rows(out, output_fields(fields, args.model), good)
    except TargetError as err:
        return _fail(f"--out {args.out}: {err}")
    except OSError as err:
        name = str(err.filename or "")
        where = "" if name in ("", str(out)) else f" (directory {out.parent})" if name.endswith(".tmp") else f" ({name})"
        return _fail(f"cannot write --out {args.out}: {err.strerror or err}{where}")
    print(f"predicted {len(good)} shots, skipped {len(problems)}; wrote {args.out}", file=sys.stderr)
    return 0


def _progress(what, every_s=5.0):
    """Progress of a run of several shots on stderr: a bar redrawn on a terminal; otherwise a line at most every
    ``every_s`` seconds and at the end (flushed: a log or a pipe sees it as it comes)."""
    t0 = time.perf_counter()
    last = [-every_s]
    tty = sys.stderr.isatty()

    def show(i, n):
        now = time.perf_counter() - t0
        if tty:
            bar = "#" * int(30 * i / max(n, 1))
            print(f"\r{what} {i}/{n} [{bar:<30}] {now:6.1f} s", end="" if i < n else "\n", file=sys.stderr, flush=True)
        elif i == n or now - last[0] >= every_s:
            last[0] = now
            print(f"{what} {i}/{n} done, {now:.1f} s", file=sys.stderr, flush=True)
    return show


class Interrupted(Exception):
    """SIGTERM or SIGINT during a run."""


def _interruptible():
    """SIGTERM ends a run as SIGINT does (an exception at the next line of Python, between two chunks of an FE
    run), so that it can say where it stopped."""
    import signal

    def stop(signum, _frame):
        raise Interrupted(signal.Signals(signum).name)
    for sig in (signal.SIGTERM, signal.SIGINT):
        signal.signal(sig, stop)


def _log():
    """The levels' progress lines (the FE run's every ~2 s; its cost estimate) to stderr, flushed; the last kept."""
    last = {"line": ""}

    def log(line):
        last["line"] = line
        print(line, file=sys.stderr, flush=True)
    log.last = last
    return log


def _partial(out, record):
    """Write the partial record of an interrupted run beside --out (OUT.partial.json); returns its path or None."""
    if out is None:
        return None
    from .pipeline.io import write_json
    path = Path(f"{out}.partial.json")
    try:
        write_json(record, path)
    except OSError:
        return None
    return path


UNKNOWN_ACCURACY = "validated accuracy unknown (no committed validation under --root)"


def _validation(args):
    """(the development shots' range, level -> errors) from the committed validation under --root, or None (a
    record that cannot be read is said on stderr, naming it: the answer stands without its accuracy)."""
    from .pipeline.records import RecordError
    from .shots.records import validated_accuracy
    try:
        return validated_accuracy(args.root, args.profile, getattr(args, "calibration", "laboratory"))
    except RecordError as err:
        print(f"warning: {err}; the validated accuracy is not known", file=sys.stderr)
        return None


def _trust(args, shot, level):
    """The validated accuracy line of ``level`` and the warnings for ``shot`` (from the committed validation), with
    the scale effect the shot ran with; a default outside the validated range is said there once, not warned."""
    from .shots.trust import defaults_note, warnings
    found = _validation(args)
    if found is None:
        return UNKNOWN_ACCURACY, []
    rng, errors = found
    line, rng = _accuracy_with_size(args, level, errors, rng)
    note = defaults_note(shot, rng)
    return f"{line}; validated range: {rng.describe()}" + (f"; {note}" if note else ""), warnings(shot, rng)


def _accuracy_with_size(args, level, errors, rng):
    """(the accuracy line of ``level`` as the run used it, the validated range): with a variant of the scale effect,
    that variant's validation (its range widened to DO1's calibre where it predicts DO1 within the goal); without,
    the level's validation and why the effect is off."""
    from .shots.records import scale_effect_accuracy
    from .shots.trust import accuracy_line, scale_effect_line, with_scale_effect_range
    variant, why = getattr(args, "size_variant", ("none", "not chosen"))
    from .pipeline.records import RecordError
    try:
        row = scale_effect_accuracy(args.root, level, variant)
    except RecordError as err:
        print(f"warning: {err}; the scale effect's validation is not known", file=sys.stderr)
        row = None
    if variant != "none":
        return f"validated accuracy of the {level} level with the {scale_effect_line(variant, why, row)}", \
            with_scale_effect_range(rng, row)
    line = accuracy_line(level, errors[level]) if level in errors else f"no validation of the {level} level"
    return f"{line}; {scale_effect_line(variant, why, row)}", rng


def _predict_trust(args, good):
    """The level's validated accuracy, and a warning for each predicted row outside the validated range (stderr)."""
    from .shots.ladder import user_shot
    from .shots.trust import warnings
    found = _validation(args)
    if found is None:
        print(UNKNOWN_ACCURACY, file=sys.stderr)
        return
    rng, errors = found
    line, rng = _accuracy_with_size(args, args.model, errors, rng)
    print(line, file=sys.stderr)
    for row in good:
        try:
            shot = user_shot(row, Path(args.shots).parent)
        except ValueError:   # Eq 9 predicts a row the other levels refuse (length_m shorter than the nose): no range
            continue
        for w in warnings(shot, rng):
            print(f"warning: {row.get('shot_id') or 'a row'}: {w}", file=sys.stderr)


# the largest value of a calibration the command line takes in place of the committed one, and why
OVERRIDE_RANGES = {
    "strength_scale": (10.0, "a factor on Table 1's whole strength surface; the committed calibrations lie between "
                             "0.5 and 1"),
    "failure_strain": (20.0, "an erosion strain; the committed calibrations lie between 1 and 3.2"),
}


def _context(args):
    """The levels' context from --root, with the command line's calibration overrides (checked)."""
    from .pipeline.config import available_memory
    from .shots.records import context_from_pipeline
    root = Path(args.root)
    if not (root / "workflow/config.yaml").is_file():
        raise ParameterError("argument", "--root", args.root, "a pipeline directory with workflow/config.yaml")
    ctx = _sized(args, context_from_pipeline(root, args.profile, args.strength_law, args.calibration))
    if not args.max_minutes > 0:
        raise ParameterError("argument", "--max-minutes", args.max_minutes, "--max-minutes > 0")
    ctx.fe_max_seconds = 60.0 * args.max_minutes
    ctx.fe_available_memory = available_memory()
    for name, attr in (("--strength-scale", "strength_scale"), ("--failure-strain", "failure_strain")):
        value = getattr(args, attr)
        if value is not None:
            top, why = OVERRIDE_RANGES[attr]
            if not (0 < value <= top):
                raise ParameterError("argument", name, value, f"0 < {name} <= {top:g} ({why})")
            setattr(ctx, attr, value)
            setattr(ctx, f"{attr}_source", f"given on the command line ({name})")
    return ctx


def _sized(args, ctx):
    """``ctx`` (None: the analytic level's own, of --strength-law) with the scale effect of --size at the level of
    --model (shots.records.chosen_size; the variant and why it was chosen kept in args for the accuracy line); None
    for the analytic level without it (Eq 9 as before)."""
    from .shots.ladder import Context
    from .shots.records import AUTO_SIZE, NO_SIZE, chosen_size, scale_effect_context
    root = Path(args.root)
    if not (root / "workflow/config.yaml").is_file():
        if args.size not in (AUTO_SIZE, NO_SIZE):
            raise ParameterError("argument", "--size", args.size, f"{AUTO_SIZE} or {NO_SIZE} without a pipeline under "
                                 f"--root {args.root} (a variant's calibration lives in its figures/scale/)")
        args.size_variant = (NO_SIZE, "no pipeline under --root")
        return ctx
    variant, why = chosen_size(root, args.model, args.size, args.profile, args.strength_law)
    args.size_variant = (variant, why)
    if variant == NO_SIZE:
        return ctx
    given = [name for name, on in (("--strength-scale", args.strength_scale is not None),
                                   ("--failure-strain", args.failure_strain is not None),
                                   (f"--calibration {args.calibration}", args.calibration != "laboratory")) if on]
    if given:
        raise ParameterError("argument", "--size", variant, f"{NO_SIZE} with {', '.join(given)} (a variant of the scale "
                             "effect brings the factor its level was fitted with on the laboratory shots)")
    return scale_effect_context(ctx or Context(strength_law=args.strength_law), root, args.model, variant,
                                args.profile, args.strength_law)


def _shot(args):
    """The UserShot of dop/simulate's keys: the shot fields of the shots CSV (converted to SI by
    shots.ladder.shot_from_keywords) and the nose's keys."""
    from .shots.ladder import shot_from_keywords
    return shot_from_keywords(args.kind, _keywords(args.params))


def _one_shot(args) -> int:
    from .pipeline.io import TargetError, check_target
    from .shots.ladder import run
    if args.command == "simulate" and args.model == "analytic":
        return _fail("--model analytic has no history; allowed for simulate: trajectory, cavity, fe")
    try:
        shot = _shot(args)
        ctx = _context(args) if args.model != "analytic" else _sized(args, None)
        if ctx is None:
            from .shots.ladder import Context
            ctx = Context(strength_law=args.strength_law)
        out = Path(args.out) if args.command == "simulate" else None
        if out is not None:
            try:
                check_target(out)
            except TargetError as err:
                return _fail(f"--out {args.out}: {err}")
        fields_dir = _fields_request(args, ctx)
        log = _log()
        _interruptible()
        t0 = time.perf_counter()
        try:
            res = run(shot, args.model, ctx, log=log if args.model == "fe" else None)
        except (Interrupted, KeyboardInterrupt) as err:
            rec = {"status": "interrupted", "signal": str(err) or "SIGINT", "level": args.model,
                   "wall_time_s": time.perf_counter() - t0, "last_progress": log.last["line"]}
            where = _partial(out, rec)
            print(f"interrupted after {rec['wall_time_s']:.1f} s; last progress: {log.last['line'] or 'none'}"
                  + (f"; partial record {where}" if where else ""), file=sys.stderr, flush=True)
            return 130
    except (ParameterError, ConfigError, OSError, RuntimeError) as err:
        return _fail(str(err))
    rec = res.record()
    rec["validated_accuracy"], rec["warnings"] = _trust(args, shot, args.model)
    if out is not None:
        import pandas as pd

        from .pipeline.io import write_csv
        cols = {"t": "t_s", "depth": "depth_m", "velocity": "velocity_m_s", "deceleration": "deceleration_m_s2"}
        try:
            write_csv(pd.DataFrame({cols[k]: v for k, v in res.history.items()}), out)
        except TargetError as err:
            return _fail(f"--out {args.out}: {err}")
        except OSError as err:
            return _fail(f"cannot write --out {args.out}: {err.strerror or err}")
        rec["history"] = str(out)
    if fields_dir is not None:
        try:
            res.asked_times = ctx.fe_snapshot_times
            rec["fields"] = _write_fields(res, shot, fields_dir)
        except (TargetError, OSError) as err:
            return _fail(f"--fields {fields_dir}: {getattr(err, 'strerror', None) or err}")
    if args.json:
        print(json.dumps(rec))
    else:
        print(f"level              {rec['level']}\ndepth              {rec['depth_m']:.6g} m\n"
              f"time to rest       {rec['time_to_rest_s']:.6g} s\npeak deceleration  {rec['peak_deceleration_m_s2']:.6g} m/s^2\n"
              f"status             {rec['status']}\nwall time          {rec['wall_time_s']:.3g} s\nnotes              {rec['notes']}"
              + (f"\nhistory            {rec['history']}" if "history" in rec else "")
              + (f"\nfields             {', '.join(rec['fields'])}" if "fields" in rec else "")
              + f"\naccuracy           {rec['validated_accuracy']}")
    for w in rec["warnings"]:
        print(f"warning: {w}: the level's accuracy there is not known", file=sys.stderr)
    return 0


MAX_FIELD_TIMES = 20


def _fields_request(args, ctx):
    """The --fields folder (None without it), checked before any run; sets ctx.fe_snapshot_times."""
    folder = getattr(args, "fields", None)
    times = getattr(args, "field_times_ms", "")
    if folder is None:
        if times:
            raise ParameterError("argument", "--field-times-ms", times, "only with --fields DIR")
        return None
    if args.model != "fe":
        raise ParameterError("argument", "--fields", folder, "only with --model fe (the other levels have no mesh)")
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise ParameterError("argument", "--fields", str(folder), "a folder (new or existing), not a file")
    try:
        values = tuple(sorted({parse_number(x.strip()) for x in times.split(",") if x.strip()}))
    except ValueError:
        raise ParameterError("argument", "--field-times-ms", times, f"numbers (ms) separated by commas: {NUMBER_FORM}") from None
    if len(values) > MAX_FIELD_TIMES or any(not (0 < v <= 1e4) for v in values):
        raise ParameterError("argument", "--field-times-ms", times, f"at most {MAX_FIELD_TIMES} times in (0, 1e4] ms")
    from .pipeline.io import TargetError, check_target
    probe = folder / "fields_end.vtu"
    try:
        check_target(probe)
    except TargetError as err:
        raise ParameterError("argument", "--fields", str(folder), str(err)) from None
    ctx.fe_snapshot_times = tuple(1e-3 * v for v in values) + (math.inf,)   # inf: the end only
    return folder


def _write_fields(res, shot, folder) -> list:
    """Each snapshot of an fe run as fields_t{ms}.vtu and .png (the last, at rest: fields_end); the paths."""
    from .figures.fe_fields import draw_snapshot
    from .pipeline.io import write_vtu
    snaps, conn = res.fields
    asked = [t for t in getattr(res, "asked_times", ()) if math.isfinite(t)]
    late = [t for t in asked if t > snaps[-1]["t"]]
    if late:
        print(f"note: field times {', '.join(f'{1e3 * t:g}' for t in late)} ms fall after the run's end at "
              f"{1e3 * snaps[-1]['t']:.3f} ms: the end is written instead", file=sys.stderr)
    written = []
    for k, snap in enumerate(snaps):
        stem = "fields_end" if k == len(snaps) - 1 else f"fields_t{1e3 * snap['t']:.3f}ms"
        path = Path(folder) / f"{stem}.vtu"
        write_vtu(path, snap["r"], snap["z"], conn, {"damage": snap["damage"], "plastic_strain": snap["eps_p"],
                                                      "pressure_Pa": snap["pressure"], "state": snap["state"]})
        draw_snapshot(snap, conn, shot.nose.radius, path.with_suffix(".png"), f"{shot.nose.kind} nose, "
                      f"{shot.velocity:g} m/s, fc {shot.fc / 1e6:g} MPa")
        written += [str(path), str(path.with_suffix(".png"))]
    return written


def _fail(message) -> int:
    print(f"error: {message}", file=sys.stderr)
    return 2


def _parse(argv):
    """The arguments, with key=value pairs taken wherever they stand: argparse alone takes positionals only
    before the first option, so `dop ogive psi=3 --model fe length=0.3` would reject length=0.3."""
    p = _parser()
    args, extra = p.parse_known_args(argv)
    keys = [a for a in extra if "=" in a and not a.startswith("-")]
    if extra and (len(keys) < len(extra) or not hasattr(args, "params")):
        p.error("unrecognized arguments: " + " ".join(extra))
    if keys:
        args.params = [*args.params, *keys]
    return args


def main(argv=None) -> int:
    args = _parse(argv)
    if args.command == "predict":
        return _predict(args)
    if args.command in ("dop", "simulate"):
        return _one_shot(args)
    if args.command == "outline":
        return _outline(args)
    if args.command == "compare":
        return _compare(args)
    try:
        nose, solution = solve_nose(args.kind, _keywords(args.params))
        result = {"nstar": nstar(nose), "length": nose.length, "volume": nose.volume()}
    except (ParameterError, OSError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    if solution is not None:
        result["solved"] = {"key": solution.key, "value": solution.value, "other_values": list(solution.other_values)}
    if args.json:
        print(json.dumps(result))
    else:
        print(f"N*      {result['nstar']:.10g}\nlength  {result['length']:.10g} m\nvolume  {result['volume']:.10g} m^3"
              + (f"\nsolved  {solution.describe()}" if solution is not None else ""))
    return 0


def _velocities(text):
    """Velocities (m/s) from 'a,b,c' or 'start:stop:step' (stop included where the steps reach it)."""
    from .shots.compare import MAX_VELOCITIES
    allowed = (f"a list a,b,c or a range start:stop:step of at most {MAX_VELOCITIES} velocities (m/s; numbers as "
               f"{NUMBER_FORM})")
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise ValueError
            a, b, step = (parse_number(x.strip()) for x in parts)
            if not (step > 0 and b >= a) or (b - a) / step > MAX_VELOCITIES:
                raise ParameterError("argument", "--velocities", text, f"start <= stop, step > 0, at most "
                                     f"{MAX_VELOCITIES} velocities")
            n = int(math.floor((b - a) / step * (1 + 1e-12)))
            return tuple(a + k * step for k in range(n + 1))
        return tuple(parse_number(x.strip()) for x in text.split(","))
    except ValueError:
        raise ParameterError("argument", "--velocities", text, allowed) from None


def _study(args):
    """The Study of compare's options and --study file (options win)."""
    from .pipeline.config import load_with
    from .shots.compare import parse_nose, study_from_doc
    doc = load_with(Path(args.study), {}) if args.study else {}
    noses = None
    if args.nose:
        noses = {}
        for text in args.nose:
            label, kind, keys = parse_nose(text)
            if label in noses:
                raise ParameterError("argument", "--nose", label, "each label once")
            noses[label] = (kind, keys)
    return study_from_doc(doc, f"study {args.study}", noses=noses, shot=_keywords(args.params),
                          velocities=_velocities(args.velocities) if args.velocities else None,
                          levels=tuple(args.levels.split(",")) if args.levels else None, members=args.members,
                          mesh_check=args.mesh_check, reference=args.reference)


def _compare(args) -> int:
    """Run a nose comparison and write its table, its figure and its noses (shots.compare)."""
    from .pipeline.io import TargetError, check_target, write_csv
    from .shots import compare as C
    out = Path(args.out)
    files = C.output_files(out)
    say = lambda line: print(line, file=sys.stderr, flush=True)  # noqa: E731
    try:
        if out.exists() and not out.is_dir():
            return _fail(f"--out {args.out} is a file; allowed: a folder (new or existing)")
        for path in files.values():
            check_target(path)
        if not args.max_minutes > 0:
            raise ParameterError("argument", "--max-minutes", args.max_minutes, "--max-minutes > 0")
        if args.workers is not None and not 1 <= args.workers <= 64:
            raise ParameterError("argument", "--workers", args.workers, "1 to 64 (fe shots run this many at a time)")
        study = _study(args)
        workers = C.with_workers(args.workers)
        noses, ctxs, validated = C.prepare(study, args.root, args.profile, args.strength_law, args.calibration,
                                           60.0 * args.max_minutes, say, workers)
    except TargetError as err:
        return _fail(f"--out {args.out}: {err}")
    except (ParameterError, ConfigError, OSError) as err:
        return _fail(str(err))
    jobs = C.plan(study)
    say(C.describe_plan(jobs, workers))
    done = []
    _interruptible()
    t0 = time.perf_counter()
    try:
        C.run_jobs(study, noses, ctxs, jobs, workers, _progress("compare: run"), done)
    except (Interrupted, KeyboardInterrupt) as err:
        table = C.tabulate(study, noses, done, validated, args.calibration, args.strength_law, ctxs)
        where = Path(f"{files['compare.csv']}.partial.csv")
        try:
            write_csv(table, where)
        except OSError:
            where = None
        say(f"interrupted ({err or 'SIGINT'}) after {len(done)} of {len(jobs)} runs"
            + (f"; partial table {where}" if where else ""))
        return 130
    failed = C.base_failures(done)
    for j, _, _, e in done:
        if e:
            say(f"warning: {j.level} {j.variant} {j.nose} {j.velocity:g} m/s failed: {e}"
                + ("" if j.variant == "base" else " (that part of the uncertainty is left out)"))
    table = C.tabulate(study, noses, done, validated, args.calibration, args.strength_law, ctxs)
    try:
        from .figures.compare import write_comparison
        write_comparison(files, table, **C.drawing(study, noses, _wrap))
    except TargetError as err:
        return _fail(f"--out {args.out}: {err}")
    except OSError as err:
        return _fail(f"cannot write into --out {args.out}: {err.strerror or err}")
    say(f"compared {len(noses)} noses at {len(study.velocities)} velocities and {len(study.levels)} levels in "
        f"{time.perf_counter() - t0:.1f} s; wrote {', '.join(str(p) for p in files.values())}")
    return 0 if not failed else 1


def _outline(args) -> int:
    """Write a nose's outline as a table-nose CSV (x, y in metres) and a PNG of it and its cumulative N*."""
    import pandas as pd

    from .figures.nose_outline import draw_noses
    from .pipeline.io import TargetError, check_target, write_csv
    out = Path(args.out)
    png = Path(args.png) if args.png else out.with_suffix(".png")
    if not 2 <= args.points <= 10000:
        return _fail(f"--points = {args.points} is not allowed: 2 <= --points <= 10000")
    if out.suffix.lower() == ".png" or png.resolve() == out.resolve():
        return _fail(f"--out {args.out}: allowed: a CSV path other than the PNG's ({png})")
    try:
        for path, name in ((out, "--out"), (png, "--png")):
            try:
                check_target(path)
            except TargetError as err:
                return _fail(f"{name} {path}: {err}")
        nose, solution = solve_nose(args.kind, _keywords(args.params))
        x, y = nose.outline(args.points)
        keep = [0] + [i for i in range(1, len(x)) if (x[i], y[i]) != (x[i - 1], y[i - 1])]
        label = f"{args.kind} " + " ".join(args.params)
        write_csv(pd.DataFrame({"x": x[keep], "y": y[keep]}), out)
        from .nose.nstar import cumulative_nstar
        draw_noses({args.kind: cumulative_nstar(nose, 120)}, png, _wrap(label, 0))
    except (ParameterError, TargetError) as err:
        return _fail(str(err))
    except OSError as err:
        return _fail(f"cannot write {err.filename or args.out}: {err.strerror or err}")
    print(f"N*      {nstar(nose):.10g}\nlength  {nose.length:.10g} m\nradius  {nose.radius:.10g} m"
          + (f"\nsolved  {solution.describe()}" if solution is not None else "") + f"\nwrote   {out}, {png}")
    return 0
