"""numerics_taylor_sign: see chainchaos.workflow.tasks.numerics.numerics_taylor_sign."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
