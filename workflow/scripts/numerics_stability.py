"""Largest stable steps of every scheme over disorder strengths and energies, and on the
near-sonic-vacuum chain (results/numerics/stability.nc)."""

import argparse
import contextlib
import json
import sys

from chainchaos.io import read_chain, write_netcdf
from chainchaos.numerics.runs import warm_up
from chainchaos.numerics.stability import stability_scan


def main(chain_file, out, s):
    chain = read_chain(chain_file)
    warm_up(chain)
    ds = stability_scan(chain, s["alphas"], s["energies"], s["schemes"], s.get("models", ["hertz", "fput"]),
                        t_final=s["t_final"], bound=s["bound"], rel_tol=s.get("rel_tol", 1e-2),
                        sonic_factor=s.get("sonic_factor", 1e-6), sonic_energies=s.get("sonic_energies"),
                        excited_site=s.get("excited_site", 21),
                        progress=lambda m: print(m, file=sys.stderr, flush=True))
    write_netcdf(ds, out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.chain, snakemake.output.data, snakemake.params.settings)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--chain", required=True)
    parser.add_argument("--settings", required=True, help="JSON of the config's numerics.stability block")
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.chain, a.out, json.loads(a.settings))
