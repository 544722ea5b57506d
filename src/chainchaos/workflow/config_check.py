"""The pipeline's config, checked before any rule runs (the Snakefile calls ``check_config``).

Three layers, each message naming the key (dotted, e.g. ``simulation.dt``), its value and what is
allowed:

1. config/schema.yaml, read as JSON schema: types, ranges, names, unknown keys;
2. what a JSON schema cannot say: every number finite (YAML's ``.nan`` and ``.inf`` are numbers);
3. what holds between keys, checked by the very objects the jobs build from the config
   (SceneParameters, StudySettings, OrbitSettings, SearchPlan, SelectionCriteria), and
   sites within the chain, scene names among the paper's scenes.

Every error of the first layer that finds any is reported, so one run names them all.
"""


from pathlib import Path

from chainchaos.errors import ConfigError, ParameterError
from chainchaos.project import project_root
from chainchaos.records.schema import (
    load_schema,
    nonfinite_errors,
    schema_errors,
)

#: The pipeline's config schema, in the project directory.
SCHEMA = Path("config/schema.yaml")


def config_schema(own_models: bool = True) -> dict:
    """The project's config schema (:data:`SCHEMA`) with the registries' names filled in
    (``records.schema.load_schema``)."""
    return load_schema(project_root("the pipeline's config schema") / SCHEMA, own_models)


def check_config(config: dict, schema: dict | None = None) -> None:
    """Raise ConfigError listing every wrong key of ``config`` (the merged config files and
    ``--config`` overrides); ``schema`` defaults to config/schema.yaml."""
    if schema is None:
        schema = config_schema()
    # each layer reads the keys as the layers before it promise them
    errors = schema_errors(config, schema) or nonfinite_errors(config) or consistency_errors(config)
    if errors:
        raise ConfigError(errors)


def typed_overrides(config: dict, overrides: dict) -> None:
    """Read the strings of nested ``--config`` values as a config file would have them.

    Snakemake types a top-level ``--config key=value`` but reads a mapping with YAML's base loader,
    whose scalars are all strings: ``--config search='{pinned_seed: 879}'`` would set the string
    '879'. Each such string in ``config`` becomes what YAML reads (879, 2.5e-4, true, empty);
    the schema then judges it like a value from a file."""
    import yaml

    def typed(text: str):
        value = yaml.safe_load(text) if text.strip() else None
        if isinstance(value, str):
            try:
                return float(text)  # YAML 1.1 reads 2.5e-4 (no dot) as a string
            except ValueError:
                return text
        return value

    def walk(target: dict, given: dict) -> None:
        for key, value in given.items():
            if isinstance(value, dict) and isinstance(target.get(key), dict):
                walk(target[key], value)
            elif isinstance(value, str) and target.get(key) == value:
                target[key] = typed(value)

    for key, value in overrides.items():
        if isinstance(value, dict) and isinstance(config.get(key), dict):
            walk(config[key], value)


def _labelled(err: ParameterError, blocks: list[tuple[str, dict]]) -> str:
    """The message of ``err`` with the config key it came from: the first block holding the
    parameter, else the first block."""
    found = ((path, key) for path, block in blocks for key in block if key.lower() == err.name.lower())
    path, key = next(found, (blocks[0][0], err.name))
    return f"config key {path}.{key} = {err.value!r}: allowed is {err.allowed}"


def _check(messages: list, blocks: list[tuple[str, dict]], build) -> None:
    try:
        build()
    except ParameterError as err:
        messages.append(_labelled(err, blocks))


def consistency_errors(config: dict) -> list[str]:
    """What holds between keys, by the objects the jobs build from the config."""
    from chainchaos.paper import panels
    from chainchaos.run.orbits import OrbitSettings
    from chainchaos.run.scenes import scene_parameters
    from chainchaos.studies.scan.runs import settings_for
    from chainchaos.studies.search.selection import SelectionCriteria
    from chainchaos.studies.search.stages import SearchPlan
    from chainchaos.studies.study.orbits import energy_range

    messages = []
    scenes = panels.scenes()
    claims = config.get("claims", {})
    for key, block in (("scenes", config.get("scenes", {})), ("claims.plateau_end", claims.get("plateau_end", {}))):
        unknown = sorted(set(block) - set(scenes))
        if unknown:
            messages.append(f"config key {key}: unknown scene name(s) {unknown}; allowed are {sorted(scenes)}")

    N = config["chain"]["N"]
    for path, site in _sites(config):
        if site > N:
            messages.append(f"config key {path} = {site!r}: allowed is a bead 1..chain.N = 1..{N}")

    chain = config["chain"]
    _check(messages, [("chain.selection", chain.get("selection", {})), ("chain", chain)],
           lambda: SelectionCriteria(alpha=float(chain["alpha"]), N=int(N), **chain.get("selection", {})))

    for name, scene in sorted(scenes.items()):
        own = config.get("scenes", {}).get(name, {})
        _check(messages, [(f"scenes.{name}", own), ("simulation", config["simulation"])],
               lambda: scene_parameters(config["simulation"], config.get("scenes", {}).get(name, {}), scene, name,
                                 panels.scene_observables(name)))

    scan = config.get("scan")
    if scan:
        for kind in ("energy_scan", "disorder"):
            blocks = [(f"scan.{kind}", scan[kind]), ("scan.settings", scan.get("settings", {}))]
            _check(messages, blocks, lambda: settings_for(kind, scan))
            _check(messages, blocks, lambda: energy_range(scan[kind]))  # no Numba in Snakemake's process

    search = config["search"]
    if search.get("archive") and search.get("pinned_seed") is None:
        messages.append(f"config key search.pinned_seed is empty while search.archive = {search['archive']!r} is used: "
                        "allowed is the archive's chosen seed (all runs on its chain; the archive's check compares "
                        "the two), or empty search.archive to search at this scale")
    for block in ("search", "search_full"):
        _check(messages, [(block, config[block])], lambda: SearchPlan.from_config(config[block]))
    for block in ("search", "verdicts"):
        settings = config[block]["settings"]
        _check(messages, [(f"{block}.settings", settings)], lambda: OrbitSettings.from_config(settings))

    return list(dict.fromkeys(messages))  # a key shared by several scenes is named once


def _sites(config: dict):
    """(dotted key, value) of every excited bead in the config."""
    for path, block in [("simulation", config["simulation"]),
                        *((f"scenes.{n}", b) for n, b in config.get("scenes", {}).items()),
                        *((f"numerics.{n}", b) for n, b in config.get("numerics", {}).items()
                          if isinstance(b, dict))]:
        if "excited_site" in block:
            yield f"{path}.excited_site", block["excited_site"]
    if "site" in config.get("scan", {}).get("energy_scan", {}):
        yield "scan.energy_scan.site", config["scan"]["energy_scan"]["site"]
