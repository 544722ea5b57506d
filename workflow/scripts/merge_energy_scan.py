"""Rule merge_energy_scan: runs chainchaos.workflow.tasks.scan.merge_energy_scan."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.scan import merge_energy_scan

run(snakemake, merge_energy_scan)  # noqa: F821 (snakemake: defined by Snakemake)
