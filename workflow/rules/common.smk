# Paths and config lookups of the rule files. Every decision (which kept file a run uses, which
# scenes share a job, what a target asks for) is a function of chainchaos.workflow.plan, called
# here with the config; the rule files are included after this one (Snakefile).

import os
import re
import sys
from pathlib import Path
from snakemake.exceptions import WorkflowError
from types import SimpleNamespace

from chainchaos.errors import StudyError
from chainchaos.kernels.cache import kernel_sources
from chainchaos.output import report_captions
from chainchaos.paper import panels, statements
from chainchaos.paper.ensembles import verdict_study_name
from chainchaos.studies.study.spec import kept_group_path, study_names
from chainchaos.system.models import PACKAGE_MODELS
from chainchaos.workflow import plan
from chainchaos.workflow.tasks.chain import selection_criteria

RESULTS = config["results"]
FIGURES = sorted(panels.LAYOUTS)
SCENES = panels.scenes()
US_PER_STEP = config["scan"].get("us_per_step", 1.0)


def result(*parts):
    return "/".join([RESULTS, *parts])


def log_file(rule_name, stem="run"):
    return result("logs", rule_name, f"{stem}.log")


def benchmark_file(rule_name, stem="run"):
    return result("benchmarks", rule_name, f"{stem}.tsv")


def scene_file(name):
    return result("scenes", f"{name}.nc")


def kept_input(path, what):
    """A kept file the config chose to use, as an input: ancient() (its checkout time says nothing
    of its age). Absent, the plan stops naming it and the ways out, and nothing computes it
    (``what``: the archive's or the study's name). A stat, not a read: a job judges what the file
    holds (check_kept_archive for an archive, the jobs that read a kept study's groups). Call it
    from an input function: only a run that needs the file looks for it."""
    if not Path(path).exists():
        raise WorkflowError(
            f"kept file {path} is absent; restore it with 'git checkout -- {path}', "
            f"remake it with '{plan.remake_command(what)}', or {plan.kept_compute(what)}"
        )
    return ancient(path)


REPORT_CATEGORIES = report_captions.CATEGORIES


# ---- scenes and figures (simulate.smk, figures.smk) --------------------------------------------
ALL_TARGETS = plan.paper_targets(RESULTS)


def kernel_flags(models=None):
    """The flags of compile_kernels for ``models`` (default: the paper's); a model of one's own
    compiles in the first jobs that run it."""
    return [
        result("kernels", f"{m}.txt") for m in (models or panels.models()) if m in PACKAGE_MODELS
    ]


def earlier_kernel_flags(wildcards):
    """The flags of the paper's models before ``wildcards.model``: its job loads the kernels they
    share from the cache instead of compiling them again."""
    models = panels.models()
    before = models[: models.index(wildcards.model)] if wildcards.model in models else []
    return [result("kernels", f"{m}.txt") for m in before]


def kernel_inputs():
    return [os.path.relpath(path) for path in kernel_sources()]


# ---- scans, search and verdicts (scan.smk, search.smk) -----------------------------------------
SCAN = config["scan"]
SEARCH_PLANS = plan.search_plans(config)
SEARCH_ARCHIVE = plan.archive_path("search_full", config)
DISORDER_ARCHIVE = plan.archive_path("disorder_full", config)


def kept_check(name):
    """The record of the check of the kept archive ``name`` (made by check_kept_archive), an
    input of every job that reads the archive."""
    return result("kept", f"{name}.txt")


def search_params(name):
    return plan.search_params(name, config)


def search_param(key):
    return lambda wildcards: search_params(wildcards.search)[key]


def search_seed_files(wildcards):
    """Stage 0's files: the chunks of seeds of the linear rule."""
    chain = plan.search_chain(wildcards.search, config)
    n = SEARCH_PLANS[wildcards.search].n_seed_jobs(selection_criteria({"chain": chain}))
    return [result(wildcards.search, "seeds", f"{k:03d}.nc") for k in range(n)]


def search_study_files(stage):
    """The groups of the studies of a search's stage (``filter``, ``score``), once the stages before
    have run (their chains are read from them); with a pinned seed, its score studies alone."""

    def files(wildcards):
        search = wildcards.search
        if SEARCH_PLANS[search].pinned:  # the pinned seed's chain is scored, and none is filtered
            if stage == "filter":
                return []
        else:
            checkpoints.search_candidates.get(search=search)
            if stage == "score":
                checkpoints.search_filter.get(search=search)
        return [f for name in plan.search_studies(search, stage) for f in study_group_files(name)]

    return files


def search_stage_inputs(search):
    """Every file the stages of ``search`` write before its merge."""

    def files(wildcards):
        stage = SimpleNamespace(search=search)
        return [
            *search_seed_files(stage),
            result(search, "candidates.nc"),
            *search_filter_file(stage),
            *search_study_files("filter")(stage),
            *search_study_files("score")(stage),
        ]

    return files


def search_filter_file(wildcards):
    """Stage 1's judged file, which a search with a pinned seed has not."""
    return [] if SEARCH_PLANS[wildcards.search].pinned else [result(wildcards.search, "filter.nc")]


