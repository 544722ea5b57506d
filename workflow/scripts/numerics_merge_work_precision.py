"""Merge the per-case work-precision files into results/numerics/work_precision.nc and write the
order tables (CSV, LaTeX) and the CSV of every run."""

import argparse
import contextlib
import json

import xarray as xr

from chainchaos.io import write_netcdf
from chainchaos.numerics.tables import work_precision_tables
from chainchaos.provenance import provenance_attrs


def main(case_files, out, orders_csv, orders_tex, runs_csv):
    parts = [xr.load_dataset(f, engine="netcdf4") for f in case_files]
    ds = xr.concat(parts, dim="case", data_vars="minimal", coords="minimal", compat="override",
                   combine_attrs="override")
    parameters = json.loads(parts[0].attrs["parameters"])
    parameters["cases"] = [c for p in parts for c in json.loads(p.attrs["parameters"])["cases"]]
    ds.attrs.update(provenance_attrs(parameters))
    write_netcdf(ds, out)
    work_precision_tables(ds, orders_csv, orders_tex, runs_csv)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        o = snakemake.output
        main(list(snakemake.input.cases), o.data, o.orders_csv, o.orders_tex, o.runs_csv)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("cases", nargs="+")
    parser.add_argument("--out", required=True)
    parser.add_argument("--orders-csv", required=True)
    parser.add_argument("--orders-tex", required=True)
    parser.add_argument("--runs-csv", required=True)
    a = parser.parse_args()
    main(a.cases, a.out, a.orders_csv, a.orders_tex, a.runs_csv)
