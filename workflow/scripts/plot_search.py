"""Rule plot_search: runs chainchaos.workflow.tasks.search.plot_search."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import plot_search

run(snakemake, plot_search)  # noqa: F821 (snakemake: defined by Snakemake)
