"""The energies where the chain delocalizes and where it is chaotic (CSV and LaTeX table)."""

import argparse
import contextlib
import os
import tempfile
from pathlib import Path

import xarray as xr

from chainchaos import scan


def write_text(path, text):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def main(data, csv, tex):
    ds = xr.load_dataset(data)
    rows = scan.thresholds_table(ds)
    write_text(csv, scan.thresholds_csv(rows, ds))
    write_text(tex, scan.thresholds_tex(rows, ds))


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.data, snakemake.output.csv, snakemake.output.tex)
else:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("data")
    ap.add_argument("--csv", required=True)
    ap.add_argument("--tex", required=True)
    a = ap.parse_args()
    main(a.data, a.csv, a.tex)
