# Shared helpers: where things go, what each scene and panel needs (from the panel table), and the
# inputs, parameters and cluster runtimes of the scan, search and manuscript rules. The functions
# of the workflow live here and the rules in the other files, as snakemake --lint asks.

import functools
import glob
import math
import os
import re
import sys
from pathlib import Path

import xarray as xr

from chainchaos.engine.batch import SERIAL_REMAINDER
from chainchaos.engine.simd import LANES
from chainchaos.output import beyond, kept
from chainchaos.output.report_captions import figure_labels, figure_subcategory, panel_labels
from chainchaos.paper import panels, statements
from chainchaos.run.scenes import scene_batches, scene_parameters
from chainchaos.studies.scan import runs as scan_runs
from chainchaos.studies.search import archive, rejudge
from chainchaos.studies.search.stages import SEARCH_RESULT_VERSION, SearchPlan
from chainchaos.studies.study import runs as study_runs
from chainchaos.studies.study.runs import scene_name
from chainchaos.studies.study.spec import kept_group_path, load_study, study_names
from chainchaos.workflow.tasks.chain import selection_criteria
from chainchaos.workflow.tasks.figures import figure_outputs as figure_files

RESULTS = config["results"]
SCENES = panels.scenes()
FIGURES = sorted(panels.LAYOUTS)


def result(*parts):
    return "/".join([RESULTS, *parts])


def kept_file(path, settings, version, remake_rule, keys=None):
    """The kept file `path` when it exists and may stand in for its computation (its settings and
    result version equal this run's, chainchaos.output.kept), else None; a kept file that is not
    used says why in one line on stderr. A file that cannot be read, or records no settings, stops
    the run with one line (KeptFileError) saying how to restore or remake it."""
    if not path or not os.path.exists(path):
        return None
    remake = f"snakemake --cores 2 {remake_rule}"
    why = kept.why_not_usable(path, settings, version, remake, keys)
    if why is None:
        return path
    print(f"{why}; not used, computed at the configured scale", file=sys.stderr)
    return None


def log_file(rule_name, stem="run"):
    return result("logs", rule_name, f"{stem}.log")


def benchmark_file(rule_name, stem="run"):
    return result("benchmarks", rule_name, f"{stem}.tsv")


# Every scene as the config runs it (built once: the simulate_scenes jobs take these objects).
SCENE_PARAMETERS = {
    name: scene_parameters(config, scene, name, panels.scene_observables(name))
    for name, scene in SCENES.items()
}
# Scenes that share their integration settings run together, as many as the SIMD width of this
# machine's batch engine (chainchaos.engine.simd.LANES), a few left over each on its own (the
# single engine) unless scene_batches.split_remainder is false; results do not depend on the
# grouping.
SCENE_BATCHES = scene_batches(
    SCENE_PARAMETERS,
    LANES,
    SERIAL_REMAINDER if config["scene_batches"]["split_remainder"] else 0,
)
SCENE_BATCH = {name: batch for batch, names in SCENE_BATCHES.items() for name in names}


def scene_file(scene_name):
    return result("scenes", f"{scene_name}.nc")


def panel_inputs(panel_id):
    """Files a panel is drawn from."""
    panel = panels.PANELS[panel_id]
    files = {s.name: scene_file(s.name) for s in panel.scenes}
    if panel.kind == "ensemble_participation":
        files["ensemble"] = result("ensemble", "participation_stats.nc")
    if panel.kind == "chain_spectrum":
        files["chain"] = result("chain", "chain.nc")
    return files


def figure_inputs(number):
    files = {}
    for panel_id in panels.panels_of_figure(number):
        files.update(panel_inputs(panel_id))
    return files


def figure_outputs(number):
    """The files figure `number`'s job draws: each panel's PDF and PNG and the composite's
    (chainchaos.workflow.tasks.figures.figure_outputs). Every PNG is in the report with its
    labels and its own caption, workflow/report/figures/<name>.rst (report_captions)."""
    outputs = {}
    for key, name in figure_files(number).items():
        path, stem = result("figures", name), Path(name).stem
        if key.startswith("png"):
            panel_id = key.partition("_")[2]
            path = report(
                path,
                caption=f"../report/figures/{stem}.rst",
                category=REPORT_CATEGORIES["figures"],
                subcategory=figure_subcategory(number),
                labels=panel_labels(panel_id) if panel_id else figure_labels(number),
            )
        outputs[key] = path
    return outputs


