"""evaluate_claims: see chainchaos.workflow.tasks.manuscript.evaluate_claims."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
