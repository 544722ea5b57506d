"""Rule numerics_step_advice: runs chainchaos.workflow.tasks.numerics.numerics_step_advice."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_step_advice

run(snakemake, numerics_step_advice)  # noqa: F821 (snakemake: defined by Snakemake)
