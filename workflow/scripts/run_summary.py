"""run_summary: see chainchaos.workflow.tasks.manuscript.run_summary."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
