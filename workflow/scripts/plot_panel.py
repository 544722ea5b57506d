"""plot_panel: see chainchaos.tasks.figures.plot_panel."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
