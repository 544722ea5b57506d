"""Energy error per scene at the production step and at larger ones (results/numerics/step_advice.nc,
results/tables/step_advice.csv and .tex)."""

import argparse
import contextlib
import json
import sys

from chainchaos.io import read_chain, write_netcdf
from chainchaos.numerics.advice import step_advice
from chainchaos.numerics.tables import advice_tables


def main(chain_file, out, csv_path, tex_path, s, scenes, integrator, k4_sign=1):
    chain = read_chain(chain_file)
    ds = step_advice(chain, scenes, integrator, s["dts"], float(s["t_final"]), float(s["paper_dt"]),
                     excited_site=s.get("excited_site", 21), k4_sign=float(k4_sign),
                     progress=lambda m: print(m, file=sys.stderr, flush=True))
    write_netcdf(ds, out)
    advice_tables(ds, csv_path, tex_path)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        o, p = snakemake.output, snakemake.params
        main(snakemake.input.chain, o.data, o.csv, o.tex, p.settings, p.scenes, p.integrator, p.k4_sign)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--chain", required=True)
    parser.add_argument("--settings", required=True, help="JSON of the config's numerics.advice block")
    parser.add_argument("--scenes", required=True, help='JSON list of [model, energy], e.g. [["hertz", 1.8]]')
    parser.add_argument("--integrator", default="SRKN6b")
    parser.add_argument("--out", required=True)
    parser.add_argument("--csv", required=True)
    parser.add_argument("--tex", required=True)
    a = parser.parse_args()
    main(a.chain, a.out, a.csv, a.tex, json.loads(a.settings), json.loads(a.scenes), a.integrator)
