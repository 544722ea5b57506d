"""search_seeds: see chainchaos.workflow.tasks.search.search_seeds."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
