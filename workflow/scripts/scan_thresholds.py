"""Rule scan_thresholds: runs chainchaos.workflow.tasks.scan.scan_thresholds."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.scan import scan_thresholds

run(snakemake, scan_thresholds)  # noqa: F821 (snakemake: defined by Snakemake)
