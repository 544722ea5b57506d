"""Rule plot_study: runs chainchaos.workflow.tasks.study.plot_study."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.study import plot_study

run(snakemake, plot_study)  # noqa: F821 (snakemake: defined by Snakemake)
