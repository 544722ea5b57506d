# Kept results: files of the repository (data/) that runs read instead of computing them, keyed by
# the settings they were made with (chainchaos.records.kept) and used where the config names them
# (search.archive, scan.disorder.archive, use_kept_studies). Their rules exist only in a run whose config
# `keep` names what to make, so that no other target remakes a kept file on its way:
#
#   snakemake --cores 2 keep --config keep=search_full      the full realization search
#   snakemake --cores 2 keep --config keep=disorder_full    the full disorder statistics
#   snakemake --cores 2 keep --config keep=search_rejudge rejudge='[id, ...]'
#   snakemake --cores 2 keep --config keep=<study>          a study's groups, one job each
#
# Each is resumable: commit what a stopped run finished and run the same command again.

import re


rule keep:
    """The kept files of what config `keep` names."""
    input:
        kept_targets,


if KEEP == "search_full":

    rule search_full:
        """The full search's merged result, with its cost and provenance."""
        input:
            search=result("search_full", "search.nc"),
            stages=search_stage_inputs("search_full"),  # the commits and CPUs they ran on
        output:
            archive=SEARCH_ARCHIVE,
        params:
            **search_params("search_full"),  # the settings that key the archive
            benchmarks=result("benchmarks"),
        localrule: True
        log:
            log_file("search_full"),
        benchmark:
            benchmark_file("search_full")
        script:
            "../scripts/search_full.py"


if KEEP == "disorder_full":

    rule disorder_full:
        """The full disorder statistics (config scan.disorder_full), with their cost and provenance."""
        input:
            groups=study_group_files("disorder_full"),
        output:
            archive=SCAN["disorder"]["archive"],
        params:
            scan=plan.scan_params("disorder_full", SCAN),
            N=config["chain"]["N"],
            benchmarks=result("benchmarks"),
        localrule: True
        log:
            log_file("disorder_full"),
        benchmark:
            benchmark_file("disorder_full")
        script:
            "../scripts/disorder_full.py"


# Re-judging the kept full search when the code that judges some statements changed: only those
# statements' scenes are integrated again (chainchaos.studies.search.rejudge), in resumable jobs
# whose files are kept beside the archive (commit them as they finish; only those not kept yet
# have a rule); the result replaces the archive, after which that directory can go. The stages read the archive they replace, so it is
# a parameter of theirs, not an input (it would be a cycle).
if KEEP == "search_rejudge":

    rule search_rejudge_filter:
        """Stage 1 again on the re-judged statements' scenes, for a group of the kept candidates."""
        output:
            result=rejudge_file("filter", "{group}.nc"),
        wildcard_constraints:
            group=plan.still_to_make(rejudge_files("filter")),
        params:
            **rejudge_params(),
        log:
            log_file("search_rejudge_filter", "search_full-{group}"),
        benchmark:
            rejudge_file("benchmarks", "search_rejudge_filter", "search_full-{group}.tsv")
        resources:
            mem_mb=1000,
        script:
            "../scripts/search_rejudge_filter.py"

    rule search_rejudge_score:
        """Stage 2 again for the survivor of a given rank of the re-judged filter."""
        input:
            filters=[ancient(f) for f in rejudge_files("filter")],
        output:
            result=rejudge_file("score", "{rank}.nc"),
        wildcard_constraints:
            rank=plan.still_to_make(rejudge_files("score")),
        params:
            **rejudge_params(),
        log:
            log_file("search_rejudge_score", "search_full-{rank}"),
        benchmark:
            rejudge_file("benchmarks", "search_rejudge_score", "search_full-{rank}.tsv")
        resources:
            mem_mb=1000,
        script:
            "../scripts/search_rejudge_score.py"

    rule search_rejudge:
        """The kept full search with the re-judged statements."""
        input:
            filters=[ancient(f) for f in rejudge_files("filter")],
            scores=[ancient(f) for f in rejudge_files("score")],
        output:
            archive=SEARCH_ARCHIVE,
        params:
            **rejudge_params(),
            benchmarks=rejudge_file("benchmarks"),
        localrule: True
        log:
            log_file("search_rejudge"),
        benchmark:
            benchmark_file("search_rejudge")
        script:
            "../scripts/search_rejudge.py"


# A study's groups, each computed straight into its kept file; only the groups not kept yet have
# a rule (plan.still_to_make), and it has no kernel flag among its inputs: a kept group is never
# redone because a fresh clone compiles its kernels or checked it out before its script.
if KEEP not in (None, *plan.KEPT_PRODUCTS):

    rule keep_study_group:
        """One group of the study config `keep` names, computed and kept."""
        input:
            unpack(study_chain),
        output:
            group=str(Path(config["kept_studies"], "{study}", "groups", "{group}.nc")),
        wildcard_constraints:
            study=re.escape(KEEP),
            group=plan.still_to_make(kept_study_groups(KEEP)),
        params:
            spec=lambda wildcards: plan.group_spec(study_of(wildcards.study)),
        log:
            log_file("keep_study_group", "{study}-{group}"),
        benchmark:
            benchmark_file("keep_study_group", "{study}-{group}")
        resources:
            mem_mb=2000,
            runtime=lambda wildcards: plan.study_minutes(study_of(wildcards.study), US_PER_STEP),
        script:
            "../scripts/keep_study_group.py"


# A kept archive the config chose to use is checked by a job before the jobs that read it (their
# input): its settings against this run's, its result version against this code's and its data
# against their checksum. A mismatch stops the jobs that read it, with one line naming the file, the
# setting that differs and the two ways out (remake it, or compute instead: plan.kept_compute). A
# kept study's groups are checked so by the jobs that read them (study_scene, study_statistics).
rule check_kept_archive:
    """A kept archive the config names (search.archive, scan.disorder.archive), checked."""
    input:
        archive=lambda wildcards: kept_input(
            plan.archive_path(wildcards.archive, config), wildcards.archive
        ),
    output:
        record=result("kept", "{archive}.txt"),
    wildcard_constraints:
        archive="|".join(plan.ARCHIVE_KEYS),
    params:
        check=lambda wildcards: plan.archive_check(wildcards.archive, config),
    localrule: True
    log:
        log_file("check_kept_archive", "{archive}"),
    benchmark:
        benchmark_file("check_kept_archive", "{archive}")
    script:
        "../scripts/check_kept_archive.py"
