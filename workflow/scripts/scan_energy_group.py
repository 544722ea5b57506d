"""scan_energy_group: see chainchaos.tasks.scan.scan_energy_group."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
