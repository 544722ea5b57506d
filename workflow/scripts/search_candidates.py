"""Rule search_candidates: runs chainchaos.workflow.tasks.search.search_candidates."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_candidates

run(snakemake, search_candidates)  # noqa: F821 (snakemake: defined by Snakemake)
