"""Rule run_summary: runs chainchaos.workflow.tasks.manuscript.run_summary."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.manuscript import run_summary

run(snakemake, run_summary)  # noqa: F821 (snakemake: defined by Snakemake)
