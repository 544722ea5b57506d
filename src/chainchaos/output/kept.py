"""Results kept as data, keyed by the settings that determine their numbers.

A kept file (``data/search/search_full.nc``, ``data/disorder/disorder_full.nc``, the archives of
later studies) is an expensive result stored in the repository, which a run reads instead of
computing it. It may stand in for the run's own computation only when it answers the same
question with the same code. So every kept file records three global attributes:

``kept_settings``
    the canonical settings that determine its numbers, as JSON with sorted keys (:func:`canonical`:
    plain data; a whole-number float is written as an integer, so ``1.0e+5`` and ``100000`` are one
    setting);
``kept_settings_digest``
    the SHA-256 of that JSON (:func:`digest`): equal digests, equal settings;
``result_version``
    an integer of the code that computes the result, bumped only when a change of code changes its
    numbers (a bit-identity test tells).

:func:`why_not_usable` compares a file with the settings a run would compute it with and the
code's current result version, and says in one line why the file may not stand in for the
computation (or ``None`` when it may). A file that cannot be read, or that records no settings,
raises :class:`~chainchaos.errors.KeptFileError`, whose one line names the file, what is wrong and
how to restore or remake it. What a result's settings are is said next to the code that computes
it (``studies.search.archive.search_settings``, ``studies.scan.runs.disorder_settings``).
"""

import hashlib
import json
import math
import shutil
import tempfile
from pathlib import Path

from chainchaos.errors import KeptFileError

SETTINGS_ATTR = "kept_settings"
DIGEST_ATTR = "kept_settings_digest"
VERSION_ATTR = "result_version"


