"""Rule beyond_the_paper: runs chainchaos.workflow.tasks.manuscript.beyond_the_paper."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.manuscript import beyond_the_paper

run(snakemake, beyond_the_paper)  # noqa: F821 (snakemake: defined by Snakemake)
