"""compute_ensemble: see chainchaos.tasks.chain.compute_ensemble."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
