"""Load YAML config and scene files, validated against a JSON schema.

Errors name the file, the field (dotted path) and what is allowed, and are
raised before any computation starts.
"""
from __future__ import annotations

import json
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

import jsonschema
import yaml

from ..paper.reference import load_reference
from ..units import parse_number


class ConfigError(ValueError):
    """A config file that does not satisfy its schema."""


class _StrictLoader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):   # libyaml's parser where PyYAML has it
    """YAML loader that refuses a key given twice in one mapping (PyYAML keeps the last silently)."""

    def construct_mapping(self, node, deep=False):
        seen = set()
        for key_node, _ in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                continue  # '<<' merges another mapping; its keys may be overridden here
            key = self.construct_object(key_node, deep=deep)
            try:
                duplicate = key in seen
            except TypeError:
                continue  # unhashable: the base class reports it as a YAML error
            if duplicate:
                raise ConfigError(f"line {key_node.start_mark.line + 1}: key {key!r} is given twice; allowed: each key once")
            seen.add(key)
        return super().construct_mapping(node, deep)


def _describe(s) -> str:
    """A short description of what a schema admits (for the alternatives of oneOf)."""
    if "const" in s:
        return repr(s["const"])
    if "enum" in s:
        return f"one of {s['enum']}"
    kind = s.get("type")
    if kind == "object":
        return f"an object with keys {s.get('required', [])}" + (
            f" (optional {sorted(set(s.get('properties', {})) - set(s.get('required', [])))})"
            if set(s.get("properties", {})) - set(s.get("required", [])) else "")
    if kind == "array":
        items = _describe(s.get("items", {})) if s.get("items") else "items"
        return f"a list of {items}" + (f", at most {s['maxItems']}" if "maxItems" in s else "")
    if kind in ("number", "integer"):
        bounds = [f"{k} {s[k]}" for k in ("minimum", "exclusiveMinimum", "maximum", "exclusiveMaximum") if k in s]
        return f"a {'number' if kind == 'number' else 'whole number'}" + (f" ({', '.join(bounds)})" if bounds else "")
    return kind or "anything"


def _allowed(err) -> str:
    v, s = err.validator, err.schema
    if v == "additionalProperties":
        return f"known keys are {sorted(s.get('properties', {}))}"
    if v == "enum":
        return f"one of {s['enum']}"
    if v == "type":
        return f"type {s['type']}"
    if v in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        bounds = [f"{k} {s[k]}" for k in ("minimum", "exclusiveMinimum", "maximum", "exclusiveMaximum") if k in s]
        return ", ".join(bounds)
    if v == "required":
        return f"required keys {s['required']}"
    if v == "pattern":
        return f"a string matching {s['pattern']}"
    if v in ("oneOf", "anyOf"):
        return " or ".join(_describe(alt) for alt in s[v])
    if v in ("maxItems", "minItems"):
        return f"{'at most' if v == 'maxItems' else 'at least'} {s[v]} items"
    return err.message


def non_finite(data, path=()):
    """(dotted path, value) of every NaN or infinite number in ``data`` (mappings and lists walked)."""
    if isinstance(data, float) and not math.isfinite(data):
        return [(".".join(str(p) for p in path) or "(top level)", data)]
    if isinstance(data, dict):
        return [hit for k, v in data.items() for hit in non_finite(v, (*path, k))]
    if isinstance(data, (list, tuple)):
        return [hit for i, v in enumerate(data) for hit in non_finite(v, (*path, i))]
    return []


def validate(data, schema, source: str):
    """Raise ConfigError listing every violation of ``schema`` in ``data``, and every number that is not finite
    (a schema's bounds let NaN through: every comparison with it is false)."""
    bad = non_finite(data)
    if bad:
        raise ConfigError("\n".join(f"{source}: {field}: {value} is not allowed: a finite number (YAML's .nan and .inf "
                                     "are refused anywhere)" for field, value in bad))
    errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(data), key=lambda e: list(e.path))
    if errors:
        lines = []
        for err in errors:
            field = ".".join(str(p) for p in err.path) or "(top level)"
            lines.append(f"{source}: {field}: {err.message}; allowed: {_allowed(err)}")
        raise ConfigError("\n".join(lines))
    return data


