"""compile_scan_kernels: see chainchaos.tasks.scan.compile_scan_kernels."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
