"""compile_kernels: see chainchaos.workflow.tasks.simulate.compile_kernels."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
