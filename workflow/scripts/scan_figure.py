"""Draw the energy-scan or the disorder-statistics figure (PDF and PNG) from its merged dataset."""

import argparse
import contextlib
from pathlib import Path

import xarray as xr

from chainchaos import scan_plots


def main(kind, data, pdf, dpi):
    ds = xr.load_dataset(data)
    fig = scan_plots.energy_scan_figure(ds) if kind == "energy_scan" else scan_plots.disorder_figure(ds)
    scan_plots.save(fig, Path(pdf).with_suffix(""), dpi=dpi)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.params.kind, snakemake.input.data, snakemake.output.pdf, snakemake.params.dpi)
else:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("kind", choices=["energy_scan", "disorder"])
    ap.add_argument("data")
    ap.add_argument("--out", required=True, help="output PDF (a PNG is written beside it)")
    ap.add_argument("--dpi", type=int, default=200)
    a = ap.parse_args()
    main(a.kind, a.data, a.out, a.dpi)
