"""The energies where the chain delocalizes and where it is chaotic (CSV and LaTeX table)."""

import argparse
import contextlib

import xarray as xr

from chainchaos import scan
from chainchaos.io import write_text


def main(data, csv, tex):
    ds = xr.load_dataset(data)
    rows = scan.thresholds_table(ds)
    write_text(scan.thresholds_csv(rows, ds), csv)
    write_text(scan.thresholds_tex(rows, ds), tex)


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
