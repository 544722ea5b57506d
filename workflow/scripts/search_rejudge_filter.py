"""search_rejudge_filter: see chainchaos.workflow.tasks.search.search_rejudge_filter."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
