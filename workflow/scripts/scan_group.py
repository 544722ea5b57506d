"""Run one job's share of the energy scan or of the disorder statistics (a group of trajectories)."""

import argparse
import contextlib
import json
import sys
import time

from chainchaos import scan
from chainchaos.io import read_chain, write_netcdf


def main(kind, group, scan_cfg, out, chain_file=None, N=40):
    start = time.perf_counter()

    def progress(done, total):
        print(f"[{kind} group {group}] {done}/{total} trajectories, {time.perf_counter() - start:.1f} s",
              file=sys.stderr, flush=True)

    if kind == "energy_scan":
        ds = scan.energy_scan_group(read_chain(chain_file), scan_cfg, group, progress)
    else:
        ds = scan.disorder_group(scan_cfg, group, N, progress)
    n = ds.sizes["trajectory"]
    elapsed = time.perf_counter() - start
    ds.attrs.update(wall_time_s=elapsed, seconds_per_trajectory=elapsed / max(n, 1))
    print(f"[{kind} group {group}] done: {n} trajectories in {elapsed:.1f} s "
          f"({elapsed / max(n, 1):.3f} s each); invalid: {int((ds['valid'] == 0).sum())}", file=sys.stderr)
    write_netcdf(ds, out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.params.kind, int(snakemake.wildcards.group), snakemake.params.scan,
             snakemake.output.group, snakemake.input.get("chain"), snakemake.params.N)
else:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("kind", choices=["energy_scan", "disorder"])
    ap.add_argument("group", type=int)
    ap.add_argument("--scan", required=True, help="JSON of the config's scan block")
    ap.add_argument("--chain", help="chain file (energy_scan)")
    ap.add_argument("--N", type=int, default=40)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    main(a.kind, a.group, json.loads(a.scan), a.out, a.chain, a.N)
