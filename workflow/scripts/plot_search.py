"""plot_search: see chainchaos.workflow.tasks.search.plot_search."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
