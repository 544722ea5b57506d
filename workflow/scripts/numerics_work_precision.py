"""Work-precision measurements of one case (model, energy) on the chosen chain (issue 5)."""

import argparse
import contextlib
import json
import sys

from chainchaos.io import read_chain, write_netcdf
from chainchaos.numerics.work_precision import work_precision


def main(chain_file, out, model, energy, settings):
    chain = read_chain(chain_file)
    s = dict(settings)
    ds = work_precision(chain, [(model, float(energy))], schemes=s["schemes"], dts=s["dts"],
                        tolerances=s["tolerances"], t_final=s["t_final"], t_probe=s["t_probe"],
                        reference=s["reference"], floor_factor=s.get("floor_factor", 10.0),
                        check_interval=s.get("check_interval", 1.0), repeats=s.get("repeats", 3),
                        repeat_below=s.get("repeat_below", 0.5), excited_site=s.get("excited_site", 21),
                        progress=lambda m: print(m, file=sys.stderr, flush=True))
    write_netcdf(ds, out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.chain, snakemake.output.data, snakemake.params.model, snakemake.params.energy,
             snakemake.params.settings)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--chain", required=True)
    parser.add_argument("--model", required=True, choices=["hertz", "fput"])
    parser.add_argument("--energy", required=True, type=float)
    parser.add_argument("--settings", required=True, help="JSON of the config's numerics.work_precision block")
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.chain, a.out, a.model, a.energy, json.loads(a.settings))
