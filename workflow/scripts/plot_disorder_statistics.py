"""plot_disorder_statistics: see chainchaos.tasks.scan.plot_disorder_statistics."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
