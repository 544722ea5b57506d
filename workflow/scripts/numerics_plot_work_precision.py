"""Rule numerics_plot_work_precision: runs chainchaos.workflow.tasks.numerics.numerics_plot_work_precision."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.numerics import numerics_plot_work_precision

run(snakemake, numerics_plot_work_precision)  # noqa: F821 (snakemake: defined by Snakemake)