def canonical(value):
    """``value`` as plain JSON data, the same for every way of writing the same settings.

    Mappings get string keys, tuples become lists, NumPy scalars Python numbers, and a finite
    float with an integral value an int (YAML reads ``1.0e+5`` as a float, ``100000`` as an int).
    Booleans stay booleans; NaN and infinities are not settings and are refused."""
    if isinstance(value, dict):
        return {str(k): canonical(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [canonical(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):  # NumPy scalar
        value = value.item()
    if isinstance(value, bool) or value is None or isinstance(value, (str, int)):
        return value
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"a setting is {value!r}: kept settings are finite numbers")
        return int(value) if value.is_integer() and abs(value) < 2**53 else value
    raise TypeError(f"a setting of type {type(value).__name__} ({value!r}) is not plain data")


def settings_json(settings: dict) -> str:
    """The canonical JSON text of ``settings``: sorted keys, no spaces."""
    return json.dumps(canonical(settings), sort_keys=True, separators=(",", ":"))


def digest(settings: dict) -> str:
    """SHA-256 (hex) of :func:`settings_json`."""
    return hashlib.sha256(settings_json(settings).encode("utf-8")).hexdigest()


def kept_attrs(settings: dict, version: int) -> dict:
    """The global attributes that key a kept file: ``kept_settings``, ``kept_settings_digest``,
    ``result_version``."""
    return {SETTINGS_ATTR: settings_json(settings), DIGEST_ATTR: digest(settings), VERSION_ATTR: int(version)}


def _remedy(path, remake: str) -> str:
    return f"restore it with 'git checkout -- {path}', or delete it and remake it with '{remake}'"


def read_key(path, remake: str) -> tuple[dict, int]:
    """The settings and result version a kept file records.

    Raises :class:`KeptFileError` (one line: the file, what is wrong, how to restore it or
    ``remake`` it) when the file cannot be read, records no settings, or its digest does not
    match its settings."""
    import netCDF4

    try:
        with netCDF4.Dataset(path) as nc:
            attrs = {name: nc.getncattr(name) for name in nc.ncattrs()}
    except (OSError, RuntimeError, ValueError) as err:
        reason = getattr(err, "strerror", None) or str(err)  # netCDF4: "NetCDF: HDF error", without the path
        raise KeptFileError(f"kept file {path} cannot be read ({reason}); {_remedy(path, remake)}") from None
    missing = [key for key in (SETTINGS_ATTR, DIGEST_ATTR, VERSION_ATTR) if key not in attrs]
    if missing:
        raise KeptFileError(f"kept file {path} records no {' / '.join(missing)} (made before kept results were "
                            f"keyed by their settings); {_remedy(path, remake)}")
    try:
        settings = json.loads(attrs[SETTINGS_ATTR])
    except ValueError as err:
        raise KeptFileError(f"kept file {path}: its {SETTINGS_ATTR} is not JSON ({err}); "
                            f"{_remedy(path, remake)}") from None
    if digest(settings) != str(attrs[DIGEST_ATTR]):
        raise KeptFileError(f"kept file {path}: its {DIGEST_ATTR} is not the digest of its {SETTINGS_ATTR}; "
                            f"{_remedy(path, remake)}")
    return settings, int(attrs[VERSION_ATTR])


def _dotted(path: tuple) -> str:
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def _shown(value) -> str:
    text = "absent" if value is _ABSENT else json.dumps(value, sort_keys=True, separators=(",", ":"))
    return text if len(text) <= 80 else text[:77] + "..."


_ABSENT = object()


def first_difference(kept, run, path: tuple = ()) -> tuple[str, object, object] | None:
    """The first setting (in sorted key order) where ``kept`` and ``run`` (canonical data)
    differ: (its dotted path, e.g. ``chain.N`` or ``statements[3].kind``, the kept value, the
    run's value), or ``None`` when they are equal. A key on one side only has the value
    ``_ABSENT`` on the other."""
    if isinstance(kept, dict) and isinstance(run, dict):
        for key in sorted(set(kept) | set(run)):
            found = first_difference(kept.get(key, _ABSENT), run.get(key, _ABSENT), (*path, key))
            if found:
                return found
        return None
    if isinstance(kept, list) and isinstance(run, list) and len(kept) == len(run):
        for i, (a, b) in enumerate(zip(kept, run)):
            found = first_difference(a, b, (*path, i))
            if found:
                return found
        return None
    if type(kept) is type(run) and kept == run:
        return None
    return _dotted(path) or "(all settings)", kept, run


def why_not_usable(path, settings: dict, version: int, remake: str, keys=None) -> str | None:
    """Why the kept file ``path`` may not stand in for a computation with ``settings`` by code of
    result version ``version``, in one line; ``None`` when it may.

    ``keys``: compare only these top-level keys of the settings (a run that takes only part of
    the result, e.g. the chain a search chose, needs only the settings of that part to match);
    the result version is always compared. ``remake``: the command that remakes the file, named
    by the :class:`KeptFileError` of a file that cannot be read or records no settings."""
    kept, kept_version = read_key(path, remake)
    if kept_version != int(version):
        return f"kept file {path}: result_version is {kept_version} in the file, {int(version)} in this code"
    run = canonical(settings)
    if keys is not None:
        kept, run = ({k: side.get(k, _ABSENT) for k in keys} for side in (kept, run))
    elif digest(run) == digest(kept):
        return None
    found = first_difference(kept, run)
    if found is None:
        return None
    key, a, b = found
    return f"kept file {path}: {key} is {_shown(a)} in the file, {_shown(b)} in this run"


def stamp(path, settings: dict, version: int) -> None:
    """Write the key (:func:`kept_attrs`) into the global attributes of the NetCDF file ``path``,
    leaving its variables byte for byte as they are: the attributes are set on a copy, which then
    replaces the file (an interrupted stamp leaves the file as it was)."""
    import netCDF4

    path = Path(path)
    with tempfile.NamedTemporaryFile(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp", delete=False) as tmp:
        pass
    tmp = Path(tmp.name)
    try:
        shutil.copy2(path, tmp)  # bytes and permissions
        with netCDF4.Dataset(tmp, "a") as nc:
            for name, value in kept_attrs(settings, version).items():
                nc.setncattr(name, value)
        tmp.replace(path)
    finally:
        tmp.unlink(missing_ok=True)
