"""Rule compile_kernels: runs chainchaos.workflow.tasks.simulate.compile_kernels."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.simulate import compile_kernels

run(snakemake, compile_kernels)  # noqa: F821 (snakemake: defined by Snakemake)
