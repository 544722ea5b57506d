# Energy scan and disorder statistics of delocalization and chaos (issue 7).
#
# Each is a study (chainchaos.studies.scan.runs.scan_study: the config block `scan` read as a
# study's keys), whose orbits run in the study's jobs (rule study_group, workflow/rules/study.smk;
# `trajectories_per_job` orbits each, so that the DAG stays at hundreds of jobs at paper scale);
# the merge rules below put its group files on the scan's (model, energy[, realization]) grid.
# `resources:` (mem_mb, runtime in minutes) feed the SLURM profile (profiles/slurm/).


# Seconds of work each: on a cluster they run on the submitting host rather than wait in the queue.
localrules:
    merge_energy_scan,
    merge_disorder,
    plot_energy_scan,
    plot_disorder_statistics,
    scan_thresholds,


rule merge_energy_scan:
    input:
        groups=study_group_files("energy_scan"),
        chain=result("chain", "chain.nc"),
    output:
        merged=result("scan", "energy_scan.nc"),
    params:
        scan=plan.scan_params("energy_scan", SCAN),
    log:
        log_file("merge_energy_scan"),
    benchmark:
        benchmark_file("merge_energy_scan")
    resources:
        mem_mb=2000,
        runtime=15,
    script:
        "../scripts/merge_energy_scan.py"


rule merge_disorder:
    """The disorder statistics on their grid: merged from the groups, or the kept full ones when
    config scan.disorder.archive names them (checked first by rule check_kept_archive)."""
    input:
        **(
            {
                "archive": lambda wildcards: kept_input(DISORDER_ARCHIVE, "disorder_full"),
                "kept": kept_check("disorder_full"),
            }
            if DISORDER_ARCHIVE
            else {"groups": study_group_files("disorder")}
        ),
    output:
        merged=result("scan", "disorder_statistics.nc"),
    params:
        scan=plan.scan_params("disorder", SCAN),
    log:
        log_file("merge_disorder"),
    benchmark:
        benchmark_file("merge_disorder")
    resources:
        mem_mb=2000,
        runtime=15,
    script:
        "../scripts/merge_disorder.py"


rule plot_energy_scan:
    input:
        data=result("scan", "energy_scan.nc"),
    output:
        pdf=result("figures", "energy_scan.pdf"),
        png=report(
            result("figures", "energy_scan.png"),
            caption="../report/energy_scan.rst",
            category=REPORT_CATEGORIES["scan"],
            labels={"result": "energy scan", "shows": "P, Lambda, eta and gaps against H"},
        ),
    params:
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_energy_scan"),
    benchmark:
        benchmark_file("plot_energy_scan")
    resources:
        mem_mb=2000,
        runtime=10,
    script:
        "../scripts/plot_energy_scan.py"


rule plot_disorder_statistics:
    input:
        data=result("scan", "disorder_statistics.nc"),
    output:
        pdf=result("figures", "disorder_statistics.pdf"),
        png=report(
            result("figures", "disorder_statistics.png"),
            caption="../report/disorder_statistics.rst",
            category=REPORT_CATEGORIES["scan"],
            labels={
                "result": "disorder statistics",
                "shows": "probabilities and onsets against H",
            },
        ),
    params:
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_disorder_statistics"),
    benchmark:
        benchmark_file("plot_disorder_statistics")
    resources:
        mem_mb=2000,
        runtime=10,
    script:
        "../scripts/plot_disorder_statistics.py"


rule scan_thresholds:
    """Energies where the chain delocalizes and where it is chaotic, with the criteria."""
    input:
        data=result("scan", "energy_scan.nc"),
    output:
        csv=report(
            result("scan", "thresholds.csv"),
            caption="../report/thresholds.rst",
            category=REPORT_CATEGORIES["scan"],
            labels={"result": "thresholds (CSV)", "shows": "threshold energies of the scan"},
        ),
        tex=result("scan", "thresholds.tex"),
    log:
        log_file("scan_thresholds"),
    benchmark:
        benchmark_file("scan_thresholds")
    resources:
        mem_mb=1000,
        runtime=5,
    script:
        "../scripts/scan_thresholds.py"


SCAN_TARGETS = [
    result("scan", "energy_scan.nc"),
    result("scan", "disorder_statistics.nc"),
    result("scan", "thresholds.csv"),
    result("scan", "thresholds.tex"),
    result("figures", "energy_scan.pdf"),
    result("figures", "energy_scan.png"),
    result("figures", "disorder_statistics.pdf"),
    result("figures", "disorder_statistics.png"),
]
