"""compile_kernels: see chainchaos.tasks.simulate.compile_kernels."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