# The categories of the HTML report (snakemake --report; captions in workflow/report/, whose
# workflow.rst links to them by name).
REPORT_CATEGORIES = {
    "run": "This run",
    "figures": "Paper figures",
    "claims": "Claims",
    "scan": "Energy scan and disorder statistics",
    "search": "Realization search",
    "numerics": "Numerical accuracy",
    "indicators": "Chaos indicators",
    "studies": "Studies",
}


PANEL_TARGETS = [
    result("figures", f"fig{p}.{ext}") for p in sorted(panels.PANELS) for ext in ("pdf", "png")
]
FIGURE_TARGETS = [result("figures", f"fig{n}.{ext}") for n in FIGURES for ext in ("pdf", "png")]
ALL_TARGETS = PANEL_TARGETS + FIGURE_TARGETS


# ---- cluster runtimes (resources: runtime, minutes; profiles/slurm/) --------------------------


def cluster_runtime(orbits, t_final, dt):
    """Minutes a job of `orbits` orbits to `t_final` at step `dt` may take: steps x the measured
    cost per step (scan.us_per_step), x3 and + 10 min for sampling, start-up and a busy node."""
    seconds = orbits * (t_final / dt) * config["scan"].get("us_per_step", 1.0) * 1e-6
    return int(math.ceil(3 * seconds / 60)) + 10


# ---- chaos indicators (workflow/rules/indicators.smk) -----------------------------------------

SPECTRA_FILES = {
    f"spectrum_{name}": result("indicators", f"spectrum_{name}.nc")
    for name in config["indicators"]["spectra"]["scenes"]
}


# ---- energy scan and disorder statistics (workflow/rules/scan.smk) -----------------------------

SCAN = config["scan"]


def scan_params(kind):
    """The part of the scan block a kind's jobs depend on: a change elsewhere reruns nothing here.
    A kind that extends another (disorder_full) gets the other's block with its own keys."""
    base, scan = scan_runs.scan_config(kind, SCAN)
    return {"settings": SCAN.get("settings", {}), base: scan[base]}


# The full disorder statistics kept in the repository (`snakemake disorder_full` writes them):
# when the file exists and its settings (those disorder_full would run with) and result version
# are this run's, `all` takes its disorder statistics from it and runs no disorder group.
DISORDER_ARCHIVE = SCAN["disorder"].get("archive") or None
DISORDER_SETTINGS = scan_runs.disorder_settings(scan_params("disorder_full"), config["chain"]["N"])
USED_DISORDER_ARCHIVE = kept_file(
    DISORDER_ARCHIVE,
    DISORDER_SETTINGS,
    scan_runs.DISORDER_RESULT_VERSION,
    "disorder_full",
)


def disorder_inputs():
    if USED_DISORDER_ARCHIVE:
        return {"archive": USED_DISORDER_ARCHIVE}
    return {"groups": study_group_files("disorder")}


# ---- the realization search and the ensemble verdicts (workflow/rules/search.smk) --------------
# Two searches share the rules: `search`, the one `all` runs (pinned to the archived full search's
# chain when search.archive names an existing file whose settings are this run's), and
# `search_full`, whose result `snakemake search_full` writes to search.archive.

SEARCH_ARCHIVE = config["search"].get("archive") or None
# Keys of the search block that are not the search's plan.
SEARCH_WORKFLOW_KEYS = ("archive", "reuse_archive_chain")
# A scale overlay that only shortens runs (search.reuse_archive_chain) takes the archive's chosen
# chain when the chain and its selection match; otherwise every setting of the full search must.
SEARCH_ARCHIVE_KEYS = ("chain",) if config["search"].get("reuse_archive_chain") else None


def search_archive():
    """The archived full search when the config names one, it exists and its settings (all of
    them, or its chain's with search.reuse_archive_chain) and result version are this run's,
    else None."""
    return USED_SEARCH_ARCHIVE


def archive_pins():
    """The archived full search when `all` pins its choice (it exists and no seed is pinned
    explicitly), else None."""
    return search_archive() if config["search"].get("pinned_seed") is None else None


