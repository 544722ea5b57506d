"""Rule study_scene: runs chainchaos.workflow.tasks.study.study_scene."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.study import study_scene

run(snakemake, study_scene)  # noqa: F821 (snakemake: defined by Snakemake)
