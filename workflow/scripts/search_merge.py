"""Rule search_merge: runs chainchaos.workflow.tasks.search.search_merge."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import search_merge

run(snakemake, search_merge)  # noqa: F821 (snakemake: defined by Snakemake)
