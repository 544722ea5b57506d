"""Rule search_rejudge_filter: runs chainchaos.workflow.tasks.keep.search_rejudge_filter."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import search_rejudge_filter

run(snakemake, search_rejudge_filter)  # noqa: F821 (snakemake: defined by Snakemake)
