"""Rule study_statistics: runs chainchaos.workflow.tasks.study.study_statistics."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.study import study_statistics

run(snakemake, study_statistics)  # noqa: F821 (snakemake: defined by Snakemake)
