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
    numbers (a bit-identity test tells);
``kept_data_checksum``
    the SHA-256 of its data (:func:`data_checksum`), written once the data are (:func:`seal`, or
    ``chainchaos.records.io.write_netcdf(..., seal=True)``): a file damaged inside its data, whose
    header still reads, is caught by :func:`check_data` in the job that reads it.

:func:`why_not_usable` compares a file with the settings a run would compute it with and the
code's current result version, and says in one line why the file may not stand in for the
computation (or ``None`` when it may); it reads the header only. :func:`check_kept`, which the
workflow's check jobs run on each kept file its config chose, adds the checksum of the data and
the two ways out of a mismatch; the workflow opens no kept file while it is parsed. A file that
cannot be read, that records no settings, or (:func:`check_data`) whose data do not match their
checksum raises :class:`~chainchaos.errors.KeptFileError`, whose one line names the file, what is
wrong and how to restore or remake it. What a result's settings are
is said next to the code that computes it (``studies.search.archive.search_settings``,
``studies.scan.runs.disorder_settings``).
"""

import hashlib
import json
import math
import shutil
from pathlib import Path

import numpy as np

from chainchaos.errors import KeptFileError
from chainchaos.records.atomic import atomic_output

SETTINGS_ATTR = "kept_settings"
DIGEST_ATTR = "kept_settings_digest"
VERSION_ATTR = "result_version"
DATA_ATTR = "kept_data_checksum"


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


# what netCDF4 raises for a file it cannot open, or a variable whose bytes HDF5 cannot decode
_READ_ERRORS = (OSError, RuntimeError, ValueError)


def _unreadable(path, err: Exception, remake: str, where: str = "") -> KeptFileError:
    reason = getattr(err, "strerror", None) or str(err)  # netCDF4: "NetCDF: HDF error", without the path
    return KeptFileError(f"kept file {path} cannot be read ({reason}{where}); {_remedy(path, remake)}")


def read_header(path, remake: str) -> tuple[dict, dict]:
    """A kept file's global attributes and dimension sizes, from its header alone.

    Raises :class:`KeptFileError` (one line: the file, why, how to restore it or ``remake`` it)
    when the header cannot be read."""
    import netCDF4

    try:
        with netCDF4.Dataset(path) as nc:
            return {name: nc.getncattr(name) for name in nc.ncattrs()}, {k: len(d) for k, d in nc.dimensions.items()}
    except _READ_ERRORS as err:
        raise _unreadable(path, err, remake) from None


def read_key(path, remake: str) -> tuple[dict, int]:
    """The settings and result version a kept file records.

    Raises :class:`KeptFileError` (one line: the file, what is wrong, how to restore it or
    ``remake`` it) when the file cannot be read, records no settings, or its digest does not
    match its settings."""
    attrs, _ = read_header(path, remake)
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


def check_kept(path, settings: dict, version: int, remake: str, compute: str, keys=None) -> dict:
    """Check that the kept file ``path``, which a run's config chose to use, stands in for the
    computation with ``settings`` by code of result version ``version``: it exists, its key
    matches (:func:`why_not_usable`) and its data match their checksum (:func:`check_data`).

    What a check job of the workflow runs (``check_kept_archive``, ``check_kept_study``): the
    jobs that read the file wait for it, and a file that does not match stops them, never
    another plan.

    Parameters
    ----------
    path : str or Path
        The kept file.
    settings : dict
        The settings this run would compute it with.
    version : int
        The result version of the code that computes it.
    remake : str
        The command that remakes the file.
    compute : str
        How to compute the result instead of using the file (the config key to change).
    keys : sequence of str, optional
        Compare only these top-level keys of the settings.

    Returns
    -------
    dict
        The file's global attributes (its settings digest among them), for the check's record.

    Raises
    ------
    KeptFileError
        One line naming the file, what does not match (the first setting that differs, with its
        two values, or the result version, or absent, unreadable or damaged data) and the two ways
        out: ``remake`` it, or ``compute``.
    """
    ways_out = f"remake it with '{remake}', or {compute}"
    if not Path(path).exists():
        raise KeptFileError(f"kept file {path} is absent; {ways_out}")
    why = why_not_usable(path, settings, version, remake, keys)
    if why is not None:
        raise KeptFileError(f"{why}; {ways_out}")
    check_data(path, remake)
    return read_header(path, remake)[0]


def _hash_variable(sha, name: str, var) -> None:
    """Add the netCDF4 variable ``var`` named ``name`` to the SHA-256 ``sha`` (:func:`data_checksum`)."""
    var.set_auto_maskandscale(False)  # the stored values, not their CF decoding
    var.set_auto_chartostring(False)
    if var.dtype is str:  # variable-length strings: each one's UTF-8 bytes after its length
        texts = [text.encode("utf-8") for text in np.asarray(var[...], dtype=object).ravel()]
        dtype, payload = "str", b"".join(len(t).to_bytes(8, "little") + t for t in texts)
    else:
        values = np.ascontiguousarray(var[...], dtype=np.dtype(var.dtype).newbyteorder("<"))
        dtype, payload = values.dtype.str, values.tobytes()
    header = "\0".join([name, dtype, ",".join(map(str, var.shape)), str(len(payload))]) + "\0"
    sha.update(header.encode("utf-8"))
    sha.update(payload)


def data_checksum(path) -> str:
    """The SHA-256 (hex) of the data of the NetCDF file ``path``: what :data:`DATA_ATTR` records.

    The data are the values every variable of the root group (coordinates included) holds, as
    netCDF4 reads them with its decoding turned off (no masking, scaling or joining of characters
    into strings): the stored values, after HDF5 has undone compression and shuffling, and not a
    library's CF decoding, which may change with its version. For each variable, in sorted name
    order (by code point), the hash takes its name, its dtype (NumPy's ``dtype.str`` after
    conversion to little-endian, or ``str`` for variable-length strings), its shape (``3,40``;
    empty for a scalar) and the length of its bytes, each followed by a NUL byte, then its bytes:
    the values in C order, little-endian, or for strings each one's UTF-8 bytes preceded by their
    length as 8 bytes little-endian. Attributes are not part of it, so stamping a key or the
    checksum itself changes nothing; neither are compression and chunking.

    Parameters
    ----------
    path : str or Path
        A NetCDF-4 file.

    Returns
    -------
    str
        64 hexadecimal digits.

    Raises
    ------
    OSError, RuntimeError
        From netCDF4, for a file or variable it cannot read (``NetCDF: HDF error``).
    """
    import netCDF4

    sha = hashlib.sha256()
    with netCDF4.Dataset(path) as nc:
        for name in sorted(nc.variables):
            _hash_variable(sha, name, nc.variables[name])
    return sha.hexdigest()


def check_data(path, remake: str) -> bool:
    """Check that the data of ``path``, when it is a kept file, are those it was kept with.

    A kept file is one that records :data:`SETTINGS_ATTR` (so is a study group this run computed:
    it is written sealed, to be kept as it is): its data must match the checksum it records
    (:data:`DATA_ATTR`, :func:`data_checksum`). A file that records no settings is not a kept file
    (a result computed by this run): only its header is read. A file whose header cannot be read
    raises, whatever it is. One open of the file, one read of its data: call it where a job reads
    an input that may be a kept file, before reading it.

    Parameters
    ----------
    path : str or Path
        The file, kept or not.
    remake : str
        The command that remakes the kept file, named by the error.

    Returns
    -------
    bool
        True for a kept file whose data match their checksum, False for a file that is not kept.

    Raises
    ------
    KeptFileError
        One line naming the file, what is wrong and how to restore it (``git checkout``) or
        ``remake`` it: the file cannot be read (its header or one of its variables: ``NetCDF: HDF
        error``), it is a kept file that records no checksum, or its data do not match it.
    """
    import netCDF4

    sha, name = hashlib.sha256(), ""
    try:
        with netCDF4.Dataset(path) as nc:
            attrs = nc.ncattrs()
            if SETTINGS_ATTR not in attrs:
                return False
            recorded = str(nc.getncattr(DATA_ATTR)) if DATA_ATTR in attrs else None
            for name in sorted(nc.variables):  # data_checksum, naming the variable HDF5 cannot decode
                _hash_variable(sha, name, nc.variables[name])
    except _READ_ERRORS as err:
        raise _unreadable(path, err, remake, f" in its variable {name}" if name else "") from None
    if recorded is None:
        raise KeptFileError(f"kept file {path} records no {DATA_ATTR} (kept before kept files recorded the "
                            f"checksum of their data); {_remedy(path, remake)}")
    if sha.hexdigest() != recorded:
        raise KeptFileError(f"kept file {path}: its data do not match the checksum it records ({DATA_ATTR}); "
                            f"{_remedy(path, remake)}")
    return True


def record_checksum(path) -> None:
    """Write :func:`data_checksum` into the global attribute :data:`DATA_ATTR` of ``path``, in
    place: for a file no one reads yet (the temporary file of an atomic write); :func:`seal` one
    that exists.

    Parameters
    ----------
    path : str or Path
        A NetCDF-4 file, opened for appending.
    """
    import netCDF4

    checksum = data_checksum(path)
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr(DATA_ATTR, checksum)


def _amend(path, edit) -> None:
    """Apply ``edit(copy)`` to a copy of ``path``, which then replaces it (``records.atomic``): an
    interrupted edit leaves the file as it was."""
    with atomic_output(path) as tmp:
        shutil.copy2(path, tmp)
        edit(tmp)


def seal(path) -> None:
    """Record the checksum of the data of the NetCDF file ``path`` (:func:`record_checksum`),
    leaving its variables byte for byte as they are, atomically (on a copy that replaces it).

    Parameters
    ----------
    path : str or Path
        A NetCDF-4 file (sealing it again writes the same checksum, its data being the same).
    """
    _amend(path, record_checksum)


def stamp(path, settings: dict, version: int) -> None:
    """Write the key (:func:`kept_attrs`) and the checksum of the data (:data:`DATA_ATTR`) into
    the global attributes of the NetCDF file ``path``, leaving its variables byte for byte as they
    are, atomically (on a copy that replaces it).

    Parameters
    ----------
    path : str or Path
        A NetCDF-4 file.
    settings : dict
        The settings that determine its numbers.
    version : int
        The result version of the code that computed it.
    """
    import netCDF4

    def edit(tmp):
        with netCDF4.Dataset(tmp, "a") as nc:
            for name, value in kept_attrs(settings, version).items():
                nc.setncattr(name, value)
        record_checksum(tmp)

    _amend(path, edit)
