"""ensemble_verdicts: see chainchaos.tasks.search.ensemble_verdicts."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
