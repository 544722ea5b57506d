"""Rule numerics_plot_stability: runs chainchaos.workflow.tasks.numerics.numerics_plot_stability."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_plot_stability

run(snakemake, numerics_plot_stability)  # noqa: F821 (snakemake: defined by Snakemake)
