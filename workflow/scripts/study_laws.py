"""study_laws: see chainchaos.workflow.tasks.study.study_laws."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
