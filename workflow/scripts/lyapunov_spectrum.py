"""lyapunov_spectrum: see chainchaos.workflow.tasks.indicators.lyapunov_spectrum."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
