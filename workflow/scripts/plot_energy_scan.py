"""Rule plot_energy_scan: runs chainchaos.workflow.tasks.scan.plot_energy_scan."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.scan import plot_energy_scan

run(snakemake, plot_energy_scan)  # noqa: F821 (snakemake: defined by Snakemake)
