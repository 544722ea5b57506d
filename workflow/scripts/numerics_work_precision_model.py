"""numerics_work_precision_model: see chainchaos.workflow.tasks.numerics.numerics_work_precision_model."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
