"""Rule simulate_scenes: runs chainchaos.workflow.tasks.simulate.simulate_scenes."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.simulate import simulate_scenes

run(snakemake, simulate_scenes)  # noqa: F821 (snakemake: defined by Snakemake)
