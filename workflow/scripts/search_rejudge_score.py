"""Rule search_rejudge_score: runs chainchaos.workflow.tasks.search.search_rejudge_score."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_rejudge_score

run(snakemake, search_rejudge_score)  # noqa: F821 (snakemake: defined by Snakemake)
