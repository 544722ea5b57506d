"""Rule search_score: runs chainchaos.workflow.tasks.search.search_score."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_score

run(snakemake, search_score)  # noqa: F821 (snakemake: defined by Snakemake)
