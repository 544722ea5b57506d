"""The stability figure (results/figures/stability.pdf and .png) and its tables (CSV, LaTeX)."""

import argparse
import contextlib
from pathlib import Path

import xarray as xr

from chainchaos.numerics.plots import plot_stability
from chainchaos.numerics.tables import stability_tables


def main(stability, drift, taylor, advice, pdf, csv_path, tex_path, integrator):
    load = lambda f: xr.load_dataset(f, engine="netcdf4")  # noqa: E731
    stab, dr, ta, ad = load(stability), load(drift), load(taylor), load(advice)
    plot_stability(stab, dr, ta, ad, scheme=integrator, path_stem=Path(pdf).with_suffix(""))
    stability_tables(stab, dr, ta, csv_path, tex_path)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        i, o = snakemake.input, snakemake.output
        main(i.stability, i.drift, i.taylor, i.advice, o.pdf, o.csv, o.tex, snakemake.params.integrator)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    for name in ("stability", "drift", "taylor", "advice", "pdf", "csv", "tex"):
        parser.add_argument(f"--{name}", required=True)
    parser.add_argument("--integrator", default="SRKN6b")
    a = parser.parse_args()
    main(a.stability, a.drift, a.taylor, a.advice, a.pdf, a.csv, a.tex, a.integrator)
