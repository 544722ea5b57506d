"""Rule build_manuscript: runs chainchaos.workflow.tasks.manuscript.build_manuscript."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.manuscript import build_manuscript

run(snakemake, build_manuscript)  # noqa: F821 (snakemake: defined by Snakemake)
