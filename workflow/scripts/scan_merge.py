"""Merge the group files of the energy scan or the disorder statistics into one dataset."""

import argparse
import contextlib
import json
import sys

import xarray as xr

from chainchaos import scan
from chainchaos.io import read_chain, write_netcdf


def main(kind, group_files, scan_cfg, out, chain_file=None):
    groups = [xr.load_dataset(f) for f in group_files]
    if kind == "energy_scan":
        ds = scan.merge_energy_scan(groups, scan_cfg, read_chain(chain_file) if chain_file else None)
    else:
        ds = scan.merge_disorder(groups, scan_cfg)
    seconds = [g.attrs.get("seconds_per_trajectory") for g in groups if "seconds_per_trajectory" in g.attrs]
    if seconds:
        ds.attrs["mean_seconds_per_trajectory"] = float(sum(seconds) / len(seconds))
    print(f"{kind}: merged {len(groups)} groups, {int((ds['valid'] == 1).sum())} valid runs", file=sys.stderr)
    write_netcdf(ds, out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.params.kind, list(snakemake.input.groups), snakemake.params.scan, snakemake.output.merged,
             snakemake.input.get("chain"))
else:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("kind", choices=["energy_scan", "disorder"])
    ap.add_argument("groups", nargs="+")
    ap.add_argument("--scan", required=True, help="JSON of the config's scan block")
    ap.add_argument("--chain")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    main(a.kind, a.groups, json.loads(a.scan), a.out, a.chain)
