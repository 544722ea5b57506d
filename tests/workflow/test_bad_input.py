"""Bad input everywhere a user types it: every config key and every command-line option, with a
wrong type, a value out of range, an unknown name, NaN, and files that are missing, empty, corrupt
or not a chain. Each is refused before anything runs, with a message naming the key or option and
what is allowed, and nothing is written.

Config keys are checked through chainchaos.workflow.config_check.check_config, the function the Snakefile
calls before any rule; a few real ``snakemake -n`` runs check that the Snakefile does call it."""

import copy
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from chainchaos import random_chain
from chainchaos.errors import ConfigError
from chainchaos.records.io import chain_dataset, write_netcdf
from chainchaos.workflow import cli, config_docs
from chainchaos.workflow.config_check import check_config, typed_overrides

ROOT = Path(__file__).resolve().parents[2]
SCENE = "hertz_H1.8"  # stands for <scene name> in a key's path


def _merge(base: dict, extra: dict) -> dict:
    for key, value in extra.items():
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            _merge(base[key], value)
        else:
            base[key] = value
    return base


def _load(name: str) -> dict:
    return yaml.safe_load((ROOT / "config" / name).read_text())


CONFIG = _merge(_load("config.yaml"), _load("quick.yaml"))
SCHEMA = config_docs.config_schema()


# ---------------------------------------------------------------------------- config: the table


def _segments(path: str) -> list:
    """The keys and list indices of a schema key path, a scene name for <scene name>."""
    out = []
    for part in path.split("."):
        name = part.removesuffix("[]")
        out.append(SCENE if name.startswith("<") else name)
        if part.endswith("[]"):
            out.append(0)
    return out


def _dotted(segments) -> str:
    text = ""
    for s in segments:
        text += f"[{s}]" if isinstance(s, int) else (f".{s}" if text else s)
    return text


def _bad_values(schema: dict) -> list[tuple[str, object]]:
    """(what is wrong, value) for a key of this schema."""
    types = schema.get("type", [])
    types = [types] if isinstance(types, str) else list(types)
    if "object" in types:
        return [("wrong type", 12345 if "string" in types else "text")]  # a name or a mapping: a number is neither
    if "array" in types:
        out = [("wrong type", 3)]
        if schema.get("minItems", 0) >= 1:
            out.append(("too few items", []))
        items = schema.get("items", {})
        if "properties" not in items:
            n = max(schema.get("minItems", 1), 1)
            out += [(f"item: {what}", [value] * n) for what, value in _bad_values(items)]
        return out
    out = []
    if {"number", "integer"} & set(types):
        out += [("wrong type", "ten"), ("NaN", math.nan), ("infinite", -math.inf if "maximum" in schema else math.inf)]
        if "number" not in types:
            out.append(("not an integer", 2.5))
        step = 1 if "number" not in types else 0.5
        for bound, value in (("minimum", lambda m: m - step), ("exclusiveMinimum", lambda m: m),
                             ("maximum", lambda m: m + step), ("exclusiveMaximum", lambda m: m)):
            if bound in schema:
                out.append((f"out of range ({bound})", value(schema[bound])))
    if "string" in types:
        out.append(("wrong type", 12345))
        if "enum" in schema:
            out.append(("unknown name", "no-such-name"))
        if "pattern" in schema:
            out.append(("not matching its pattern", "paper.txt"))
    if "boolean" in types:
        out.append(("wrong type", "maybe"))
    return out


def _with(config: dict, segments: list, value=None, delete=False) -> dict:
    config = copy.deepcopy(config)
    node = config
    for s in segments[:-1]:
        if isinstance(node, dict) and s not in node:
            node[s] = {}
        node = node[s]
    if delete:
        del node[segments[-1]]
    else:
        node[segments[-1]] = value
    return config


KEYS = config_docs.keys(SCHEMA)
VALUE_CASES = [(key.path, what, value) for key in KEYS for what, value in _bad_values(key.schema)]
REQUIRED_CASES = [key.path for key in KEYS if key.required]
CLOSED_OBJECTS = [""] + [key.path for key in KEYS if key.schema.get("additionalProperties") is False]


def _refused(config: dict) -> str:
    with pytest.raises(ConfigError) as err:
        check_config(config, SCHEMA)
    return str(err.value)


def test_the_config_files_pass():
    check_config(copy.deepcopy(CONFIG), SCHEMA)
    check_config(_load("config.yaml"), SCHEMA)


def test_the_table_covers_every_key():
    covered = {path for path, _, _ in VALUE_CASES}
    assert covered == {key.path for key in KEYS}
    assert len(VALUE_CASES) > 3 * len(KEYS)


