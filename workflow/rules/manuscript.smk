# The reproduction manuscript: the paper's claims measured on the results (evaluate_claims), and
# manuscript/ms.tex built by latexmk from the figures, tables and generated macros (build_manuscript).
# Every input comes from the `results` directory, so `--config results=DIR` builds entirely from DIR;
# the PDF goes to config manuscript.pdf (default manuscript/ms.pdf).

MANUSCRIPT_PDF = config.get("manuscript", {}).get("pdf", "manuscript/ms.pdf")

# The code that measures and writes the claims: an input of evaluate_claims.
CLAIMS_CODE = sorted(str(p) for p in Path("src/chainchaos/paper/claims").glob("*.py")) + [
    "src/chainchaos/records/formatting.py",
    "src/chainchaos/workflow/tasks/manuscript.py",
]

CLAIMS_OUTPUTS = {
    "csv": result("claims", "claims.csv"),
    "table": result("claims", "claims_table.tex"),
    "notes": result("claims", "claims_notes.tex"),
    "scenes": result("claims", "scenes_table.tex"),
    "macros": result("claims", "macros.tex"),
    "search": result("claims", "search_table.tex"),
}

# The numerical-error report (workflow/rules/numerics.smk): its figures and tables go into the
# manuscript when config manuscript.numerics is true; otherwise the manuscript says that the report
# is not part of this build.
NUMERICS_FOR_MANUSCRIPT = {
    "wpfigure": result("figures", "work_precision.pdf"),
    "wptable": result("tables", "work_precision.tex"),
    "stabfigure": result("figures", "stability.pdf"),
    "stabtable": result("tables", "stability.tex"),
    "advicetable": result("tables", "step_advice.tex"),
}
if not config.get("manuscript", {}).get("numerics", True):
    NUMERICS_FOR_MANUSCRIPT = {}


rule evaluate_claims:
    """Measure every quantitative statement of the paper on the scene, chain and ensemble files:
    claims.csv, the LaTeX table and notes, and macros.tex with every number the manuscript prints.
    """
    input:
        **{f"verdict_{name}": path for name, path in VERDICT_FILES.items()},
        **SPECTRA_FILES,
        **{name: scene_file(name) for name in sorted(SCENES)},
        **({"kept": SEARCH_INPUTS["kept"]} if "kept" in SEARCH_INPUTS else {}),
        code=CLAIMS_CODE,  # a changed criterion or text in the code reruns the claims
        chain=result("chain", "chain.nc"),
        ensemble=result("ensemble", "participation_stats.nc"),
        energy_scan=result("scan", "energy_scan.nc"),
        disorder=result("scan", "disorder_statistics.nc"),
        search=result("search", "search.nc"),
        search_population=SEARCH_INPUTS["search"],
    output:
        csv=report(
            CLAIMS_OUTPUTS["csv"],
            caption="../report/claims.rst",
            category=REPORT_CATEGORIES["claims"],
            labels={
                "result": "claims table (CSV)",
                "shows": "the paper's statements and verdicts",
            },
        ),
        table=CLAIMS_OUTPUTS["table"],
        notes=CLAIMS_OUTPUTS["notes"],
        scenes=CLAIMS_OUTPUTS["scenes"],
        macros=CLAIMS_OUTPUTS["macros"],
        search=CLAIMS_OUTPUTS["search"],
    params:
        claims=config.get("claims", {}),
        simulation=config["simulation"],
        ensemble=config["ensemble"],
        chain=config["chain"],
        scenes=config.get("scenes", {}),
        scan=config["scan"],
    log:
        log_file("evaluate_claims"),
    benchmark:
        benchmark_file("evaluate_claims")
    script:
        "../scripts/evaluate_claims.py"


rule beyond_the_paper:
    """The generated body of the section Beyond the paper: the kept studies' power laws beside the
    published exponents, and their figures."""
    input:
        laws=[result("studies", name, "laws.nc") for name in SHOWN],
    output:
        body=result("tables", "beyond_the_paper.tex"),
    params:
        studies=list(SHOWN),
        figures=SHOWN,
    log:
        log_file("beyond_the_paper"),
    benchmark:
        benchmark_file("beyond_the_paper")
    script:
        "../scripts/beyond_the_paper.py"


rule build_manuscript:
    """latexmk in results/manuscript_build/ on a copy of manuscript/ms.tex and of its inputs; stops
    with a message naming the Debian TeX packages when TeX or revtex4-2 is missing."""
    input:
        **CLAIMS_OUTPUTS,
        **{f"fig{n}": result("figures", f"fig{n}.pdf") for n in FIGURES},
        **{f"numerics_{key}": path for key, path in NUMERICS_FOR_MANUSCRIPT.items()},
        **plan.beyond_inputs(RESULTS, SHOWN),
        tex="manuscript/ms.tex",
        figscan=result("figures", "energy_scan.pdf"),
        figdisorder=result("figures", "disorder_statistics.pdf"),
        thresholds=result("scan", "thresholds.tex"),
        figsearch=result("figures", "search.pdf"),
        figsearchjoint=result("figures", "search_joint.pdf"),
        figspectra=result("figures", "lyapunov_spectra.pdf"),
    output:
        pdf=MANUSCRIPT_PDF,
    params:
        build_dir=result("manuscript_build"),
    log:
        log_file("build_manuscript"),
    benchmark:
        benchmark_file("build_manuscript")
    script:
        "../scripts/build_manuscript.py"


rule run_summary:
    """What this run did, read from its files (the chain and how it was chosen, the integration,
    the scans and the archives they came from, the claims' verdicts): the report's front page
    points to it."""
    input:
        chain=result("chain", "chain.nc"),
        lock="requirements/lock.txt",
        scene=scene_file(sorted(SCENES)[0]),
        energy_scan=result("scan", "energy_scan.nc"),
        disorder=result("scan", "disorder_statistics.nc"),
        claims=CLAIMS_OUTPUTS["csv"],
    output:
        csv=report(
            result("report", "run_summary.csv"),
            caption="../report/run_summary.rst",
            category=REPORT_CATEGORIES["run"],
            labels={"result": "this run", "shows": "what the run did, from its files"},
        ),
    log:
        log_file("run_summary"),
    benchmark:
        benchmark_file("run_summary")
    script:
        "../scripts/run_summary.py"


MANUSCRIPT_TARGETS = [*CLAIMS_OUTPUTS.values(), MANUSCRIPT_PDF, result("report", "run_summary.csv")]