def read_yaml(path):
    """The data of a YAML file read with the strict loader (a key given twice is refused with its line)."""
    path = Path(path)
    try:
        return yaml.load(path.read_text(), Loader=_StrictLoader)
    except ConfigError as err:
        raise ConfigError(f"{path}: {err}") from None
    except yaml.YAMLError as err:
        raise ConfigError(f"{path}: not valid YAML: {err}") from None
    except (OSError, UnicodeDecodeError) as err:
        raise ConfigError(f"{path}: cannot read: {err}") from None


def check_config_files(paths):
    """Re-read each config file (the Snakefile's configfile and every --configfile) with the strict loader:
    Snakemake's own loader keeps the last of a key given twice silently. Raises ConfigError naming the file and
    the line."""
    for path in paths:
        read_yaml(path)


def load(path, schema_path):
    """Read a YAML file and validate it against the schema file; returns the parsed dict."""
    return load_with(path, json.loads(Path(schema_path).read_text()))


def load_with(path, schema: dict):
    """Read a YAML file and validate it against ``schema``; returns the parsed dict."""
    data = read_yaml(path)
    return validate(data if data is not None else {}, schema, str(path))


def coerce(data, schema):
    """``data`` with strings turned into numbers or booleans where ``schema`` asks for them.

    Snakemake's ``--config key={a: 1}`` passes the nested values as strings;
    this lets such overrides mean what they say. Numbers are read in the one
    form of units.NUMBER_FORM (whole numbers: digits only); anything that does
    not convert is left as it is, for validation to report.
    """
    kind = schema.get("type")
    if isinstance(data, dict):
        props = schema.get("properties", {})
        extra = schema.get("additionalProperties")
        return {k: coerce(v, props.get(k, extra if isinstance(extra, dict) else {})) for k, v in data.items()}
    if isinstance(data, list):
        return [coerce(v, schema.get("items", {})) for v in data]
    if isinstance(data, str):
        if kind == "integer":
            return int(data) if re.fullmatch(r"[+-]?[0-9]+", data, re.ASCII) else data
        if kind == "number":
            try:
                return parse_number(data)  # the one form of a number ('nan', 'inf', '1_0', ' 5' stay strings)
            except ValueError:
                return data
        text = data.strip()
        if kind == "boolean" and text.lower() in ("true", "false"):
            return text.lower() == "true"
    return data


# config fields naming input files (dotted path): checked to exist when the config is loaded
FILE_FIELDS = ("reference", "findings", "check", "validation.shots")
# config fields naming rows of the reference file by id ("[]" walks a list)
REFERENCE_FIELDS = ("projectile.density", "projectile.diameter", "table4_do1.nstar_target", "table4_do1.mass_target",
                    "calibration.do1.mass", "calibration.do1.velocity", "calibration.do1.depth",
                    "diameter_450kg.axes.[].top")


def _values(cfg, dotted):
    """The values at a dotted path of the config ("[]" expands a list)."""
    values = [cfg]
    for key in dotted.split("."):
        values = [x for v in values for x in v] if key == "[]" else [v[key] for v in values]
    return values


# lists whose order or distinctness a task relies on ("*" stands for every key of a mapping)
ORDERED_LISTS = {
    "cavity.velocities": "increasing",          # the sigma_n(v) table's nodes
    "cavity.quasi_static_from": "increasing",   # two slow velocities v1 < v2
    "fe.cutoffs_hz": "increasing",
    "fe.profiles.*.mesh_study": "distinct",     # elements across the shank radius, listed coarse to fine
    "fig01.strengths": "increasing",
    "fig10.unload_from": "increasing",
    "diameter_450kg.axes.[].velocity": "distinct",
    "sweep.velocities": "distinct",             # run in the order given
    "sweep.sizes.*": "increasing",              # the first n shots of the grid, n growing
}
BRACKETS = ("fe.fs_bracket",)  # [low, high] with low < high

