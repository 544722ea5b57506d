"""Rule check_kept_archive: runs chainchaos.workflow.tasks.keep.check_kept_archive."""

from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.keep import check_kept_archive

run(snakemake, check_kept_archive)  # noqa: F821 (snakemake: defined by Snakemake)
