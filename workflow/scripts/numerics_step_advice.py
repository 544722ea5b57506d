"""numerics_step_advice: see chainchaos.tasks.numerics.numerics_step_advice."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