# Memory of the FE level: bytes per element of the model at its peak while it is built (the solver's element
# fields, forces, connectivity and node arrays and the construction's temporaries; tracemalloc over
# penetration.fe.solver.Model of 2e5-7e5 element meshes gives 590-670 bytes per element)
FE_BYTES_PER_ELEMENT = 600
# Cost of the cavity level: one expansion at 100 zones takes about 0.11 s on one core (the zones study of
# figures/timing/accuracy_cavity.csv: 0.026, 0.106, 0.42 and 1.47 s at 50, 100, 200 and 400 zones), growing as
# zones^2 (the time step shrinks with the finest zone, and each step visits every zone). A sigma_n table is one
# expansion per velocity plus the two quasi-static ones; CAVITY_TABLE_BUDGET_S bounds its time (the DO1
# calibration builds one table per trial, the cavity scenes one per material and caliber).
CAVITY_SECONDS_AT_100_ZONES = 0.11
CAVITY_TABLE_BUDGET_S = 600.0


def cpu_model() -> str:
    """The CPU model from /proc/cpuinfo where there is one, else what platform knows of the processor."""
    import platform

    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine_name() -> str:
    """The CPU model, the number of CPUs and the Python version, for timing records."""
    import platform

    return f"{cpu_model()}, {os.cpu_count()} CPUs, Python {platform.python_version()}"


def machine_memory() -> int:
    """Bytes of physical memory of this machine (os.sysconf)."""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


def available_memory() -> float:
    """Bytes of memory available now (os.sysconf; infinite where the system does not say)."""
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return math.inf


def _paths(cfg, dotted):
    """(dotted path, value) at a dotted path with "*" (every key of a mapping) and "[]" (every item of a list);
    a missing key gives nothing."""
    found = [("", cfg)]
    for key in dotted.split("."):
        nxt = []
        for where, v in found:
            if key == "*" and isinstance(v, dict):
                nxt += [(f"{where}.{k}".lstrip("."), x) for k, x in v.items()]
            elif key == "[]" and isinstance(v, list):
                nxt += [(f"{where}.{i}".lstrip("."), x) for i, x in enumerate(v)]
            elif isinstance(v, dict) and key in v:
                nxt.append((f"{where}.{key}".lstrip("."), v[key]))
        found = nxt
    return found


def _graded_cells(span, h, ratio):
    """Cells of sizes h ratio, h ratio^2, ... that cover ``span`` (the FE mesh's grading outside its core)."""
    if span <= 0:
        return 0
    if ratio == 1.0:
        return math.ceil(span / h)
    return math.ceil(math.log1p(span * (ratio - 1.0) / (h * ratio)) / math.log(ratio))


def fe_mesh_elements(h, fe, radius, depth) -> int:
    """Elements of the FE level's semi-infinite target meshed at element size ``h`` for a shot of shank radius
    ``radius`` expected to reach ``depth`` (fe.shot.model_for with fe.mesh.graded): a uniform core of
    core_calibers radii and depth + depth_margin/2, graded by ``grading`` out to fe.target_radius and
    depth + depth_margin (the level's settings of the ``fe`` slice, fe.spec.Settings.from_config)."""
    s = _fe_settings(fe, h)
    q = s.grading
    core_r, core_d = s.core_calibers * radius, depth + 0.5 * s.depth_margin
    nr = math.ceil(core_r / h - 1e-9)   # as fe.mesh.graded: a core of a whole number of cells counts them exactly
    nz = math.ceil(core_d / h - 1e-9)
    nr += _graded_cells(fe["target_radius"] - nr * h, h, q)
    nz += _graded_cells(depth + s.depth_margin - nz * h, h, q)
    return nr * nz


def _fe_settings(fe, h):
    from ..fe.spec import Settings  # light: no solver code
    return Settings.from_config(fe, None, h)


