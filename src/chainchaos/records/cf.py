"""The NetCDF conventions of every product, CF-1.11 and ACDD-1.3, applied where files are written
(chainchaos.records.io.write_netcdf), so that each file passes ``compliance-checker --test=cf:1.11``.

Only the form of a file changes here, never a value of its data:

- global attributes ``Conventions``, ``history`` (when and by which Snakemake rule or command the
  file was written) and the ACDD ``title`` (set by each product), ``summary``, ``source``,
  ``references``, ``date_created``;
- coordinate variables without ``_FillValue``: CF forbids missing values in them;
- int64 variables stored as int32 when every value fits (CF before 1.9 has no 64-bit integers),
  else left int64 (allowed since CF-1.9);
- string-valued coordinate variables (``model``, ``scheme``, ``statement``, ...) stored as
  character arrays: a CF coordinate variable is numeric, and a one-dimensional string variable may
  not share its dimension's name (CF-1.12), while ``name(name, name_strlen)`` is a label variable.
  xarray reads the character array back as the same string index;
- no ``standard_name = "time"`` on a variable whose units are not "<unit> since <epoch>": the
  model's time is dimensionless (unit 1/omega_max), which that standard name cannot express.
"""

import os
import shlex
import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

CONVENTIONS = "CF-1.11, ACDD-1.3"

REFERENCES = ("A. Ngapasare, G. Theocharis, O. Richoux, Ch. Skokos, V. Achilleos, \"Chaos and Anderson "
              "localisation in disordered classical chains: Hertzian vs FPUT models\" (the article this "
              "pipeline reproduces)")

SUMMARY = ("Computed by chainchaos, a reproduction of the numerical study of chaos and Anderson "
           "localisation in disordered Hertzian and FPUT chains of the article in 'references'. Model "
           "quantities are dimensionless: mass in units of the reference bead mass, length of the "
           "reference static overlap, time of 1/omega_max of the homogeneous linear chain. Settings in "
           "'parameters' (JSON); code version, git commit and machine in the other global attributes.")


def creation_time() -> str:
    """Now as ISO 8601 UTC to the second, or SOURCE_DATE_EPOCH (seconds since 1970) when set, the
    reproducible-builds convention for writing the same bytes twice."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(int(epoch) if epoch else None))


def writer() -> str:
    """What is writing the file: the Snakemake rule (and wildcards) whose script runs, found as the
    ``snakemake`` object Snakemake puts in the script's globals, else the command line."""
    smk = getattr(sys.modules.get("__main__"), "snakemake", None)
    if smk is not None:
        wildcards = ", ".join(f"{k}={v}" for k, v in smk.wildcards.items())
        return f"snakemake rule {smk.rule}" + (f" ({wildcards})" if wildcards else "")
    return shlex.join([Path(sys.argv[0]).name, *sys.argv[1:]])


def global_attrs(attrs: dict) -> dict:
    """``attrs`` completed with the CF and ACDD global attributes (``summary`` kept if set)."""
    from chainchaos import __version__

    when = creation_time()
    return {**attrs, "Conventions": CONVENTIONS, "history": f"{when} {writer()} (chainchaos {__version__})",
            "date_created": when, "source": f"chainchaos {__version__}", "references": REFERENCES,
            "summary": attrs.get("summary", SUMMARY)}


def _is_coordinate_variable(ds: xr.Dataset, name) -> bool:
    return ds[name].dims == (name,)


def _int_storage(values: np.ndarray) -> dict:
    if values.dtype != np.int64:
        return {}
    i32 = np.iinfo(np.int32)
    fits = values.size == 0 or (values.min() >= i32.min and values.max() <= i32.max)
    return {"dtype": "int32"} if fits else {}


def encoded(ds: xr.Dataset) -> tuple[xr.Dataset, dict]:
    """A shallow copy of ``ds`` in the conventions above, and the ``encoding`` of ``to_netcdf``
    for every variable (zlib for data arrays; the loaded encoding of a read file is not reused)."""
    out = ds.copy(deep=False)
    out.attrs = global_attrs(ds.attrs)
    encoding = {}
    for name, var in out.variables.items():
        enc = {"zlib": True, "complevel": 4} if name in out.data_vars and var.ndim > 0 else {}
        enc.update(_int_storage(var.values))
        if _is_coordinate_variable(out, name):
            enc["_FillValue"] = None
            if var.dtype.kind in "OUS":
                enc.update(dtype="S1", char_dim_name=f"{name}_strlen")
        if var.attrs.get("standard_name") == "time" and " since " not in str(var.attrs.get("units", "")):
            var.attrs = {k: v for k, v in var.attrs.items() if k != "standard_name"}
        encoding[name] = enc
    return out, encoding
