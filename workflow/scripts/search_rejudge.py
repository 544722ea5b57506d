"""Rule search_rejudge: runs chainchaos.workflow.tasks.search.search_rejudge."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_rejudge

run(snakemake, search_rejudge)  # noqa: F821 (snakemake: defined by Snakemake)
