"""scan_disorder_group: see chainchaos.workflow.tasks.scan.scan_disorder_group."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
