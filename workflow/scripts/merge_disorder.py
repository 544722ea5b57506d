"""Rule merge_disorder: runs chainchaos.workflow.tasks.scan.merge_disorder."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.scan import merge_disorder

run(snakemake, merge_disorder)  # noqa: F821 (snakemake: defined by Snakemake)
