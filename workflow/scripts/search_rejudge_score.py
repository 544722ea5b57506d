"""search_rejudge_score: see chainchaos.workflow.tasks.search.search_rejudge_score."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
