"""plot_disorder_statistics: see chainchaos.workflow.tasks.scan.plot_disorder_statistics."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
