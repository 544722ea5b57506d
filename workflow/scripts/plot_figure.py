"""Draw a composite figure of the paper, laid out like the original (PDF and PNG)."""

import argparse
import contextlib
from pathlib import Path

import xarray as xr

from chainchaos.plotting import plot_figure, save_figure


def main(number, inputs: dict, pdf, dpi):
    data = {name: xr.load_dataset(path) for name, path in inputs.items()}
    save_figure(plot_figure(number, data), str(Path(pdf).with_suffix("")), dpi=dpi)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(int(snakemake.wildcards.number), dict(snakemake.input.items()), snakemake.output.pdf,
             snakemake.params.dpi)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("number", type=int, help="figure number 1..9")
    parser.add_argument("inputs", nargs="+", help="NAME=FILE: scene names, 'chain', 'ensemble'")
    parser.add_argument("--out", required=True, help="output PDF (a PNG is written beside it)")
    parser.add_argument("--dpi", type=int, default=200)
    a = parser.parse_args()
    main(a.number, dict(item.split("=", 1) for item in a.inputs), a.out, a.dpi)
