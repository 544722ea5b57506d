"""Rule study_group: runs chainchaos.workflow.tasks.study.study_group."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.study import study_group

run(snakemake, study_group)  # noqa: F821 (snakemake: defined by Snakemake)
