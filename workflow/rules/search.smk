# The realization chosen by the paper's published dynamics (chainchaos.studies.search.stages): the linear rule,
# a short-run filter, and ensembles of the survivors scored against the paper's statements
# (chainchaos.paper.statements.STATEMENTS); then, on the chosen chain, the ensemble verdicts of every statement
# (chainchaos.paper.verdicts) that the claims table reads. With `search.pinned_seed` set, the search
# re-scores that chain only.


wildcard_constraints:
    rank=r"\d+",


N_STATEMENT_SCENES = len(statements.statement_scenes())


rule search_candidates:
    """Stage 0: the chains that pass the linear rule (or the pinned seed), computed once."""
    output:
        result=result("search", "candidates.nc"),
    params:
        **search_params(),
    log:
        log_file("search_candidates"),
    benchmark:
        benchmark_file("search_candidates")
    script:
        "../scripts/search_candidates.py"


rule search_filter:
    """Stage 1: one short orbit per scene for a group of candidates."""
    input:
        candidates=result("search", "candidates.nc"),
        kernels=result("kernels_compiled.txt"),
    output:
        result=result("search", "filter", "{group}.nc"),
    params:
        **search_params(),
    log:
        log_file("search_filter", "{group}"),
    benchmark:
        benchmark_file("search_filter", "{group}")
    resources:
        mem_mb=1000,
        runtime=search_runtime(
            N_STATEMENT_SCENES * SEARCH_PLAN.candidates_per_job, SEARCH_PLAN.filter_t_final
        ),
    script:
        "../scripts/search_filter.py"


rule search_score:
    """Stage 2: the ensembles of the survivor of a given rank."""
    input:
        candidates=result("search", "candidates.nc"),
        filters=search_filter_files(),
        kernels=result("kernels_compiled.txt"),
    output:
        result=result("search", "score", "{rank}.nc"),
    priority: 4
    params:
        **search_params(),
    log:
        log_file("search_score", "{rank}"),
    benchmark:
        benchmark_file("search_score", "{rank}")
    resources:
        mem_mb=1000,
        runtime=search_runtime(
            N_STATEMENT_SCENES * SEARCH_PLAN.lanes, config["search"]["settings"]["t_final"]
        ),
    script:
        "../scripts/search_score.py"


rule search_merge:
    input:
        candidates=result("search", "candidates.nc"),
        filters=search_filter_files(),
        scores=search_score_files(),
    output:
        result=result("search", "search.nc"),
    params:
        **search_params(),
    log:
        log_file("search_merge"),
    benchmark:
        benchmark_file("search_merge")
    script:
        "../scripts/search_merge.py"


rule plot_search:
    input:
        search=result("search", "search.nc"),
    output:
        pdf=result("figures", "search.pdf"),
        png=report(
            result("figures", "search.png"),
            caption="../report/search.rst",
            category=REPORT_CATEGORIES["search"],
            labels={"result": "search", "shows": "statements kept by each candidate chain"},
        ),
    params:
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_search"),
    benchmark:
        benchmark_file("plot_search")
    script:
        "../scripts/plot_search.py"


rule ensemble_verdicts:
    """A scene's ensemble of perturbed orbits on the chosen chain, and its statements' verdicts."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=result("kernels_compiled.txt"),
    output:
        result=result("verdicts", "{scene}.nc"),
    priority: 3
    params:
        verdicts=config["verdicts"],
        claims=config.get("claims", {}),
        site=config["simulation"]["excited_site"],
    log:
        log_file("ensemble_verdicts", "{scene}"),
    benchmark:
        benchmark_file("ensemble_verdicts", "{scene}")
    resources:
        mem_mb=1000,
        runtime=search_runtime(
            config["verdicts"]["lanes"], config["verdicts"]["settings"]["t_final"]
        ),
    script:
        "../scripts/ensemble_verdicts.py"


VERDICT_FILES = {name: result("verdicts", f"{name}.nc") for name in statements.statement_scenes()}
SEARCH_TARGETS = [
    result("search", "search.nc"),
    result("figures", "search.pdf"),
    result("figures", "search.png"),
    *VERDICT_FILES.values(),
]
