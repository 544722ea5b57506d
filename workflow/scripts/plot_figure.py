"""Rule plot_figure: runs chainchaos.workflow.tasks.figures.plot_figure."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.figures import plot_figure

run(snakemake, plot_figure)  # noqa: F821 (snakemake: defined by Snakemake)
