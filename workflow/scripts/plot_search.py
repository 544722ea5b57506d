"""plot_search: see chainchaos.tasks.search.plot_search."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