def _ordered_problems(cfg, source):
    bad = []
    for dotted, rule in ORDERED_LISTS.items():
        groups = {}
        if "[]." in dotted:  # values spread over the items of a list: one group
            head = dotted.split(".[].")[0]
            groups[head + "[]." + dotted.split(".[].")[1]] = [v for _, v in _paths(cfg, dotted)]
        else:
            groups = {where: v for where, v in _paths(cfg, dotted) if isinstance(v, list)}
        for where, values in groups.items():
            if rule == "increasing" and any(b <= a for a, b in zip(values, values[1:])):
                bad.append(f"{source}: {where}: {values} is not allowed: strictly increasing values (each once, "
                           "smallest first)")
            elif rule == "distinct" and len(set(values)) < len(values):
                twice = sorted({v for v in values if values.count(v) > 1})
                bad.append(f"{source}: {where}: {values} is not allowed: each value once ({twice} repeated)")
    for dotted in BRACKETS:
        for where, v in _paths(cfg, dotted):
            if isinstance(v, list) and len(v) == 2 and not v[0] < v[1]:
                bad.append(f"{source}: {where}: {v} is not allowed: [low, high] with low < high")
    return bad


def element_size(radius, across):
    """The element size (m) of a mesh with ``across`` elements across the shank radius: the radius over it at 12
    significant digits (the size that names a profile's calibration files and records)."""
    return float(f"{radius / across:.12g}")


def element_sizes(cfg, radius):
    """Add to ``cfg`` the element size of every FE mesh profile, which the config gives as elements across the shank
    radius: fe.profiles.*.element_size and .mesh_study_sizes, fe_convergence.sizes, fe_band.sizes,
    fe_erosion_free.sizes (profile name -> element size in m)."""
    for spec in cfg["fe"]["profiles"].values():
        spec["element_size"] = element_size(radius, spec["elements_across"])
        spec["mesh_study_sizes"] = [element_size(radius, n) for n in spec["mesh_study"]]
    if "fe_convergence" in cfg:
        cfg["fe_convergence"]["sizes"] = {p: element_size(radius, n) for p, n in cfg["fe_convergence"]["profiles"].items()}
    if "fe_band" in cfg:
        cfg["fe_band"]["sizes"] = {c: {p: element_size(radius, n) for p, n in band.items()}
                                   for c, band in cfg["fe_band"]["bands"].items()}
    if "fe_erosion_free" in cfg:
        cfg["fe_erosion_free"]["sizes"] = {p: element_size(radius, n)
                                           for p, n in cfg["fe_erosion_free"]["profiles"].items()}
    return cfg


