# Reproduction of Ngapasare, Theocharis, Richoux, Skokos & Achilleos, "Chaos and Anderson
# localisation in disordered classical chains: Hertzian vs FPUT models".
#
#   snakemake --cores 2 all                                   paper scale
#   snakemake --cores 2 all --configfile config/quick.yaml    quick scale
#   snakemake --cores 2 results/figures/fig4d.pdf             one panel and what it needs

from snakemake.utils import min_version, validate

from chainchaos.workflow import jobserver, tasks
from chainchaos.workflow.config_check import check_config, typed_overrides

min_version("9.0")


configfile: "config/config.yaml"


# Every wrong key named with what is allowed, before any rule runs; then the schema's defaults.
typed_overrides(config, workflow.config_settings.config)
check_config(config)
validate(config, "config/schema.yaml")


report: "workflow/report/workflow.rst"


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


# A local run's jobs that read, reduce and draw are forked from one process that has imported the
# libraries they use (chainchaos.workflow.jobserver, tasks.SERVED_TASKS): such a job then costs its
# work, not a new interpreter's imports.
JOB_SERVERS = []


onstart:
    if workflow.local_exec:
        JOB_SERVERS.append(jobserver.start(tasks.MODULES))


onsuccess:
    for server in JOB_SERVERS:
        print(f"chainchaos job server: {server.stop()}")


onerror:
    for server in JOB_SERVERS:
        server.stop()


rule all:
    default_target: True
    input:
        ALL_TARGETS,
        NUMERICS_TARGETS,
        SCAN_TARGETS,
        SEARCH_TARGETS,
        MANUSCRIPT_TARGETS,
