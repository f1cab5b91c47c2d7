"""Load YAML config and scene files, validated against a JSON schema.

Errors name the file, the field (dotted path) and what is allowed, and are
raised before any computation starts.
"""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import jsonschema
import yaml

from .reference import load_reference
from .units import parse_number


class ConfigError(ValueError):
    """A config file that does not satisfy its schema."""


class _StrictLoader(yaml.SafeLoader):
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


def validate(data, schema, source: str):
    """Raise ConfigError listing every violation of ``schema`` in ``data``."""
    errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(data), key=lambda e: list(e.path))
    if errors:
        lines = []
        for err in errors:
            field = ".".join(str(p) for p in err.path) or "(top level)"
            lines.append(f"{source}: {field}: {err.message}; allowed: {_allowed(err)}")
        raise ConfigError("\n".join(lines))
    return data


def load(path, schema_path):
    """Read a YAML file and validate it against the schema file; returns the parsed dict."""
    return load_with(path, json.loads(Path(schema_path).read_text()))


def load_with(path, schema: dict):
    """Read a YAML file and validate it against ``schema``; returns the parsed dict."""
    path = Path(path)
    try:
        data = yaml.load(path.read_text(), Loader=_StrictLoader)
    except ConfigError as err:
        raise ConfigError(f"{path}: {err}") from None
    except yaml.YAMLError as err:
        raise ConfigError(f"{path}: not valid YAML: {err}") from None
    except (OSError, UnicodeDecodeError) as err:
        raise ConfigError(f"{path}: cannot read: {err}") from None
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
FILE_FIELDS = ("reference", "findings", "validation.shots")
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
    classes = cfg["check"]["precision"]
    bad = []
    for path, spec in cfg["check"]["outputs"].items():
        spec = {"default": spec} if isinstance(spec, str) else spec
        for column, name in [("default", spec.get("default"))] + list(spec.get("columns", {}).items()):
            if name not in classes:
                bad.append(f"{source}: check.outputs.{path}.{column}: precision class {name!r} is not defined; "
                           f"allowed: one of {sorted(classes)}")
    if bad:
        raise ConfigError("\n".join(bad))
    return cfg
