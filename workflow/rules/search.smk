# The realization chosen by the paper's published dynamics (chainchaos.studies.search.stages): the linear rule
# over chunks of seeds, a short-run filter, and ensembles of the survivors scored against the paper's
# statements (chainchaos.paper.statements.STATEMENTS), each stage's orbits a study of its chains
# (chainchaos.paper.ensembles); then, on the chosen chain, the ensemble verdicts of every statement
# (chainchaos.paper.verdicts) that the claims table reads, judged on the studies verdicts_<model>.
#
# The rules serve two searches ({search}): `search`, the one `all` runs, and `search_full`, the
# search over many more chains whose merged result is kept in the repository (config
# search.archive; made by `snakemake --cores 2 keep --config keep=search_full`, keep.smk). When
# config search.archive names it, `all` takes its candidates and chosen chain (checked by rule
# check_kept_archive) and re-scores that chain only (search.pinned_seed, its chosen seed); without
# an archive, search.pinned_seed pins any seed, and with neither `all` searches at its scale. Stages 1 and
# 2 are studies of their chains, one per model (<search>-filter-<model>, <search>-score-<model>),
# whose groups rule study_group makes (study.smk); the chunks of seeds and the groups are files of
# their own, so a killed search resumes where it stopped.


wildcard_constraints:
    search="search|search_full",
    chunk=r"\d+",
    group=r"\d+",
    rank=r"\d+",


rule search_seeds:
    """Stage 0: the chains of a chunk of seeds that pass the linear rule."""
    output:
        result=result("{search}", "seeds", "{chunk}.nc"),
    priority: 10  # needs no kernel: runs while they compile, and the stages after it wait for it
    params:
        search=search_param("search"),
        chain=search_param("chain"),
    log:
        log_file("search_seeds", "{search}-{chunk}"),
    benchmark:
        benchmark_file("search_seeds", "{search}-{chunk}")
    script:
        "../scripts/search_seeds.py"


checkpoint search_candidates:
    """Stage 0: the candidates (or the pinned seed), from every chunk of seeds."""
    input:
        seeds=search_seed_files,
    output:
        result=result("{search}", "candidates.nc"),
    priority: 10
    params:
        search=search_param("search"),
        chain=search_param("chain"),
    log:
        log_file("search_candidates", "{search}"),
    benchmark:
        benchmark_file("search_candidates", "{search}")
    script:
        "../scripts/search_candidates.py"


checkpoint search_filter:
    """Stage 1 judged: the filter studies' short orbits (rule study_group) decide each candidate's
    early statements; the survivors, whose chains the score studies run."""
    input:
        candidates=result("{search}", "candidates.nc"),
        groups=search_study_files("filter"),
    output:
        result=result("{search}", "filter.nc"),
    priority: 4
    params:
        search=search_param("search"),
        chain=search_param("chain"),
        claims=search_param("claims"),
        site=search_param("site"),
    log:
        log_file("search_filter", "{search}"),
    benchmark:
        benchmark_file("search_filter", "{search}")
    script:
        "../scripts/search_filter.py"


rule search_merge:
    """Stage 2 judged (the score studies' ensembles of the survivors), the chosen chain, and the
    search as one file."""
    input:
        candidates=result("{search}", "candidates.nc"),
        filters=search_filter_file,
        groups=search_study_files("score"),
    output:
        result=result("{search}", "search.nc"),
    priority: 4
    params:
        search=search_param("search"),
        chain=search_param("chain"),
        claims=search_param("claims"),
        site=search_param("site"),
    log:
        log_file("search_merge", "{search}"),
    benchmark:
        benchmark_file("search_merge", "{search}")
    script:
        "../scripts/search_merge.py"


rule plot_search:
    """The search's two figures from one read of its candidates: the statements each keeps, and
    the statements analysed jointly."""
    input:
        **SEARCH_INPUTS,
    output:
        pdf=result("figures", "search.pdf"),
        png=report(
            result("figures", "search.png"),
            caption="../report/search.rst",
            category=REPORT_CATEGORIES["search"],
            labels={"result": "search", "shows": "statements kept by each candidate chain"},
        ),
        joint_pdf=result("figures", "search_joint.pdf"),
        joint_png=report(
            result("figures", "search_joint.png"),
            caption="../report/search_joint.rst",
            category=REPORT_CATEGORIES["search"],
            labels={
                "result": "search_joint",
                "shows": "statements that hold together, scores, H = 1.8 chaos",
            },
        ),
    params:
        dpi=config["figures"]["dpi"],
        claims=config.get("claims", {}),
    log:
        log_file("plot_search"),
    benchmark:
        benchmark_file("plot_search")
    script:
        "../scripts/plot_search.py"


# The scenes of one model are one study (paper.ensembles.verdict_study, study verdicts_<model>): its
# orbits run in the study's jobs (rule study_group), and this rule judges one scene's statements on
# its ensemble (seconds of work).
rule ensemble_verdicts:
    """The verdicts of one scene's statements over its ensemble on the chosen chain."""
    localrule: True
    input:
        chain=result("chain", "chain.nc"),
        groups=lambda wildcards: study_group_files(
            verdict_study_name(SCENES[wildcards.scene].model)
        ),
    output:
        verdicts=result("verdicts", "{scene}.nc"),
    priority: 3
    params:
        verdicts=config["verdicts"],
        claims=config.get("claims", {}),
    log:
        log_file("ensemble_verdicts", "{scene}"),
    benchmark:
        benchmark_file("ensemble_verdicts", "{scene}")
    script:
        "../scripts/ensemble_verdicts.py"


SEARCH_TARGETS = [
    result("search", "search.nc"),
    result("figures", "search.pdf"),
    result("figures", "search.png"),
    result("figures", "search_joint.pdf"),
    result("figures", "search_joint.png"),
    *VERDICT_FILES.values(),
]