def _size_problems(cfg, source, refs):
    """Sizes beyond what this machine can hold or run: FE meshes against its memory, cavity zones against the
    cost of a table, sweep sizes against the sweep's grid."""
    bad = []
    fe = cfg["fe"]
    radius = 0.5 * refs[cfg["projectile"]["diameter"]].si
    depth = refs[cfg["calibration"]["do1"]["depth"]].si
    ram = machine_memory()
    sizes = (_paths(cfg, "fe.profiles.*.elements_across") + _paths(cfg, "fe.profiles.*.mesh_study.[]")
             + _paths(cfg, "fe_convergence.profiles.*") + _paths(cfg, "fe_band.bands.*.*")
             + _paths(cfg, "fe_erosion_free.profiles.*"))
    for where, across in sizes:
        h = element_size(radius, across)
        n = fe_mesh_elements(h, fe, radius, depth)
        need = n * FE_BYTES_PER_ELEMENT
        if need > ram:
            s = _fe_settings(fe, h)
            lo, hi = h, 1.0  # the smallest element size whose mesh fits (the count falls as h grows)
            while hi - lo > 1e-3 * lo:
                mid = math.sqrt(lo * hi)
                lo, hi = (lo, mid) if fe_mesh_elements(mid, fe, radius, depth) * FE_BYTES_PER_ELEMENT <= ram else (mid, hi)
            bad.append(f"{source}: {where}: {across:g} elements across the shank radius ({h:.3g} m elements) is not allowed: the DO1 calibration shot's mesh (every element size "
                       f"is calibrated on DO1) would have about {n:.3g} elements (a core of {s.core_calibers:g} "
                       f"shank radii of {radius:g} m and {depth + 0.5 * s.depth_margin:g} m deep, graded by "
                       f"{s.grading:g} to the {fe['target_radius']:g} m target radius and "
                       f"{depth + s.depth_margin:g} m), about {need / 1e9:.3g} GB at {FE_BYTES_PER_ELEMENT} bytes "
                       f"per element, beyond this machine's {ram / 1e9:.3g} GB of memory (os.sysconf); allowed: at "
                       f"most {radius / hi:.3g} elements across (elements of at least {hi:.3g} m)")
    cav = cfg["cavity"]
    expansions = len(cav["velocities"]) + len(cav["quasi_static_from"])
    per_table = lambda z: CAVITY_SECONDS_AT_100_ZONES * (z / 100.0) ** 2 * expansions
    if per_table(cav["zones"]) > CAVITY_TABLE_BUDGET_S:
        most = int(100.0 * math.sqrt(CAVITY_TABLE_BUDGET_S / (CAVITY_SECONDS_AT_100_ZONES * expansions)))
        bad.append(f"{source}: cavity.zones: {cav['zones']} is not allowed: one sigma_n table ({expansions} expansions: "
                   f"the velocities and the two quasi-static ones) would take about {per_table(cav['zones']) / 60:.3g} "
                   f"min on one core ({CAVITY_SECONDS_AT_100_ZONES:g} s per expansion at 100 zones, "
                   "figures/timing/accuracy_cavity.csv, growing as zones^2); allowed: at most "
                   f"{most} zones, a table within {CAVITY_TABLE_BUDGET_S / 60:g} min")
    sweep = cfg.get("sweep")
    if sweep:
        grid = len(sweep["noses"]) * len(sweep["velocities"])
        for where, sizes in _paths(cfg, "sweep.sizes.*"):
            over = [n for n in sizes if n > grid]
            if over:
                bad.append(f"{source}: {where}: {over} is not allowed: at most the {grid} shots of the sweep's grid "
                           f"({len(sweep['noses'])} noses times {len(sweep['velocities'])} velocities)")
    return bad


def check_config(cfg: dict, schema_path, source: str) -> dict:
    """Coerce command-line overrides, validate ``cfg`` in place and check that the files it names exist."""
    schema = json.loads(Path(schema_path).read_text())
    cfg.update(coerce(dict(cfg), schema))
    validate(cfg, schema, source)
    missing = [f"{source}: {dotted}: file {value!r} does not exist; allowed: the path of an existing file"
               for dotted in FILE_FIELDS for value in _values(cfg, dotted) if not Path(value).is_file()]
    if missing:
        raise ConfigError("\n".join(missing))
    ids = load_reference(cfg["reference"])
    unknown = [f"{source}: {dotted}: {value!r} is not an id of {cfg['reference']}; allowed: one of its ids"
               for dotted in REFERENCE_FIELDS for value in _values(cfg, dotted) if value not in ids]
    if unknown:
        raise ConfigError("\n".join(unknown))
    element_sizes(cfg, 0.5 * ids[cfg["projectile"]["diameter"]].si)
    bad = _ordered_problems(cfg, source) + _size_problems(cfg, source, ids)
    if bad:
        raise ConfigError("\n".join(bad))
    return cfg


