"""Rule evaluate_claims: runs chainchaos.workflow.tasks.manuscript.evaluate_claims."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.manuscript import evaluate_claims

run(snakemake, evaluate_claims)  # noqa: F821 (snakemake: defined by Snakemake)