def search_block(name):
    """The config of a search: block `search` (its seed pinned to the archive's choice when it
    pins none), or block `search_full` with the orbit settings of `search`."""
    if name == "search_full":
        return {**config["search_full"], "settings": config["search"]["settings"]}
    block = {k: v for k, v in config["search"].items() if k not in SEARCH_WORKFLOW_KEYS}
    if archive_pins():
        block["pinned_seed"] = ARCHIVE_CHOSEN_SEED
    return block


def chosen_search():
    """The search file the chosen chain is read from: the archived full search when `all` pins
    its choice (the chain is then known before any job runs, and the pinned re-score runs beside
    the rest), else this run's search."""
    return archive_pins() or result("search", "search.nc")


def search_chain(name):
    """The chain block of a search: the full search scans search_full.n_seeds seeds."""
    if name != "search_full":
        return config["chain"]
    selection = {**config["chain"]["selection"], "n_seeds": config["search_full"]["n_seeds"]}
    return {**config["chain"], "selection": selection}


def search_selection(name):
    return selection_criteria({"chain": search_chain(name)})


def search_params(name):
    return {
        "search": search_block(name),
        "chain": search_chain(name),
        "claims": config.get("claims", {}),
        "site": config["simulation"]["excited_site"],
    }


# The settings the full search would run with: the key of the archive `all` may take it from.
USED_SEARCH_ARCHIVE = kept_file(
    SEARCH_ARCHIVE,
    archive.search_settings(search_params("search_full")),
    SEARCH_RESULT_VERSION,
    "search_full",
    SEARCH_ARCHIVE_KEYS,
)
# The seed of the archive's chosen chain, read once, when `all` pins it (search_block).
ARCHIVE_CHOSEN_SEED = archive.chosen_seed(archive_pins()) if archive_pins() else None


SEARCH_PLANS = {
    name: SearchPlan.from_config(search_block(name)) for name in ("search", "search_full")
}


def search_param(key):
    """A parameter of the search named by the rule's `search` wildcard."""
    return lambda wildcards: search_params(wildcards.search)[key]


def search_seed_files(wildcards):
    plan = SEARCH_PLANS[wildcards.search]
    n = plan.n_seed_jobs(search_selection(wildcards.search))
    return [result(wildcards.search, "seeds", f"{k:03d}.nc") for k in range(n)]


def _n_candidates(name):
    """Stage 0's count of candidates (read once the checkpoint search_candidates has run)."""
    with xr.open_dataset(checkpoints.search_candidates.get(search=name).output.result) as found:
        return found.sizes["candidate"]


def search_filter_files(wildcards):
    plan = SEARCH_PLANS[wildcards.search]
    if plan.pinned:
        return []
    n = plan.n_filter_jobs(_n_candidates(wildcards.search))
    return [result(wildcards.search, "filter", f"{g:03d}.nc") for g in range(n)]


def search_score_files(wildcards):
    plan = SEARCH_PLANS[wildcards.search]
    n = plan.n_score_jobs(1 if plan.pinned else _n_candidates(wildcards.search))
    return [result(wildcards.search, "score", f"{k:03d}.nc") for k in range(n)]


def rejudge_params():
    """The full search's parameters, its archive and the statements config `rejudge` names."""
    return {
        **search_params("search_full"),
        "archive": SEARCH_ARCHIVE,
        "rejudge": list(config.get("rejudge") or []),
    }


def _kept_candidates():
    """How many candidates the kept full search holds (0 when there is none)."""
    if not SEARCH_ARCHIVE or not os.path.exists(SEARCH_ARCHIVE):
        return 0
    with xr.open_dataset(SEARCH_ARCHIVE) as ds:
        return ds.sizes["candidate"]


# The re-judging's stage files are kept beside the archive (committed in chunks: it may take more
# than a session), and so are its jobs' benchmark files, from which the archive states its cost.
REJUDGE_DIR = str(Path(SEARCH_ARCHIVE or "data/search/search_full.nc").parent / "rejudge")


def rejudge_file(*parts):
    return str(Path(REJUDGE_DIR, *parts))


def rejudge_filter_files():
    if not config.get("rejudge"):
        return []
    plan = rejudge.filter_plan(SEARCH_PLANS["search_full"], rejudge.check_ids(config["rejudge"]))
    n = plan.n_filter_jobs(_kept_candidates())
    return [rejudge_file("filter", f"{g:03d}.nc") for g in range(n)]


