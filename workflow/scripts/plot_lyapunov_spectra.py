"""plot_lyapunov_spectra: see chainchaos.workflow.tasks.indicators.plot_lyapunov_spectra."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
