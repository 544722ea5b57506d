"""simulate_scene: see chainchaos.tasks.simulate.simulate_scene."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