def rejudge_score_files():
    n = SEARCH_PLANS["search_full"].n_score_jobs(_kept_candidates())
    return [rejudge_file("score", f"{k:03d}.nc") for k in range(n)]


def search_runtime(stage):
    """Minutes a stage-1 ("filter") or stage-2 ("score") job of a search may take."""

    def minutes(wildcards):
        plan = SEARCH_PLANS[wildcards.search]
        if stage == "filter":
            orbits, t_final = plan.candidates_per_job, plan.filter_t_final
        else:
            orbits, t_final = plan.lanes, config["search"]["settings"]["t_final"]
        return orbit_runtime(len(statements.statement_scenes()) * orbits, t_final)

    return minutes


def orbit_runtime(orbits_per_job, t_final):
    """Minutes a job of orbits at the search's step may take."""
    return cluster_runtime(
        orbits_per_job, float(t_final), float(config["search"]["settings"]["dt"])
    )


def search_population():
    """The search whose candidates the manuscript counts: the archived full search when `all`
    uses it, else this run's."""
    return search_archive() or result("search", "search.nc")


# ---- claims and manuscript (workflow/rules/manuscript.smk) -------------------------------------


def manuscript_numerics():
    """The numerics inputs of the manuscript (NUMERICS_FOR_MANUSCRIPT), or {} when the switch
    config manuscript.numerics is off or workflow/rules/numerics.smk is not part of the workflow."""
    wanted = config.get("manuscript", {}).get("numerics", True)
    return dict(NUMERICS_FOR_MANUSCRIPT) if wanted and "NUMERICS_TARGETS" in globals() else {}


# The code that measures and writes the claims (an input of evaluate_claims).
CLAIMS_CODE = [
    *sorted(glob.glob("src/chainchaos/paper/claims/*.py")),
    "src/chainchaos/output/formatting.py",
    "src/chainchaos/workflow/tasks/manuscript.py",
]


def claims_inputs(wildcards=None):
    files = {
        "code": CLAIMS_CODE,  # a changed criterion or text in the code reruns the claims
        "chain": result("chain", "chain.nc"),
        "ensemble": result("ensemble", "participation_stats.nc"),
        "energy_scan": result("scan", "energy_scan.nc"),  # the threshold statements
        "disorder": result("scan", "disorder_statistics.nc"),  # numbers quoted in the text
        "search": result("search", "search.nc"),
        "search_population": search_population(),
    }
    files.update({f"verdict_{name}": path for name, path in VERDICT_FILES.items()})
    files.update(SPECTRA_FILES)
    files.update({name: scene_file(name) for name in sorted(SCENES)})
    return files


def beyond_entries():
    """config manuscript.beyond as {study: figures shown}: a name shows every figure of its study,
    a mapping {name: [figures]} only those."""
    entries = {}
    for item in config.get("manuscript", {}).get("beyond", []):
        for name, figures in (item.items() if isinstance(item, dict) else [(item, None)]):
            known = study_figure_names(name)
            unknown = sorted(set(figures or ()) - set(known))
            if unknown:
                raise ValueError(
                    f"config manuscript.beyond: study {name} has no figure {', '.join(unknown)}; its figures: {known}"
                )
            if name in entries:
                raise ValueError(f"config manuscript.beyond: study {name} is named twice")
            entries[name] = known if figures is None else list(figures)
    return entries


def beyond_studies():
    """The studies of config manuscript.beyond that are kept in full (every group under
    data/studies/ with the study's settings); one line on stderr for each that is not."""
    shown = []
    for name in BEYOND_ENTRIES:
        groups = range(study_of(name).n_groups)
        missing = [g for g in groups if study_group_file(name, g) != kept_group_file(name, g)]
        if missing:
            print(
                f"study {name}: {len(missing)} of {len(groups)} groups not kept; the section Beyond the paper "
                f"leaves it out (snakemake --cores 2 keep_study --config study={name})",
                file=sys.stderr,
            )
        else:
            shown.append(name)
    return shown


def study_figure_names(name):
    spec = study_of(name).spec
    return [*spec["figures"], *(["comparison"] if spec["compare_with"] else [])]


