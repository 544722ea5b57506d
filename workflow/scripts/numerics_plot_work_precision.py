"""The work-precision figure (results/figures/work_precision.pdf and .png)."""

import argparse
import contextlib
from pathlib import Path

import xarray as xr

from chainchaos.numerics.plots import plot_work_precision


def main(data, pdf):
    plot_work_precision(xr.load_dataset(data, engine="netcdf4"), Path(pdf).with_suffix(""))


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.data, snakemake.output.pdf)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--data", required=True)
    parser.add_argument("--pdf", required=True, help="output PDF; the PNG goes beside it")
    a = parser.parse_args()
    main(a.data, a.pdf)
