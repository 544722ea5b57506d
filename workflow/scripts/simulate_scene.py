"""Rule simulate_scene: runs chainchaos.workflow.tasks.simulate.simulate_scene."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.simulate import simulate_scene

run(snakemake, simulate_scene)  # noqa: F821 (snakemake: defined by Snakemake)
