"""Rule plot_lyapunov_spectra: runs chainchaos.workflow.tasks.indicators.plot_lyapunov_spectra."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.indicators import plot_lyapunov_spectra

run(snakemake, plot_lyapunov_spectra)  # noqa: F821 (snakemake: defined by Snakemake)
