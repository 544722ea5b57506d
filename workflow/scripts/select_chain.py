"""select_chain: see chainchaos.workflow.tasks.chain.select_chain."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
