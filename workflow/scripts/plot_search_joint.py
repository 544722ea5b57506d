"""plot_search_joint: see chainchaos.workflow.tasks.search.plot_search_joint."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
