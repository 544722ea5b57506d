"""Rule search_rejudge_score: runs chainchaos.workflow.tasks.keep.search_rejudge_score."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import search_rejudge_score

run(snakemake, search_rejudge_score)  # noqa: F821 (snakemake: defined by Snakemake)
