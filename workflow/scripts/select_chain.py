"""Rule select_chain: runs chainchaos.workflow.tasks.chain.select_chain."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.chain import select_chain

run(snakemake, select_chain)  # noqa: F821 (snakemake: defined by Snakemake)
