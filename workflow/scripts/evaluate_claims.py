"""evaluate_claims: see chainchaos.tasks.manuscript.evaluate_claims."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
