"""study_statistics: see chainchaos.workflow.tasks.study.study_statistics."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