def load_check(path, schema_path) -> dict:
    """The reproduction check's file (config ``check``: precision classes, the outputs and studies they apply to),
    validated against its schema, every class an output names defined."""
    check = load(path, schema_path)
    classes = check["precision"]
    bad = []
    for section in ("outputs", "studies"):
        for out, spec in check.get(section, {}).items():
            spec = {"default": spec} if isinstance(spec, str) else spec
            named = [("default", spec.get("default"))] + list(spec.get("columns", {}).items()) + [
                (f"rows[{k}].{c}", n) for k, row in enumerate(spec.get("rows", [])) for c, n in row["columns"].items()]
            bad += [f"{path}: {section}.{out}.{column}: precision class {name!r} is not defined; allowed: one of "
                    f"{sorted(classes)}" for column, name in named if name is not None and name not in classes]
    if bad:
        raise ConfigError("\n".join(bad))
    return check


def checked_outputs(check, profiles, bands=(), section="outputs"):
    """The output specs by path of one section of the check (``outputs``: the paper's target; ``studies``: the
    studies'): a ``{profile}`` entry stands for each of ``profiles``, a ``{band}`` one for each of ``bands`` (the band
    profiles of fe_band)."""
    return {path.format(profile=p, band=b): spec for path, spec in check[section].items()
            for p in (profiles if "{profile}" in path else [None]) for b in (bands if "{band}" in path else [None])}


def scale_grid(cfg, level, variant) -> list:
    """The grid of ``level``'s factor in the scale effect's study with ``variant`` (``cfg``: the config mapping): the
    closed form's scale_effect.s_scales, the cavity level's laboratory strength scales, and the fe level's laboratory
    failure strains without the effect and scale_effect.fe_failure_strains with it (the rate law wants lower ones)."""
    lab, study = cfg["validation"]["laboratory"], cfg["scale_effect"]
    if level == "analytic":
        return study["s_scales"]
    if level == "cavity":
        return lab["strength_scales"]
    return lab["failure_strains"] if variant == "none" else study["fe_failure_strains"]


@dataclass(frozen=True)
class MeshProfiles:
    """The FE level's mesh profiles beyond ``full`` and ``ci`` (the studies' meshes), from a checked config:
    ``convergence`` (fe_convergence.profiles: Table 3 again at finer meshes), ``bands`` (fe_band.bands: centre -> its
    band's profiles, the mesh realisations of the FE nose contrasts), ``free`` (fe_erosion_free.profiles: the
    erosion-free grid study's, coarse first) and ``extra`` (profile -> element size in m, every one of them)."""
    convergence: list
    bands: dict
    free: list
    extra: dict

    @property
    def band_profiles(self):
        return [p for band in self.bands.values() for p in band]

    def fe_slice(self, fe, profile):
        """The ``fe`` config slice for a profile's jobs; a profile beyond full and ci joins its element size."""
        if profile not in self.extra:
            return fe
        h = self.extra[profile]
        return {**fe, "profiles": {**fe["profiles"], profile: {"element_size": h, "mesh_study_sizes": [h]}}}


def mesh_profiles(cfg) -> MeshProfiles:
    """The mesh profiles of a config checked by check_config (its element sizes computed), their names checked
    to be distinct across the studies and each band centred on full or a convergence profile (ConfigError)."""
    convergence = list(cfg["fe_convergence"]["profiles"])
    bands = {centre: list(band) for centre, band in cfg["fe_band"]["bands"].items()}
    members = [p for band in bands.values() for p in band]
    free = list(cfg["fe_erosion_free"]["profiles"])
    extra = {**cfg["fe_convergence"]["sizes"], **{p: h for band in cfg["fe_band"]["sizes"].values() for p, h in band.items()},
             **cfg["fe_erosion_free"]["sizes"]}
    if len(extra) != len(convergence) + len(members) + len(free):
        raise ConfigError(f"fe_erosion_free.profiles {free}: names must differ from fe_convergence's and fe_band's")
    for centre in bands:
        if centre not in ["full", *convergence]:
            raise ConfigError(f"fe_band.bands.{centre}: allowed centres full or a profile of fe_convergence.profiles "
                              f"{convergence}")
    if len(members) != len(set(members)) or set(members) & set(convergence):
        raise ConfigError(f"fe_band.bands: profile names {members} must be distinct and not those of fe_convergence")
    return MeshProfiles(convergence, bands, free, extra)
