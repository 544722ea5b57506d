"""Rule plot_panel: runs chainchaos.workflow.tasks.figures.plot_panel."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.figures import plot_panel

run(snakemake, plot_panel)  # noqa: F821 (snakemake: defined by Snakemake)
