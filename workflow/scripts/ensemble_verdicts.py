"""ensemble_verdicts: see chainchaos.tasks.ensemble_verdicts."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
