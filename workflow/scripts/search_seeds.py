"""Rule search_seeds: runs chainchaos.workflow.tasks.search.search_seeds."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_seeds

run(snakemake, search_seeds)  # noqa: F821 (snakemake: defined by Snakemake)
