"""scan_thresholds: see chainchaos.workflow.tasks.scan.scan_thresholds."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
