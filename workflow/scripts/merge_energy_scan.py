"""merge_energy_scan: see chainchaos.workflow.tasks.scan.merge_energy_scan."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
