"""numerics_plot_stability: see chainchaos.tasks.numerics.numerics_plot_stability."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
