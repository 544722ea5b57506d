"""Rule numerics_energy_drift: runs chainchaos.workflow.tasks.numerics.numerics_energy_drift."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_energy_drift

run(snakemake, numerics_energy_drift)  # noqa: F821 (snakemake: defined by Snakemake)
