"""Rule compute_ensemble: runs chainchaos.workflow.tasks.chain.compute_ensemble."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.chain import compute_ensemble

run(snakemake, compute_ensemble)  # noqa: F821 (snakemake: defined by Snakemake)
