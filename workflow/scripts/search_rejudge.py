"""Rule search_rejudge: runs chainchaos.workflow.tasks.keep.search_rejudge."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import search_rejudge

run(snakemake, search_rejudge)  # noqa: F821 (snakemake: defined by Snakemake)
