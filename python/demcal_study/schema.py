"""A study file against schema.json (JSON Schema, draft 7, checked by Debian's python3-jsonschema): the first
error it breaks becomes one line naming the file and the field, e.g.
`data/studies/x.json: inversion.restarts: 'a' is not of type 'integer'`."""
import json
import math
import os

import jsonschema

from .errors import fail

SCHEMA_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "schema.json")


def schema():
    with open(SCHEMA_PATH) as f:
        return json.load(f)


def field_path(path):
    """The field an error is about, as the study file writes it: surfaces[0].design.kind."""
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def message(error):
    """One error in today's words: unknown and missing fields named, enums listed, the schema's own
    errorMessage where it gives one, else jsonschema's message after the field."""
    where = field_path(error.absolute_path)
    prefix = f"{where}: " if where else ""
    if error.validator == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        unknown = sorted(set(error.instance) - set(allowed))
        return f"{prefix}unknown field \"{unknown[0]}\" (allowed: {', '.join(allowed)})"
    if error.validator == "required":
        missing = [name for name in error.validator_value if name not in error.instance]
        return f"{prefix}missing \"{missing[0]}\""
    custom = error.schema.get("errorMessage") if isinstance(error.schema, dict) else None
    if custom:
        return f"{where} {custom}" if where else custom
    if error.validator == "enum":
        return f"{where} must be one of {', '.join(sorted(map(str, error.validator_value)))}"
    return f"{prefix}{error.message}"


def non_finite(value, path=()):
    """The path of the first NaN or infinity in `value` (Python's json reads NaN, Infinity and 1e400 as such,
    and JSON Schema's number takes them), else None."""
    if isinstance(value, float) and not math.isfinite(value):
        return path
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    for key, item in items:
        found = non_finite(item, path + (key,))
        if found is not None:
            return found
    return None


def check(study, path):
    """Stops on the first error of `study` (read from `path`) in the schema's order."""
    where = non_finite(study)
    if where is not None:
        value = study
        for key in where:
            value = value[key]
        fail(f"{path}: {field_path(where)}: {value} is not a finite number")
    error = next(iter(jsonschema.Draft7Validator(schema()).iter_errors(study)), None)
    if error is not None:
        fail(f"{path}: {message(error)}")
