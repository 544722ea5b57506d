# Reproduction of Ngapasare, Theocharis, Richoux, Skokos & Achilleos, "Chaos and Anderson
# localisation in disordered classical chains: Hertzian vs FPUT models".
#
#   snakemake --cores 2 all                                   paper scale
#   snakemake --cores 2 all --configfile config/quick.yaml    quick scale
#   snakemake --cores 2 results/figures/fig4d.pdf             one panel and what it needs (paper scale)
#   snakemake --cores 2 results/figures/fig4d.pdf --configfile config/quick.yaml   (quick scale: targets first)
#   snakemake --cores 2 keep --config keep=<what>             a kept result (workflow/rules/keep.smk)

import os
import sys

from snakemake.utils import min_version, validate

min_version("9.0")

# The package of this checkout, whatever else is installed: a second clone runs its own code, here
# and in every job (PYTHONPATH is passed on to the jobs' interpreters).
SOURCES = str(Path(workflow.basedir, "src").resolve())
sys.path.insert(0, SOURCES)
os.environ.update(PYTHONPATH=os.pathsep.join(filter(None, [SOURCES, os.environ.get("PYTHONPATH")])))
# One matplotlib config directory for every job, inside the project: its font cache is built once,
# not by each plotting job on a machine with a fresh home (a user's MPLCONFIGDIR wins).
os.environ.setdefault("MPLCONFIGDIR", str(Path(workflow.basedir, ".matplotlib")))
import chainchaos

if str(Path(chainchaos.__file__).resolve().parents[1]) != SOURCES:
    raise ImportError(
        f"this workflow ({workflow.basedir}) would run the chainchaos of {chainchaos.__file__}, "
        "not its own src/: unset PYTHONPATH or run the other checkout's workflow"
    )

from chainchaos.errors import ConfigError
from chainchaos.workflow.config_check import check_config, typed_overrides


configfile: "config/config.yaml"


# Every wrong key named with what is allowed, one line each and no traceback, before any rule runs;
# then the schema's defaults.
typed_overrides(config, workflow.config_settings.config)
try:
    check_config(config)
except ConfigError as error:
    sys.exit(str(error))
validate(config, "config/schema.yaml")


report: "workflow/report/workflow.rst"


# common.smk first: the paths and lookups the rule files use; the rule files define the lists of
# targets that `all` asks for (numerics.smk: NUMERICS_TARGETS, ...).
include: "workflow/rules/common.smk"
include: "workflow/rules/chain.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/numerics.smk"
include: "workflow/rules/scan.smk"
include: "workflow/rules/indicators.smk"
include: "workflow/rules/search.smk"
include: "workflow/rules/manuscript.smk"
include: "workflow/rules/study.smk"
include: "workflow/rules/keep.smk"


rule all:
    default_target: True
    input:
        ALL_TARGETS,
        NUMERICS_TARGETS,
        SCAN_TARGETS,
        SEARCH_TARGETS,
        MANUSCRIPT_TARGETS,
