"""Rule lyapunov_spectrum: runs chainchaos.workflow.tasks.indicators.lyapunov_spectrum."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.indicators import lyapunov_spectrum

run(snakemake, lyapunov_spectrum)  # noqa: F821 (snakemake: defined by Snakemake)
