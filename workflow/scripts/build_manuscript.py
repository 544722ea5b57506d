"""build_manuscript: see chainchaos.tasks.manuscript.build_manuscript."""

from chainchaos.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
