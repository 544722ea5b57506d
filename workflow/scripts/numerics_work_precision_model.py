"""Rule numerics_work_precision_model: runs chainchaos.workflow.tasks.numerics.numerics_work_precision_model."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_work_precision_model

run(snakemake, numerics_work_precision_model)  # noqa: F821 (snakemake: defined by Snakemake)
