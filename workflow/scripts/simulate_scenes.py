"""simulate_scenes: see chainchaos.tasks.simulate.simulate_scenes."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
