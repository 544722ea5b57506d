"""plot_figure: see chainchaos.workflow.tasks.figures.plot_figure."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
