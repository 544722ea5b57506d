"""Rule plot_disorder_statistics: runs chainchaos.workflow.tasks.scan.plot_disorder_statistics."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.scan import plot_disorder_statistics

run(snakemake, plot_disorder_statistics)  # noqa: F821 (snakemake: defined by Snakemake)
