"""simulate_scenes: see chainchaos.workflow.tasks.simulate.simulate_scenes."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
