"""Rule search_filter: runs chainchaos.workflow.tasks.search.search_filter."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_filter

run(snakemake, search_filter)  # noqa: F821 (snakemake: defined by Snakemake)
