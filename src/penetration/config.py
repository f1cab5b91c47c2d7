"""Load YAML config and scene files, validated against a JSON schema.

Errors name the file, the field (dotted path) and what is allowed, and are
raised before any computation starts.
"""
from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import yaml


class ConfigError(ValueError):
    """A config file that does not satisfy its schema."""


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
    """Read a YAML file and validate it; returns the parsed dict."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except yaml.YAMLError as err:
        raise ConfigError(f"{path}: not valid YAML: {err}") from None
    schema = json.loads(Path(schema_path).read_text())
    return validate(data if data is not None else {}, schema, str(path))