@pytest.mark.parametrize("path, what, value", VALUE_CASES,
                         ids=[f"{p}:{w}" for p, w, _ in VALUE_CASES])
def test_a_bad_config_value_is_named_with_what_is_allowed(path, what, value):
    segments = _segments(path)
    message = _refused(_with(CONFIG, segments, value))
    assert f"config key {_dotted(segments)}" in message, message
    assert "allowed" in message, message


@pytest.mark.parametrize("path", REQUIRED_CASES)
def test_a_missing_required_key_is_named(path):
    segments = _segments(path)
    message = _refused(_with(CONFIG, segments, delete=True))
    parent = _dotted(segments[:-1]) or "(top level)"
    assert f"config key {parent}: '{segments[-1]}' is a required property" in message, message


@pytest.mark.parametrize("path", CLOSED_OBJECTS)
def test_an_unknown_key_is_named_with_the_known_ones(path):
    segments = _segments(path) if path else []
    message = _refused(_with(CONFIG, [*segments, "no_such_key"], 1))
    assert f"config key {_dotted(segments) or '(top level)'}: unknown key(s) ['no_such_key']; allowed are" in message


# What the schema cannot say: keys that bound each other. (key, value, what the message says)
CROSS_CASES = [
    (["simulation", "excited_site"], 41, "config key simulation.excited_site = 41: allowed is a bead 1..chain.N = 1..40"),
    (["scenes", SCENE, "excited_site"], 50, f"config key scenes.{SCENE}.excited_site = 50: allowed is a bead 1..chain.N"),
    (["numerics", "drift", "excited_site"], 41, "config key numerics.drift.excited_site = 41: allowed is a bead"),
    (["scan", "energy_scan", "site"], 99, "config key scan.energy_scan.site = 99: allowed is a bead 1..chain.N"),
    (["simulation", "dt"], 5000.0, "config key simulation.dt = 5000.0: allowed is dt <= t_final = 1000.0"),
    (["scenes", SCENE, "t_final"], 1e-3, "config key simulation.dt = 0.01: allowed is dt <= t_final = 0.001"),
    (["scan", "energy_scan", "energy_min"], 50.0,
     "config key scan.energy_scan.energy_min = 50.0: allowed is 0 < energy_min <= energy_max = 10"),
    (["scan", "disorder", "dt"], 1e6, "config key scan.disorder.dt = 1000000.0: allowed is dt <= t_final"),
    (["search", "settings", "dt"], 1e6, "config key search.settings.dt = 1000000.0: allowed is dt <= t_final"),
    (["verdicts", "settings", "dt"], 1e6, "config key verdicts.settings.dt = 1000000.0: allowed is dt <= t_final"),
    (["chain", "selection", "p_min"], 3.5, "config key chain.selection.p_min = 3.5: allowed is <= p_max"),
    (["chain", "selection", "mode"], 41, "config key chain.selection.mode = 41: allowed is 1..N = 1..40"),
    (["chain", "N"], 20, "allowed is 1..N = 1..20"),  # the selection's mode 34 no longer fits
]


@pytest.mark.parametrize("segments, value, expected", CROSS_CASES, ids=[_dotted(c[0]) for c in CROSS_CASES])
def test_keys_that_bound_each_other(segments, value, expected):
    message = _refused(_with(CONFIG, segments, value))
    assert expected in message, message


@pytest.mark.parametrize("block", ["scenes", "claims.plateau_end"])
def test_an_unknown_scene_name_is_named_with_the_scenes(block):
    message = _refused(_with(CONFIG, [*block.split("."), "hertz_H9.9"], {"dt": 1e-3} if block == "scenes" else 10.0))
    assert f"config key {block}: unknown scene name(s) ['hertz_H9.9']; allowed are" in message
    assert SCENE in message


def test_every_wrong_key_is_named_at_once():
    config = _with(_with(CONFIG, ["simulation", "dt"], -1.0), ["figures", "dpi"], 1)
    message = _refused(config)
    assert "config key figures.dpi = 1" in message and "config key simulation.dt = -1.0" in message


def test_nested_config_overrides_are_read_as_yaml():
    """Snakemake reads a mapping given with --config as strings; they are typed as in a file."""
    config = copy.deepcopy(CONFIG)
    overrides = {"search": {"pinned_seed": "879"}, "scenes": {SCENE: {"dt": "2.5e-4"}},
                 "simulation": {"integrator": "verlet", "dt": ".nan"}}
    _merge(config, copy.deepcopy(overrides))
    typed_overrides(config, overrides)
    assert config["search"]["pinned_seed"] == 879 and config["scenes"][SCENE]["dt"] == 2.5e-4
    assert config["simulation"]["integrator"] == "verlet" and math.isnan(config["simulation"]["dt"])
    message = _refused(config)
    assert "config key simulation.dt = nan: allowed is a finite number" in message


