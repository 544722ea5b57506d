"""The chosen alpha = 5 realization (DESIGN section 4), written as the chain file."""

import argparse
import contextlib
import sys

from chainchaos.io import chain_dataset, write_netcdf
from chainchaos.selection import SelectionCriteria, select_realization


def main(out, alpha, N, wall_radius=1.0, **selection):
    chain, record = select_realization(SelectionCriteria(alpha=alpha, N=N, **selection))
    if wall_radius != chain.wall_radius:
        from chainchaos.chain import random_chain

        chain = random_chain(record["selection_seed"], alpha, N, wall_radius)
    print(f"chose seed {record['selection_seed']} of {record['selection_candidates']} candidates, "
          f"score {record['selection_score']:.4g}", file=sys.stderr)
    write_netcdf(chain_dataset(chain, record), out)


if "snakemake" in globals():
    c = snakemake.params.chain
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.output.chain, c["alpha"], c["N"], c.get("wall_radius", 1.0), **c.get("selection", {}))
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--alpha", type=float, default=5.0)
    parser.add_argument("--N", type=int, default=40)
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.out, a.alpha, a.N)
