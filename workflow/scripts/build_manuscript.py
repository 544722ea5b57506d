"""build_manuscript: see chainchaos.workflow.tasks.manuscript.build_manuscript."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
