"""search_score: see chainchaos.tasks.search.search_score."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
