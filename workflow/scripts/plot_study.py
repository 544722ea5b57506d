"""plot_study: see chainchaos.workflow.tasks.study.plot_study."""

from chainchaos.workflow.tasks import run_rule

run_rule(snakemake)  # noqa: F821 (defined by Snakemake)
