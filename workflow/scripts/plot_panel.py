"""Draw one panel of the paper from its NetCDF inputs (PDF and PNG)."""

import argparse
import contextlib
from pathlib import Path

import xarray as xr

from chainchaos.plotting import plot_panel, save_figure


def main(panel_id, inputs: dict, pdf, dpi):
    data = {name: xr.load_dataset(path) for name, path in inputs.items()}
    save_figure(plot_panel(panel_id, data), str(Path(pdf).with_suffix("")), dpi=dpi)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.wildcards.panel, dict(snakemake.input.items()), snakemake.output.pdf, snakemake.params.dpi)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("panel", help="panel id, e.g. 4d")
    parser.add_argument("inputs", nargs="+", help="NAME=FILE: scene names, 'chain', 'ensemble'")
    parser.add_argument("--out", required=True, help="output PDF (a PNG is written beside it)")
    parser.add_argument("--dpi", type=int, default=200)
    a = parser.parse_args()
    main(a.panel, dict(item.split("=", 1) for item in a.inputs), a.out, a.dpi)
