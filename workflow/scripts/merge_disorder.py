"""merge_disorder: see chainchaos.workflow.tasks.scan.merge_disorder."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
