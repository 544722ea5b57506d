"""Rule search_full: runs chainchaos.workflow.tasks.keep.search_full."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import search_full

run(snakemake, search_full)  # noqa: F821 (snakemake: defined by Snakemake)
