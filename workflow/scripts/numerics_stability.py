"""Rule numerics_stability: runs chainchaos.workflow.tasks.numerics.numerics_stability."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_stability

run(snakemake, numerics_stability)  # noqa: F821 (snakemake: defined by Snakemake)
