"""search_rejudge: see chainchaos.workflow.tasks.search.search_rejudge."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
