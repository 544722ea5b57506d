"""Rule search_full: runs chainchaos.workflow.tasks.search.search_full."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_full

run(snakemake, search_full)  # noqa: F821 (snakemake: defined by Snakemake)
