"""Rule search_rejudge_filter: runs chainchaos.workflow.tasks.search.search_rejudge_filter."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_rejudge_filter

run(snakemake, search_rejudge_filter)  # noqa: F821 (snakemake: defined by Snakemake)
