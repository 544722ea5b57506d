"""merge_disorder: see chainchaos.tasks.scan.merge_disorder."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
