"""plot_energy_scan: see chainchaos.tasks.scan.plot_energy_scan."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