# The search whose candidates the manuscript counts and whose chosen chain `all` runs on: the kept
# full search, with the record of its check, or this run's.
SEARCH_INPUTS = (
    {
        "search": lambda wildcards: kept_input(SEARCH_ARCHIVE, "search_full"),
        "kept": kept_check("search_full"),
    }
    if SEARCH_ARCHIVE
    else {"search": result("search", "search.nc")}
)
VERDICT_FILES = {name: result("verdicts", f"{name}.nc") for name in statements.statement_scenes()}
SPECTRA_FILES = {
    f"spectrum_{name}": result("indicators", f"spectrum_{name}.nc")
    for name in config["indicators"]["spectra"]["scenes"]
}


# ---- studies (study.smk, scan.smk, manuscript.smk) ---------------------------------------------
STUDIES = {}


def study_of(name):
    """The study ``name`` (a scan kind, the file config `study` names, or studies/<name>.yaml),
    read and checked once."""
    if name not in STUDIES:
        STUDIES[name] = plan.load_run_study(name, config)
    return STUDIES[name]


def study_figure_names(name):
    return plan.study_figure_names(study_of(name))


KEPT_STUDIES = config["use_kept_studies"]


def kept_group_file(name, group):
    return str(kept_group_path(name, group, config["kept_studies"]))


def is_kept_study(name):
    """Whether study ``name``'s groups are kept files: config use_kept_studies names it, or config
    keep makes it."""
    return name == KEEP or name in KEPT_STUDIES


def study_group_file(name, group):
    """A group of a study: its kept file for a kept study (one this run makes need not exist yet),
    else the file study_group makes."""
    if not is_kept_study(name):
        return result("studies", name, "groups", f"{group:04d}.nc")
    path = kept_group_file(name, group)
    return path if name == KEEP else kept_input(path, name)


def study_group_files(name):
    return [study_group_file(name, g) for g in range(study_of(name).n_groups)]


def study_group_check(wildcards):
    """For a kept study, what the jobs that read its groups say when one does not match it."""
    name = wildcards.study
    return plan.kept_study_check(name, config["kept_studies"]) if is_kept_study(name) else {}


def study_chain(wildcards):
    chain_file = study_of(wildcards.study).spec["lattice"]["chain_file"]
    return {"chain": chain_file} if chain_file else {}


NAMED_STUDY = plan.study_name(config["study"]) if config.get("study") else None
# A study named on the command line is checked before anything is planned: its wrong keys, one
# line each and no traceback.
if NAMED_STUDY:
    try:
        study_of(NAMED_STUDY)
    except StudyError as error:
        sys.exit(str(error))
# The kept result this run makes (config keep; workflow/rules/keep.smk).
KEEP = plan.kept_product(config.get("keep"), [*study_names(), *filter(None, [NAMED_STUDY])])
# The studies of the section Beyond the paper and the figures it shows of each (config
# manuscript.beyond): a study there that config use_kept_studies names is read from its kept
# groups, never computed.
SHOWN = plan.beyond_entries(config.get("manuscript", {}).get("beyond", []), study_figure_names)


def study_figure_inputs(wildcards):
    """The statistics a study's figure reads: its own, and for ``comparison`` its compared
    studies'."""
    figures = study_figure_names(wildcards.study)
    if wildcards.figure not in figures:
        raise ValueError(
            f"study {wildcards.study} draws no figure {wildcards.figure}; its figures: {figures}"
        )
    compared = (
        study_of(wildcards.study).spec["compare_with"] if wildcards.figure == "comparison" else []
    )
    return {n: result("studies", n, "statistics.nc") for n in [wildcards.study, *compared]}


def named_study():
    if not NAMED_STUDY:
        raise ValueError(
            f"the target study needs a study: --config study=<name>, one of {study_names()}"
        )
    return NAMED_STUDY


# ---- kept results (keep.smk) -------------------------------------------------------------------


def rejudge_file(*parts):
    return str(Path(SEARCH_ARCHIVE).parent.joinpath("rejudge", *parts))


def rejudge_params():
    """The full search's parameters, its archive and the statements config `rejudge` names."""
    return {
        **search_params("search_full"),
        "archive": SEARCH_ARCHIVE,
        "rejudge": list(config.get("rejudge") or []),
    }


def rejudge_files(stage):
    """The stage files of re-judging the kept full search: their number is its candidates' (the
    one kept file a plan reads, its header alone, and only in a run of keep=search_rejudge)."""
    from chainchaos.records.kept import read_header

    sizes = read_header(SEARCH_ARCHIVE, plan.remake_command("search_full"))[1]
    return plan.rejudge_files(config, SEARCH_PLANS["search_full"], sizes["candidate"], stage)


def kept_targets(wildcards):
    return plan.kept_targets(
        KEEP, config, study_of(KEEP) if KEEP not in plan.KEPT_PRODUCTS else None
    )


def kept_study_groups(name):
    """Where every group of study ``name`` is kept."""
    return [kept_group_file(name, g) for g in range(study_of(name).n_groups)]
