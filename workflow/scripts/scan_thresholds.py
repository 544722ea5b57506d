"""scan_thresholds: see chainchaos.tasks.scan.scan_thresholds."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