def manuscript_beyond():
    """The inputs of the section Beyond the paper: its generated body and the shown studies' figures."""
    if not BEYOND_STUDIES:
        return {}
    files = {"beyond_body": result("tables", "beyond_the_paper.tex")}
    for name in BEYOND_STUDIES:
        for figure in BEYOND_ENTRIES[name]:
            files[f"beyond_{beyond.figure_key(name, figure)}"] = result(
                "studies", name, "figures", f"{figure}.pdf"
            )
    return files


def manuscript_inputs(wildcards=None):
    files = {
        "tex": "manuscript/ms.tex",
        **CLAIMS_OUTPUTS,
    }
    files.update({f"fig{n}": result("figures", f"fig{n}.pdf") for n in FIGURES})
    files.update(
        {
            "figscan": result("figures", "energy_scan.pdf"),
            "figdisorder": result("figures", "disorder_statistics.pdf"),
            "thresholds": result("scan", "thresholds.tex"),
            "figsearch": result("figures", "search.pdf"),
            "figsearchjoint": result("figures", "search_joint.pdf"),
            "figspectra": result("figures", "lyapunov_spectra.pdf"),
        }
    )
    files.update({f"numerics_{key}": path for key, path in manuscript_numerics().items()})
    files.update(manuscript_beyond())
    return files


# ---- studies of one's own (workflow/rules/study.smk) -------------------------------------------


def study_name(given):
    """The name of the study config `study` gives: a name of studies/, or the stem of a file."""
    return Path(given).stem if str(given).endswith((".yaml", ".yml")) else given


# The scans are studies too (chainchaos.studies.scan.runs.scan_study), named by their kind.
SCAN_STUDIES = ("energy_scan", "disorder", "disorder_full")


@functools.cache
def study_of(name):
    """The study of studies/<name>.yaml (or of the file config `study` names, whose stem is
    ``name``; or the scan kind ``name``, from config block `scan`), read and checked once."""
    if name in SCAN_STUDIES:
        chain_file = result("chain", "chain.nc")
        return load_study(scan_runs.scan_study(name, SCAN, config["chain"]["N"], chain_file))
    given = str(config.get("study") or "")
    return load_study(given if study_name(given) == name and given != name else name)


def study_spec(name):
    """The keys of a study as its jobs see them: a changed key reruns them."""
    return {"name": name, **study_of(name).spec}


def study_group_spec(name):
    """The keys of a study that its groups' numbers depend on (with the title their files state):
    a changed figure, comparison or law reruns no group."""
    study = study_of(name)
    return {"name": name, "title": study.spec["title"], **study_runs.numbers_spec(study)}


def kept_group_file(name, group):
    """Where a study's group is kept in the repository (`snakemake keep_study` writes it)."""
    return str(kept_group_path(name, group, config["kept_studies"]))


@functools.cache
def study_group_file(name, group):
    """A group of a study: its kept file when that exists and was made with this study's
    settings and code (a finished group is never rerun), else the file study_group computes."""
    if name not in SCAN_STUDIES:
        study = study_of(name)
        used = kept_file(
            kept_group_file(name, group),
            study_runs.group_settings(study, group),
            study_runs.STUDY_RESULT_VERSION,
            f"keep_study --config study={name}",
        )
        if used:
            return used
    return result("studies", name, "groups", f"{group:04d}.nc")


def study_group_files(name):
    return [study_group_file(name, g) for g in range(study_of(name).n_groups)]


def keep_study_targets(name):
    """The kept files of every group of a study; a kept group made with other settings is not
    overwritten silently: delete the study's kept directory to remake it."""
    if not name:
        raise ValueError(
            f"the target keep_study needs a study: --config study=<name>, one of {study_names()}"
        )
    name = study_name(name)
    stale = [
        kept_group_file(name, g)
        for g in range(study_of(name).n_groups)
        if os.path.exists(kept_group_file(name, g))
        and study_group_file(name, g) != kept_group_file(name, g)
    ]
    if stale:
        raise ValueError(
            f"kept groups of study {name} made with other settings: {', '.join(stale)}; "
            f"delete {Path(config['kept_studies']) / name} to remake them, or restore the study file they were made with"
        )
    # a group kept already is done: asking for it again would rerun its job when a key that does
    # not change its numbers (figures, laws, ...) changed
    return [
        result("studies", name, "kept", f"{g:04d}.txt")
        for g in range(study_of(name).n_groups)
        if study_group_file(name, g) != kept_group_file(name, g)
    ]


