"""search_candidates: see chainchaos.tasks.search.search_candidates."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
