"""Rule ensemble_verdicts: runs chainchaos.workflow.tasks.search.ensemble_verdicts."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.search import ensemble_verdicts

run(snakemake, ensemble_verdicts)  # noqa: F821 (snakemake: defined by Snakemake)
