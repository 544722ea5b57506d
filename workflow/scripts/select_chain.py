"""select_chain: see chainchaos.tasks.chain.select_chain."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
