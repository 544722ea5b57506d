"""Rule disorder_full: runs chainchaos.workflow.tasks.keep.disorder_full."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import disorder_full

run(snakemake, disorder_full)  # noqa: F821 (snakemake: defined by Snakemake)
