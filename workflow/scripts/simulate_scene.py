"""Integrate one scene of the paper and write its NetCDF file (progress in the log)."""

import argparse
import contextlib
import json

from chainchaos.io import read_chain, write_netcdf
from chainchaos.simulate import ProgressReporter, SceneParameters, simulate


def main(chain_file, out, params):
    scene = SceneParameters(**{**params, "observables": tuple(params["observables"])})
    chain = read_chain(chain_file)
    ds = simulate(chain, scene, progress=ProgressReporter(scene.name, scene.t_final, every=10.0))
    write_netcdf(ds, out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.chain, snakemake.output.scene, dict(snakemake.params.scene))
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--chain", required=True)
    parser.add_argument("--params", required=True, help="JSON of SceneParameters keyword arguments")
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.chain, a.out, json.loads(a.params))
