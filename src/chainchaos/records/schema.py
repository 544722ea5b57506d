"""The schemas the package's config and study files are checked against, and the checks.

A schema is JSON Schema in YAML (``config/schema.yaml`` of the project, the study schema shipped in
the package); a key marked ``x-registry: <registry>`` takes the names of a registry (the models,
the schemes, the study observables) as it is when the schema is loaded, so that a new model or a
model of one's own is allowed without an edit. Every check returns one message per wrong key,
naming the key, its value and what is allowed.
"""

import copy
import functools
import math
from pathlib import Path


# JSON-schema keywords shown as constraints, with how each reads.
CONSTRAINTS = {
    "minimum": ">= {}",
    "exclusiveMinimum": "> {}",
    "maximum": "<= {}",
    "exclusiveMaximum": "< {}",
    "minItems": "{} or more items",
    "pattern": "matches `{}`",
}


def registries(own_models: bool = True) -> dict[str, list]:
    """The names a key marked ``x-registry: <registry>`` in the schema may take: the models of
    ``chainchaos.system.models`` (with ``own_models``, those added in this process too; without,
    the package's, as its documentation lists them; ``models`` the bond models the paper's
    pipeline runs, ``study_models`` every model) and the schemes (``study_schemes`` with the split
    models' three-part schemes) of
    ``chainchaos.engine.integrators``, so that a new model or scheme is allowed without an edit to
    the schema."""
    from chainchaos.engine.integrators import SCHEMES
    from chainchaos.engine.split_schemes import SPLIT_SCHEMES
    from chainchaos.observe.registry import study_observables
    from chainchaos.system.models import BOND_MODELS, MODELS, PACKAGE_MODELS

    # the paper's pipeline (scenes, scans, numerics) runs bond models; a study runs any model
    models = list(BOND_MODELS) if own_models else [m for m in PACKAGE_MODELS if m in BOND_MODELS]
    study_models = list(MODELS) if own_models else list(PACKAGE_MODELS)
    return {"models": models, "study_models": study_models, "schemes": list(SCHEMES),
            "study_schemes": list(SCHEMES) + list(SPLIT_SCHEMES), "study_observables": study_observables()}


def _fill_registry_enums(node, names: dict[str, list]) -> None:
    """Give every schema node marked ``x-registry`` its registry's names as ``enum`` (with null
    where the node's type allows it), in place: Snakemake's own validation, which reads the file,
    ignores the marker, and check_config, which reads this, names the allowed values."""
    if isinstance(node, dict):
        if "x-registry" in node:
            nullable = "null" in (node["type"] if isinstance(node.get("type"), list) else [node.get("type")])
            node["enum"] = names[node["x-registry"]] + ([None] if nullable else [])
        for value in node.values():
            _fill_registry_enums(value, names)
    elif isinstance(node, list):
        for value in node:
            _fill_registry_enums(value, names)


def load_yaml(text: str):
    """``text`` read by YAML's safe loader, libyaml's where PyYAML has it (the workflow reads its
    schemas and study files about twenty times before the first job: ten times faster)."""
    import yaml

    return yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))


def load_schema(path: Path, own_models: bool = True) -> dict:
    """The schema at ``path`` with the registries' names filled in (a copy of its own for each
    caller; the file is read once per process and version of it, the registries as they are now: a
    model added since is allowed; ``own_models=False``: the package's models only, for its
    documentation)."""
    path = Path(path).resolve()
    schema = copy.deepcopy(_parsed_schema(path, path.stat().st_mtime_ns))
    _fill_registry_enums(schema, registries(own_models))
    return schema


@functools.cache


def _parsed_schema(path: Path, version: int) -> dict:
    return load_yaml(path.read_text())


def _value(v) -> str:
    if v is None:
        return "empty"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (dict, list)):
        import json

        return json.dumps(v)
    return str(v)


def _type(schema: dict) -> str:
    types = schema.get("type", "")
    types = [types] if isinstance(types, str) else list(types)
    text = " or ".join("empty" if t == "null" else t for t in types if t)
    if "enum" in schema:
        text += ": " + ", ".join(f"`{_value(v)}`" for v in schema["enum"])
    limits = [fmt.format(schema[k]) for k, fmt in CONSTRAINTS.items() if k in schema]
    items = schema.get("items")
    if isinstance(items, dict) and "properties" not in items:
        text += f" of {_type(items)}"
        return text + (f", {', '.join(limits)}" if limits else "")
    return text + (f" ({', '.join(limits)})" if limits else "")


def allowed(schema: dict) -> str:
    """What a key with this schema allows, in words: its type, values and limits (the config
    README's column, for error messages)."""
    return _type(schema).replace("`", "'")


def _dotted(path) -> str:
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text or "(top level)"


def schema_errors(config: dict, schema: dict, what: str = "config key") -> list[str]:
    """One message per violation of the JSON schema, each starting with ``what`` and the key."""
    from jsonschema.validators import validator_for

    validator = validator_for(schema)(schema)
    messages = []
    for error in sorted(validator.iter_errors(config), key=lambda e: [str(p) for p in e.absolute_path]):
        key = _dotted(error.absolute_path)
        if error.validator == "additionalProperties" and isinstance(error.instance, dict):
            known = sorted(error.schema.get("properties", {}))
            unknown = sorted(set(error.instance) - set(known))
            messages.append(f"{what} {key}: unknown key(s) {unknown}; allowed are {known}")
        elif error.validator == "required":
            messages.append(f"{what} {key}: {error.message}")
        else:
            messages.append(f"{what} {key} = {error.instance!r}: allowed is {allowed(error.schema)}")
    return messages


def nonfinite_errors(config, path=(), what: str = "config key") -> list[str]:
    """Messages for NaN and infinite numbers anywhere in ``config``."""
    if isinstance(config, dict):
        return [m for k, v in config.items() for m in nonfinite_errors(v, (*path, k), what)]
    if isinstance(config, list):
        return [m for i, v in enumerate(config) for m in nonfinite_errors(v, (*path, i), what)]
    if isinstance(config, float) and not math.isfinite(config):
        return [f"{what} {_dotted(path)} = {config!r}: allowed is a finite number"]
    return []