# ---------------------------------------------------------------------------- config: real dry runs


def _snakemake(*args, results):
    done = subprocess.run([sys.executable, "-m", "snakemake", "-n", "--cores", "1", "--configfile",
                           "config/quick.yaml", "--config", f"results={results}", *args],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    return done.returncode, done.stdout + done.stderr


@pytest.mark.parametrize("extra, expected", [
    (("simulation={dt: .nan}",), "config key simulation.dt = nan: allowed is a finite number"),
    ((f"scenes={{{SCENE}: {{excited_site: 50}}}}",), f"config key scenes.{SCENE}.excited_site = 50"),
    (("--configfile", "BAD"), "config key simulation.integrator = 'rk4': allowed is string: 'verlet'"),
    (("manuscript={beyond: [{hertz500: [nosuch]}]}",),
     "config manuscript.beyond: study hertz500 has no figure nosuch; its figures: ['spreading', 'comparison']"),
    (("manuscript={beyond: [hertz500, {hertz500: []}]}",), "config manuscript.beyond: study hertz500 is named twice"),
])
@pytest.mark.pipeline
def test_snakemake_refuses_a_bad_config_before_any_job(tmp_path, extra, expected):
    bad = tmp_path / "bad.yaml"
    bad.write_text("simulation:\n  integrator: rk4\n")
    results = tmp_path / "results"
    code, out = _snakemake(*[str(bad) if e == "BAD" else e for e in extra], results=results)
    assert code != 0 and expected in out, out[-3000:]
    assert "Job stats" not in out and not results.exists()


@pytest.mark.pipeline
def test_snakemake_accepts_a_typed_nested_override(tmp_path):
    code, out = _snakemake("search={pinned_seed: 879}", results=tmp_path / "results")
    assert code == 0, out[-3000:]
    assert "search_filter" not in out and "/search-score-hertz/" in out


# ---------------------------------------------------------------------------- command line


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad_input")
    chain = chain_dataset(random_chain(879, 5.0))
    write_netcdf(chain, d / "chain.nc")
    (d / "empty.nc").write_bytes(b"")
    (d / "junk.nc").write_bytes(np.random.default_rng(0).bytes(4096))
    (d / "truncated.nc").write_bytes((d / "chain.nc").read_bytes()[:3000])
    (d / "text.nc").write_text("radius\n1.0\n")
    write_netcdf(chain.drop_vars("K2"), d / "no_K2.nc")
    write_netcdf(chain.drop_vars("radius").assign(radius=("bond", np.ones(41))), d / "radius_on_bonds.nc")
    write_netcdf(xr.Dataset({"participation": ("time", np.ones(3))}), d / "scene_like.nc")
    write_netcdf(chain.assign(radius=("site", np.full(40, np.nan))), d / "nan_radius.nc")
    (d / "a_directory.nc").mkdir()
    (d / "radii_empty.txt").write_text("")
    (d / "radii_words.txt").write_text("small\nlarge\n")
    (d / "radii_one.txt").write_text("1.0\n")
    (d / "radii_nan.txt").write_text("1.0\nnan\n2.0\n")
    (d / "radii_negative.txt").write_text("1.0\n-2.0\n")
    (d / "radii_ragged.txt").write_text("1.0 2.0\n3.0\n")
    return d


def _main(argv, capsys):
    try:
        code = cli.main([str(a) for a in argv])
    except SystemExit as stop:  # argparse refuses before the command runs
        code = stop.code
    return code, capsys.readouterr().err


CHAIN = ["chain", "--out", "OUT"]
SIMULATE = ["simulate", "--chain", "chain.nc", "--model", "hertz", "--energy", "1", "--t-final", "10", "--out", "OUT"]
ENSEMBLE = ["ensemble", "--alpha", "5", "--realizations", "10", "--out", "OUT"]
BENCH = ["bench", "--steps", "10", "--repeats", "1"]


def _set(base: list, option: str, *values) -> list:
    """``base`` with ``option`` given ``values`` (replacing its value there, if any)."""
    argv = list(base)
    if option in argv:
        i = argv.index(option)
        del argv[i:i + 2]
    return [*argv, option, *values]


# (command line, option named, what the message says is allowed)
CLI_CASES = [
    # chain
    (_set(CHAIN, "--seed", "1.5"), "--seed", "an integer >= 0"),
    (_set(CHAIN, "--seed", "-1"), "--seed", "an integer >= 0"),
    (_set(CHAIN, "--alpha", "0.5"), "--alpha", "a finite number >= 1"),
    (_set(CHAIN, "--alpha", "nan"), "--alpha", "a finite number >= 1"),
    (_set(CHAIN, "--alpha", "five"), "--alpha", "a finite number >= 1"),
    (_set(CHAIN, "--N", "1"), "--N", "an integer >= 2"),
    (_set(CHAIN, "--N", "forty"), "--N", "an integer >= 2"),
    (_set(CHAIN, "--n-seeds", "0"), "--n-seeds", "an integer >= 1"),
    (_set(CHAIN, "--wall-radius", "0"), "--wall-radius", "a finite number > 0"),
    (_set(CHAIN, "--wall-radius", "inf"), "--wall-radius", "a finite number > 0"),
    (_set(CHAIN, "--reference-radius", "2"), "--reference-radius", "only together with --radii"),
    (_set(CHAIN, "--reference-radius", "-1"), "--reference-radius", "a finite number > 0"),
    (_set(CHAIN, "--radii", "absent.txt"), "--radii", "does not exist"),
    (_set(CHAIN, "--radii", "a_directory.nc"), "--radii", "is not a file"),
    (_set(CHAIN, "--radii", "radii_empty.txt"), "--radii", "at least 2"),
    (_set(CHAIN, "--radii", "radii_one.txt"), "--radii", "at least 2"),
    (_set(CHAIN, "--radii", "radii_words.txt"), "--radii", "one number per line"),
    (_set(CHAIN, "--radii", "radii_ragged.txt"), "--radii", "one number per line"),
    (_set(CHAIN, "--radii", "chain.nc"), "--radii", "one number per line"),
    (_set(CHAIN, "--radii", "radii_nan.txt"), "--radii", "finite radii > 0"),
    (_set(CHAIN, "--radii", "radii_negative.txt"), "--radii", "finite radii > 0"),
    (_set(_set(CHAIN, "--radii", "radii_nan.txt"), "--search"), "--search", "not allowed with argument --radii"),
    (_set(CHAIN, "--out", "a_directory.nc"), "--out", "a file path"),
    (_set(CHAIN, "--out", "chain.nc/inside.nc"), "--out", "is a file, not a directory"),
    (["chain"], "--out", "required"),
    # simulate
    (_set(SIMULATE, "--chain", "absent.nc"), "--chain", "does not exist"),
    (_set(SIMULATE, "--chain", "a_directory.nc"), "--chain", "is not a file"),
    (_set(SIMULATE, "--chain", "empty.nc"), "--chain", "not a readable NetCDF file"),
    (_set(SIMULATE, "--chain", "junk.nc"), "--chain", "not a readable NetCDF file"),
    (_set(SIMULATE, "--chain", "truncated.nc"), "--chain", "not a readable NetCDF file"),
    (_set(SIMULATE, "--chain", "text.nc"), "--chain", "not a readable NetCDF file"),
    (_set(SIMULATE, "--chain", "no_K2.nc"), "--chain", "lacks variable(s) ['K2']"),
    (_set(SIMULATE, "--chain", "scene_like.nc"), "--chain", "lacks variable(s)"),
    (_set(SIMULATE, "--chain", "radius_on_bonds.nc"), "--chain", "wrong dimensions"),
    (_set(SIMULATE, "--chain", "nan_radius.nc"), "--chain", "finite radii > 0"),
    (_set(SIMULATE, "--model", "morse"), "--model", "or one of your own as 'package.module:NAME'"),
    (_set(SIMULATE, "--model", "absent.py:MORSE"), "--model", "an existing Python file before ':'"),
    (_set(SIMULATE, "--model", "no_such_module:MORSE"), "--model", "an importable module before ':'"),
    (_set(SIMULATE, "--W", "4"), "--W", "only for a model on a KG lattice"),
    (_set(SIMULATE, "--W", "-4"), "--W", "a finite number > 0"),
    (_set(_set(SIMULATE, "--model", "kg"), "--W", "4"), "--chain", "no chain file for model 'kg'"),
    (_set(_set(_set(SIMULATE, "--model", "kg"), "--W", "4"), "--seed", "-1"), "--seed", "an integer >= 0"),
    (_set(_set(_set(SIMULATE, "--model", "kg"), "--W", "4"), "--N", "1"), "--N", "an integer >= 2"),
    (_set(SIMULATE, "--energy", "0"), "--energy", "a finite number > 0"),
    (_set(SIMULATE, "--energy", "nan"), "--energy", "a finite number > 0"),
    (_set(SIMULATE, "--energy", "one"), "--energy", "a finite number > 0"),
    (_set(SIMULATE, "--t-final", "-10"), "--t-final", "a finite number > 0"),
    (_set(SIMULATE, "--t-final", "inf"), "--t-final", "a finite number > 0"),
    (_set(SIMULATE, "--dt", "0"), "--dt", "a finite number > 0"),
    (_set(SIMULATE, "--dt", "100"), "--dt", "dt <= t_final"),
    (_set(SIMULATE, "--integrator", "rk4"), "--integrator", "choose from"),
    (_set(SIMULATE, "--observables", "temperature"), "--observables", "choose from"),
    (_set(_set(SIMULATE, "--model", "fput"), "--observables", "n_gaps"), "--observables",
     "gap observables only with a model whose bonds open: ['hertz']"),
    (_set(SIMULATE, "--site", "0"), "--site", "an integer >= 1"),
    (_set(SIMULATE, "--site", "41"), "--site", "1..40"),
    (_set(SIMULATE, "--site", "x"), "--site", "an integer >= 1"),
    (_set(SIMULATE, "--k4-sign", "2"), "--k4-sign", "choose from"),
    (_set(SIMULATE, "--deviation-seed", "-3"), "--deviation-seed", "an integer >= 0"),
    (_set(SIMULATE, "--samples-per-decade", "0"), "--samples-per-decade", "an integer >= 1"),
    (_set(SIMULATE, "--max-energy-error", "nan"), "--max-energy-error", "a finite number > 0"),
    (_set(SIMULATE, "--exponents", "-1"), "--exponents", "an integer >= 0"),
    (_set(SIMULATE, "--gali-order", "1"), "--gali-order", "an integer >= 2"),
    (_set(SIMULATE, "--out", "a_directory.nc"), "--out", "a file path"),
    (SIMULATE[:SIMULATE.index("--energy")] + ["--t-final", "10", "--out", "OUT"], "--energy", "required"),
    # ensemble
    (_set(ENSEMBLE, "--alpha", "0.5", "5"), "--alpha", "a finite number >= 1"),
    (_set(ENSEMBLE, "--alpha", "nan"), "--alpha", "a finite number >= 1"),
    (_set(ENSEMBLE, "--realizations", "1"), "--realizations", "an integer >= 2"),
    (_set(ENSEMBLE, "--realizations", "many"), "--realizations", "an integer >= 2"),
    (_set(ENSEMBLE, "--N", "0"), "--N", "an integer >= 2"),
    (_set(ENSEMBLE, "--first-seed", "-1"), "--first-seed", "an integer >= 0"),
    (_set(ENSEMBLE, "--convention", "kinetic"), "--convention", "choose from"),
    (_set(ENSEMBLE, "--out", "chain.nc/inside.nc"), "--out", "is a file, not a directory"),
    # bench
    (_set(BENCH, "--model", "morse"), "--model", "choose from"),
    (_set(BENCH, "--integrator", "euler"), "--integrator", "choose from"),
    (_set(BENCH, "--N", "1"), "--N", "an integer >= 2"),
    (_set(BENCH, "--steps", "0"), "--steps", "an integer >= 1"),
    (_set(BENCH, "--repeats", "0.5"), "--repeats", "an integer >= 1"),
]


def test_the_table_covers_every_option():
    parser = cli.build_parser()
    commands = next(a for a in parser._actions if a.dest == "command").choices
    options = {(name, opt) for name, sub in commands.items() for action in sub._actions
               for opt in action.option_strings if opt not in ("-h", "--help", "--json")}
    covered = {(argv[0], option) for argv, option, _ in CLI_CASES}
    assert options <= covered, sorted(options - covered)


@pytest.mark.parametrize("argv, option, allowed", CLI_CASES,
                         ids=[f"{a[0]} {o} {a[a.index(o) + 1] if o in a[:-1] else ''}".strip() for a, o, _ in CLI_CASES])
def test_a_bad_option_is_named_and_nothing_is_written(files, capsys, monkeypatch, argv, option, allowed):
    monkeypatch.chdir(files)
    out = files / "out" / "written.nc"
    before = sorted(p.name for p in files.rglob("*"))
    code, err = _main([str(out) if a == "OUT" else a for a in argv], capsys)
    assert code == 2, err
    assert option in err and allowed in err, err
    assert not out.exists() and sorted(p.name for p in files.rglob("*")) == before
