"""search_merge: see chainchaos.tasks.search.search_merge."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
