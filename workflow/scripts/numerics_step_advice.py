"""numerics_step_advice: see chainchaos.workflow.tasks.numerics.numerics_step_advice."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
