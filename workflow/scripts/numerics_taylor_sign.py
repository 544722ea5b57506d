"""FPUT with the Taylor sign of K4: which energies stay bounded, which escape and are stopped by
the guard, which cannot be reached (results/numerics/taylor_sign.nc)."""

import argparse
import contextlib
import json
import sys

from chainchaos.io import read_chain, write_netcdf
from chainchaos.numerics.stability import taylor_dataset, taylor_sign_probe


def main(chain_file, out, s, integrator):
    chain = read_chain(chain_file)
    rows = taylor_sign_probe(chain, s["energies"], float(s["t_final"]), float(s["dt"]), integrator,
                             site=s.get("excited_site", 21))
    for r in rows:
        print(f"H = {r['energy']:g}: {r['outcome']} {r['message']}", file=sys.stderr, flush=True)
    write_netcdf(taylor_dataset(rows, chain, float(s["t_final"]), float(s["dt"]), integrator), out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.chain, snakemake.output.data, snakemake.params.settings, snakemake.params.integrator)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--chain", required=True)
    parser.add_argument("--settings", required=True, help="JSON of the config's numerics.taylor block")
    parser.add_argument("--integrator", default="SRKN6b")
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.chain, a.out, json.loads(a.settings), a.integrator)
