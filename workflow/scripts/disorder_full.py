"""disorder_full: see chainchaos.workflow.tasks.scan.disorder_full."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
