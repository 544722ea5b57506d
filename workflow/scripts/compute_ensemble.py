"""compute_ensemble: see chainchaos.workflow.tasks.chain.compute_ensemble."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
