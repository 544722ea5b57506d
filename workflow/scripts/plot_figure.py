"""plot_figure: see chainchaos.tasks.figures.plot_figure."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