def kernel_flags(models=None):
    """The flags of compile_kernels for ``models`` (default: the paper's): a job that integrates
    waits for its models' kernels only."""
    return [
        result("kernels", f"{model}.txt")
        for model in (panels.models() if models is None else models)
    ]


def earlier_kernel_flags(wildcards):
    """The flags of the paper's models before ``wildcards.model`` (panels.models() order): its
    compile_kernels job loads the kernels they share (the eigen solver, the chaos indicators')
    from the cache instead of compiling them again, while the other core runs jobs that need no
    kernel."""
    models = panels.models()
    return kernel_flags(
        models[: models.index(wildcards.model)] if wildcards.model in models else []
    )


def study_group_inputs(wildcards):
    files = {"kernels": kernel_flags(study_of(wildcards.study).models)}
    chain_file = study_of(wildcards.study).spec["lattice"]["chain_file"]
    if chain_file:
        files["chain"] = chain_file
    return files


def study_runtime(name):
    """Minutes a group job of a study may take (cluster_runtime at its size)."""
    study = study_of(name)
    settings = study.settings
    orbits = (
        study.per_job * study.lanes * (1 + 0.4 * (settings.gali_order - 1) * settings.alignment)
    )
    N = study.spec["lattice"].get("N") or 40  # a chain file may not exist yet
    return cluster_runtime(orbits * max(1.0, N / 40), settings.t_final, settings.dt)


def figure_studies():
    """The studies whose figures a run can ask for: those the manuscript shows and the one config
    `study` names. Only the studies a run reads are read at parse time: a half-written file in
    studies/ stops no other run."""
    names = set(BEYOND_STUDIES)
    if config.get("study"):
        names.add(study_name(config["study"]))
    return [name for name in sorted(names) if asked_figures(name)]


def asked_figures(name):
    """The figures of study `name` a run asks for, in the study's order: every one of the study
    config `study` names, those config manuscript.beyond shows of a study the manuscript shows."""
    asked = set(BEYOND_ENTRIES[name]) if name in BEYOND_STUDIES else set()
    if config.get("study") and study_name(config["study"]) == name:
        asked.update(study_figure_names(name))
    return [figure for figure in study_figure_names(name) if figure in asked]


def rule_key(name):
    """``name`` as a part of a rule's name (a study may be named ``my-study.v2``)."""
    return re.sub(r"\W", "_", name)


def study_figure_inputs(name):
    """The statistics a study's asked figures read: its own, then, for its comparison, those of
    the studies it compares with."""
    compared = study_of(name).spec["compare_with"] if "comparison" in asked_figures(name) else []
    names = [name, *compared]
    return {n: result("studies", n, "statistics.nc") for n in names}


def study_figure_outputs(name):
    """Each figure of a study the run asks for as PDF and PNG, the PNG in the report (category
    Studies)."""
    outputs = {}
    for figure in asked_figures(name):
        path = result("studies", name, "figures", figure)
        caption = "study_comparison" if figure == "comparison" else "study"
        outputs[f"{figure}_pdf"] = f"{path}.pdf"
        outputs[f"{figure}_png"] = report(
            f"{path}.png",
            caption=f"../report/{caption}.rst",
            category=REPORT_CATEGORIES["studies"],
            subcategory=name,
            labels={"study": name, "figure": figure},
        )
    return outputs


def study_targets(name):
    """Every product of a study: its NetCDF files, its figures and the comparison it asks for."""
    if not name:
        raise ValueError(
            f"the target study needs a study: --config study=<name>, one of {study_names()}"
        )
    name = study_name(name)
    study = study_of(name)
    files = [
        result("studies", name, f"{scene_name(m, e)}.nc")
        for m in study.models
        for e in study.energies
    ]
    files += [result("studies", name, "statistics.nc"), result("studies", name, "laws.nc")]
    files += [
        result("studies", name, "figures", f"{f}.{ext}")
        for f in study_figure_names(name)
        for ext in ("pdf", "png")
    ]
    return files


BEYOND_ENTRIES = beyond_entries()
BEYOND_STUDIES = beyond_studies()


# A study named on the command line is read and checked before anything is planned: a wrong key
# stops the run with one line per key, as a wrong config key does.
if config.get("study"):
    study_of(study_name(config["study"]))
