"""numerics_work_precision_case: see chainchaos.workflow.tasks.numerics.numerics_work_precision_case."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
