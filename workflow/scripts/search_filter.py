"""search_filter: see chainchaos.tasks.search.search_filter."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
