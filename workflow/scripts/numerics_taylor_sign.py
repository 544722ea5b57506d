"""Rule numerics_taylor_sign: runs chainchaos.workflow.tasks.numerics.numerics_taylor_sign."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_taylor_sign

run(snakemake, numerics_taylor_sign)  # noqa: F821 (snakemake: defined by Snakemake)
