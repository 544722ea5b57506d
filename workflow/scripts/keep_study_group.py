"""Rule keep_study_group: runs chainchaos.workflow.tasks.keep.keep_study_group."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import keep_study_group

run(snakemake, keep_study_group)  # noqa: F821 (snakemake: defined by Snakemake)
