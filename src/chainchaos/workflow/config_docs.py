"""config/README.md and studies/README.md, generated from config/schema.yaml and the study schema
(src/chainchaos/studies/study/schema.yaml): every key, its type, allowed values, default and
description.

The schema is the single place a key is described: a test checks that every key has a
description and that the committed config/README.md is what this module writes, so the two cannot
drift. After a change to the schema run ``python -m chainchaos.workflow.config_docs`` (``--check``: only
compare). Needs PyYAML (installed with Snakemake, the workflow extra).
"""

import argparse
import sys
from dataclasses import dataclass
from pathlib import Path

from chainchaos.project import project_root
from chainchaos.studies.study import spec as study_spec
from chainchaos.records.schema import _type, _value, load_schema
from chainchaos.workflow.config_check import SCHEMA, config_schema

#: The pipeline's config schema and its README, in the project directory.
README = Path("config/README.md")
#: The study schema, package data; its README in the project directory.
STUDY_SCHEMA = study_spec.SCHEMA
STUDY_README = Path("studies/README.md")


@dataclass
class Key:
    path: str  # dotted, "<scene name>" for a free-form name, "[]" for an array's items
    schema: dict
    required: bool
    same_as: str = ""  # path of an earlier key with the very same schema (a YAML anchor)


def _children(schema: dict, path: str):
    """(path, schema, required) of the keys one level below ``schema`` at ``path``."""
    prefix = f"{path}." if path else ""
    required = set(schema.get("required", ()))
    for name, sub in schema.get("properties", {}).items():
        yield f"{prefix}{name}", sub, name in required
    extra = schema.get("additionalProperties")
    if isinstance(extra, dict) and ("properties" in extra or "type" in extra):
        yield f"{prefix}<{_free_name(path)}>", extra, False
    items = schema.get("items")
    if isinstance(items, dict) and "properties" in items:
        yield from _children(items, f"{path}[]")


def _free_name(path: str) -> str:
    """What the free-form keys of an object at ``path`` name."""
    return "scene name" if path.split(".")[-1] in ("scenes", "plateau_end") else "name"


def keys(schema: dict) -> list[Key]:
    """Every key of the schema, depth first in schema order. A key whose schema is the same
    object as an earlier one with the same name (a YAML anchor or merge) records that key's path."""
    seen: dict[tuple[str, int], str] = {}
    out: list[Key] = []

    def walk(node: dict, path: str) -> None:
        for child, sub, required in _children(node, path):
            name = child.rsplit(".", 1)[-1]
            first = seen.setdefault((name, id(sub)), child)
            out.append(Key(child, sub, required, "" if first == child else first))
            if first == child:
                walk(sub, child)

    walk(schema, "")
    return out


def undescribed(schema: dict) -> list[str]:
    """Paths of the keys that have no description."""
    return [k.path for k in keys(schema) if not k.same_as and not k.schema.get("description")]


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _row(key: Key) -> str:
    s = key.schema
    default = f"`{_value(s['default'])}`" if "default" in s else ("required" if key.required else "")
    description = s.get("description", "")
    if key.same_as:
        description = f"as `{key.same_as}`" + (f": {description}" if description else "")
    return f"| `{key.path}` | {_cell(_type(s))} | {_cell(default)} | {_cell(description)} |"


HEADER = """# Configuration keys

<!-- Generated from config/schema.yaml by `python -m chainchaos.workflow.config_docs`; do not edit by hand. -->

The pipeline reads `config/config.yaml` (paper scale); `--configfile config/quick.yaml` layers the
quick scale over it, and `--config key=value` overrides single keys. `config/schema.yaml`
validates the merged config before any rule runs: a key not listed here, or a value outside what is
allowed, stops the run with a message naming the key. Times are in units of `1/omega_max`.

*Default*: the value the schema fills in when the key is absent; *required*: the key must be given
(config/config.yaml gives every required key). `<scene name>` stands for a scene such as
`hertz_H0.25`; `[]` for each item of a list.
"""


STUDY_HEADER = """# Study keys

<!-- Generated from src/chainchaos/studies/study/schema.yaml by `python -m chainchaos.workflow.config_docs`; do not edit by hand. -->

A study is one file `studies/<name>.yaml`, run by `snakemake --cores 2 study --config study=<name>`
or, in Python, by `chainchaos.run_study("<name>")`. The study schema validates it before
anything runs: a key not listed here, a value outside what is allowed, or keys that do not fit
each other (an excited site beyond N, a mode above N, a step longer than the run) stop it with a
message naming the key. Times are in units of `1/omega_max` of the homogeneous chain.

A study given in Python as a dict of these keys (`run_study({...})`, `load_study({...})`) may
also carry the two things a file gives by being a file: `name`, its name (a file's stem), and
`directory`, where a model file it names is looked up (a file's folder).

*Default*: the value taken when the key is absent; *required*: the key must be given. `[]`
stands for each item of a list.
"""


def render(schema: dict | None = None, header: str = HEADER) -> str:
    """The text of config/README.md (or, with the study schema and :data:`STUDY_HEADER`, of
    studies/README.md)."""
    schema = config_schema(own_models=False) if schema is None else schema
    all_keys = keys(schema)
    lines = [header]
    for top in schema["properties"]:
        block = [k for k in all_keys if k.path == top or k.path.startswith(f"{top}.")]
        lines += [f"## `{top}`", ""]
        lines += ["| key | type, allowed values | default | description |", "| --- | --- | --- | --- |"]
        lines += [_row(k) for k in block]
        lines.append("")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m chainchaos.workflow.config_docs",
                                     description="Write (or --check) config/README.md and studies/README.md "
                                                 "from their schemas.")
    parser.add_argument("--check", action="store_true", help="only compare; exit 1 if a file differs")
    args = parser.parse_args(argv)
    status = 0
    root = project_root("python -m chainchaos.workflow.config_docs")
    for schema_path, readme, header in ((SCHEMA, README, HEADER), (STUDY_SCHEMA, STUDY_README, STUDY_HEADER)):
        schema = load_schema(root / schema_path, own_models=False)
        missing = undescribed(schema)
        if missing:
            print(f"{schema_path}: keys without a description: " + ", ".join(missing), file=sys.stderr)
            status = 1
            continue
        text = render(schema, header)
        target = root / readme
        if target.is_file() and target.read_text() == text:
            continue
        if args.check:
            print(f"{readme} is out of date: run python -m chainchaos.workflow.config_docs", file=sys.stderr)
            status = 1
            continue
        target.write_text(text)
        print(f"wrote {readme}", file=sys.stderr)
    return status


if __name__ == "__main__":
    sys.exit(main())
