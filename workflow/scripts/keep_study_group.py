"""keep_study_group: see chainchaos.workflow.tasks.study.keep_study_group."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
