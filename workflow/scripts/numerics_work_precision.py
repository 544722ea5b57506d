"""numerics_work_precision: see chainchaos.tasks.numerics.numerics_work_precision."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
