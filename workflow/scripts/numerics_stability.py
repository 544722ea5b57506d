"""numerics_stability: see chainchaos.workflow.tasks.numerics.numerics_stability."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
