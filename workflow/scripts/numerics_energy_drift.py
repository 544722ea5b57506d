"""numerics_energy_drift: see chainchaos.workflow.tasks.numerics.numerics_energy_drift."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
