"""Fig. 1(a) data: participation-number statistics of the linear modes over disorder realizations."""

import argparse
import contextlib

from chainchaos.io import ensemble_dataset, write_netcdf


def main(out, alphas, realizations, N, first_seed=0, convention="potential"):
    write_netcdf(ensemble_dataset(alphas, realizations, N, first_seed, convention), out)


if "snakemake" in globals():
    e = snakemake.params.ensemble
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.output.stats, e["alphas"], e["realizations"], snakemake.params.N,
             e.get("first_seed", 0), e.get("convention", "potential"))
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--alphas", type=float, nargs="+", required=True)
    parser.add_argument("--realizations", type=int, default=1000)
    parser.add_argument("--N", type=int, default=40)
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.out, a.alphas, a.realizations, a.N)
