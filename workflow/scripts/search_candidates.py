"""search_candidates: see chainchaos.workflow.tasks.search.search_candidates."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
