"""ensemble_verdicts: see chainchaos.workflow.tasks.search.ensemble_verdicts."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
