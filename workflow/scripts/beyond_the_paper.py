"""beyond_the_paper: see chainchaos.workflow.tasks.manuscript.beyond_the_paper."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
