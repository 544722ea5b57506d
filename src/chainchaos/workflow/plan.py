"""What a run of the workflow asks for and how its work is cut into jobs.

The rule files (``workflow/rules/*.smk``) hold paths and config lookups; every decision they need
is a function here, of explicit arguments (the config, or a part of it), so that it can be tested
without Snakemake:

- which kept results (``data/``) a run uses, from the config alone (:func:`archive_path`; the
  studies of config ``use_kept_studies``), and what the jobs that check them compare them with
  (:func:`archive_check`): no function here opens a file while the workflow is parsed (a search
  stage's study reads the stage before it, a checkpoint's output, once it ran);
- how each scene of the paper runs (:func:`scene_run`), what the paper's targets are
  (:func:`paper_targets`), which files a panel or a figure reads (:func:`panel_inputs`,
  :func:`figure_inputs`);
- the settings each kind of job gets (:func:`scan_params`, :func:`search_params`) and how many
  jobs a search stage has (:func:`search_plans`);
- which studies and figures a run asks for (:func:`beyond_entries`, :func:`study_targets`), and
  what a cluster job may take (:func:`cluster_minutes`).
"""

import math
from dataclasses import asdict
from pathlib import Path

from chainchaos.paper import panels
from chainchaos.run.scenes import scene_parameters

#: Kept results a run can make when config ``keep`` names them (a study's name keeps its groups).
KEPT_PRODUCTS = ("search_full", "search_rejudge", "disorder_full")


# ---- kept results: chosen in the config, checked by jobs ---------------------------------------

#: The archives a config may choose to use, by name: the config key that names the file (empty:
#: computed at the configured scale).
ARCHIVE_KEYS = {"search_full": "search.archive", "disorder_full": "scan.disorder.archive"}


def remake_command(name: str) -> str:
    """The command that remakes the kept result ``name`` (an archive or a study)."""
    return f"snakemake --cores 2 keep --config keep={name}"


def kept_compute(name: str) -> str:
    """How a run computes the kept result ``name`` instead of using it: the config key to change."""
    if name == "search_full":
        return "empty config search.archive and search.pinned_seed to search at this run's scale"
    if name in ARCHIVE_KEYS:
        return f"empty config {ARCHIVE_KEYS[name]} to compute it at this run's scale"
    return f"take {name} out of config use_kept_studies to compute it in this run"


def archive_path(name: str, config: dict) -> str | None:
    """The kept file of archive ``name`` (:data:`ARCHIVE_KEYS`) that the config chose to use, or
    None: computed at the configured scale. Read from the config alone (no file is looked at)."""
    block = config
    for key in ARCHIVE_KEYS[name].split("."):
        block = block.get(key) or {}
    return str(block) if block else None


def archive_check(name: str, config: dict) -> dict:
    """What the job that checks the used archive ``name`` compares it with
    (``records.kept.check_kept``): the settings this run would compute it with, the result
    version, the keys compared (the full search with ``search.reuse_archive_chain``: its chain's
    only), the attributes it must hold (``{name: [config key, value]}``; the full search: the
    chosen seed that config ``search.pinned_seed`` names, which the plan runs on), and the two ways out of a mismatch."""
    compute = kept_compute(name)
    if name == "search_full":
        from chainchaos.studies.search.archive import search_settings
        from chainchaos.studies.search.stages import SEARCH_RESULT_VERSION

        return {"settings": search_settings(search_params("search_full", config)), "version": SEARCH_RESULT_VERSION,
                "keys": ["chain"] if config["search"].get("reuse_archive_chain") else None,
                "attrs": {"chosen_seed": ["search.pinned_seed", config["search"].get("pinned_seed")]},
                "remake": remake_command(name), "compute": compute}
    from chainchaos.studies.scan.runs import DISORDER_RESULT_VERSION, disorder_settings

    scan = config["scan"]
    return {"settings": disorder_settings(scan_params("disorder_full", scan), config["chain"]["N"]),
            "version": DISORDER_RESULT_VERSION, "keys": None, "attrs": {},
            "remake": remake_command(name), "compute": compute}


def kept_study_check(name: str, kept_root) -> dict:
    """The two ways out when a kept group of study ``name`` does not match its study file."""
    return {"remake": f"rm -r {Path(kept_root) / name} && {remake_command(name)}", "compute": kept_compute(name)}


# ---- the paper's scenes and figures --------------------------------------------------------------


def scene_run(config: dict, name: str) -> dict:
    """Scene ``name`` of the paper as the config runs it, as its job's params: the settings of
    every scene (config ``simulation``), its own overrides (config ``scenes.<name>``) and the
    observables its panels use, validated (``run.scenes.SceneParameters``) and given as the
    dataclass's fields, built-in types that Snakemake records, so that a changed setting reruns
    the scene. One job per scene (rule simulate_scene).

    Parameters
    ----------
    config : dict
        The workflow's config (blocks ``simulation`` and ``scenes``).
    name : str
        A scene of ``panels.scenes()``.

    Returns
    -------
    dict
        The keywords of its ``SceneParameters``.
    """
    scene = scene_parameters(config["simulation"], config.get("scenes", {}).get(name, {}),
                             panels.scenes()[name], name, panels.scene_observables(name))
    return asdict(scene)


def paper_targets(results: str) -> list[str]:
    """Every panel's and every figure's PDF and PNG under ``results``/figures."""
    stems = [f"fig{p}" for p in sorted(panels.PANELS)] + [f"fig{n}" for n in sorted(panels.LAYOUTS)]
    return [f"{results}/figures/{stem}.{ext}" for stem in stems for ext in ("pdf", "png")]


def panel_inputs(panel_id: str, results: str) -> dict[str, str]:
    """The files panel ``panel_id`` is drawn from: its scenes, and the ensemble statistics or
    the chain where it shows them."""
    panel = panels.PANELS[panel_id]
    files = {s.name: f"{results}/scenes/{s.name}.nc" for s in panel.scenes}
    if panel.kind == "ensemble_participation":
        files["ensemble"] = f"{results}/ensemble/participation_stats.nc"
    if panel.kind == "chain_spectrum":
        files["chain"] = f"{results}/chain/chain.nc"
    return files


def figure_inputs(number: int, results: str) -> dict[str, str]:
    """The files figure ``number``'s panels are drawn from (:func:`panel_inputs` of each)."""
    files = {}
    for panel_id in panels.panels_of_figure(number):
        files.update(panel_inputs(panel_id, results))
    return files


def cluster_minutes(orbits: float, t_final: float, dt: float, us_per_step: float = 1.0) -> int:
    """Minutes a cluster job of ``orbits`` orbits to ``t_final`` at step ``dt`` may take: the
    steps times ``us_per_step`` (microseconds, config ``scan.us_per_step``), three times over
    and ten minutes more for sampling, start-up and a busy node."""
    seconds = orbits * (float(t_final) / float(dt)) * us_per_step * 1e-6
    return math.ceil(3 * seconds / 60) + 10


# ---- scans and the search -------------------------------------------------------------------


def scan_params(kind: str, scan: dict) -> dict:
    """The part of the config block ``scan`` that a kind's jobs depend on (a change elsewhere
    reruns nothing there); a kind that extends another (disorder_full) gets the other's block
    updated with its own keys."""
    from chainchaos.studies.scan.runs import scan_config

    base, block = scan_config(kind, scan)
    return {"settings": scan.get("settings", {}), base: block[base]}


#: Keys of the config block ``search`` that say where its archive is, not what it searches.
SEARCH_WORKFLOW_KEYS = ("archive", "reuse_archive_chain")


def search_chain(name: str, config: dict) -> dict:
    """The chain block of search ``name``: the full search scans ``search_full.n_seeds`` seeds."""
    if name != "search_full":
        return config["chain"]
    selection = {**config["chain"]["selection"], "n_seeds": config["search_full"]["n_seeds"]}
    return {**config["chain"], "selection": selection}


def search_params(name: str, config: dict) -> dict:
    """The parameters of search ``name`` (``search`` or ``search_full``): its block (the full
    search's with the orbit settings of ``search``), chain, claims and excited site. With
    ``search.pinned_seed`` (the kept full search's chosen seed when config ``search.archive``
    names it), ``search`` re-scores that seed's chain instead of searching."""
    if name == "search_full":
        block = {**config["search_full"], "settings": config["search"]["settings"]}
    else:
        block = {k: v for k, v in config["search"].items() if k not in SEARCH_WORKFLOW_KEYS}
    return {"search": block, "chain": search_chain(name, config),
            "claims": config.get("claims", {}), "site": config["simulation"]["excited_site"]}


def search_plans(config: dict):
    """The :class:`~chainchaos.studies.search.stages.SearchPlan` of each search."""
    from chainchaos.studies.search.stages import SearchPlan

    return {name: SearchPlan.from_config(search_params(name, config)["search"]) for name in ("search", "search_full")}


# ---- studies --------------------------------------------------------------------------------


def study_name(given) -> str:
    """The name of the study config ``study`` gives: a name of studies/, or a file's stem."""
    return Path(given).stem if str(given).endswith((".yaml", ".yml")) else str(given)


def search_studies(search: str, stage: str) -> list[str]:
    """The studies of a stage of search ``search``, one per model of the statement scenes."""
    from chainchaos.studies.search.stages import search_models, study_name

    return [study_name(search, stage, model) for model in search_models()]


def _search_stage_keys(search: str, stage: str, model: str, config: dict) -> dict:
    """The keys of a search stage's study: its chains are the candidates (``filter``), or the
    survivors by rank (``score``), read from the stage before (``<results>/<search>/candidates.nc``,
    ``filter.nc``: call it once those exist); with a pinned seed, that seed's chain."""
    import xarray as xr

    from chainchaos.studies.search.stages import stage_studies
    from chainchaos.workflow.tasks.search import search_parts

    selection, search_plan, settings, criteria, site = search_parts(search_params(search, config))
    root = Path(config["results"], search)
    if search_plan.pinned:
        seeds = [search_plan.pinned_seed]
    else:
        seeds = xr.load_dataset(root / "candidates.nc")["seed"].values
        if stage == "score":
            seeds = seeds[xr.load_dataset(root / "filter.nc")["survivor"].values]
    return stage_studies(search, stage, selection, search_plan, settings, criteria, site, seeds)[model]


def config_studies(config: dict) -> dict:
    """The studies the config itself defines, by name, each as a function that makes its keys
    (``studies/README.md``): the scans (config ``scan``: ``energy_scan``, ``disorder``,
    ``disorder_full``), the ensemble of each model's statement scenes on the chosen chain (config
    ``verdicts``: ``verdicts_<model>``) and the stages of each search (config ``search``,
    ``search_full``: ``<search>-<stage>-<model>``). A study of a search's stage reads the stage
    before it (a checkpoint's output): call its function once that ran."""
    from functools import partial

    from chainchaos.paper.ensembles import verdict_study, verdict_study_name
    from chainchaos.paper.statements import statement_scenes_by_model
    from chainchaos.studies.scan.runs import scan_study
    from chainchaos.studies.search.stages import STUDY_STAGES, search_models
    from chainchaos.studies.search.stages import study_name as stage_name

    chain_file = f"{config['results']}/chain/chain.nc"
    studies = {kind: partial(scan_study, kind, config["scan"], config["chain"]["N"], chain_file)
               for kind in ("energy_scan", "disorder", "disorder_full")}
    studies.update({verdict_study_name(model): partial(verdict_study, model, config["verdicts"], config.get("claims"),
                                                       config["simulation"]["excited_site"], chain_file)
                    for model in statement_scenes_by_model()})
    studies.update({stage_name(search, stage, model): partial(_search_stage_keys, search, stage, model, config)
                    for search in ("search", "search_full") for stage in STUDY_STAGES for model in search_models()})
    return studies


def load_run_study(name: str, config: dict):
    """The study ``name`` as this run reads it: one the config defines (:func:`config_studies`),
    the file config ``study`` names (whose stem is ``name``), or ``studies/<name>.yaml``. Its keys
    are checked, but no chain file it names is read: its jobs read it (while the workflow is
    parsed, it may be absent, or made by an earlier run)."""
    from chainchaos.studies.study.spec import load_study

    defined = config_studies(config)
    if name in defined:
        return load_study(defined[name](), read_files=False)
    given = str(config.get("study") or "")
    return load_study(given if study_name(given) == name and given != name else name, read_files=False)


def study_figure_names(study) -> list[str]:
    """The figures a study draws: those of its key ``figures``, and ``comparison`` when it
    compares itself with other studies."""
    return [*study.spec["figures"], *(["comparison"] if study.spec["compare_with"] else [])]


def beyond_entries(beyond: list, figure_names) -> dict[str, list[str]]:
    """Config ``manuscript.beyond`` as ``{study: figures shown}``: a name shows every figure of its
    study, a mapping ``{name: [figures]}`` only those. ``figure_names(name)``: a study's figures.

    Raises
    ------
    ValueError
        For a figure the study does not draw, or a study named twice.
    """
    entries = {}
    for item in beyond or []:
        for name, figures in (item.items() if isinstance(item, dict) else [(item, None)]):
            known = figure_names(name)
            unknown = sorted(set(figures or ()) - set(known))
            if unknown:
                raise ValueError(f"config manuscript.beyond: study {name} has no figure {', '.join(unknown)}; "
                                 f"its figures: {known}")
            if name in entries:
                raise ValueError(f"config manuscript.beyond: study {name} is named twice")
            entries[name] = known if figures is None else list(figures)
    return entries


def study_targets(study, results: str, figure_names: list[str]) -> list[str]:
    """Every product of a study: its file per model and energy, statistics, laws and figures."""
    from chainchaos.studies.study.runs import scene_name

    root = f"{results}/studies/{study.name}"
    files = [f"{root}/{scene_name(m, e)}.nc" for m in study.models for e in study.energies]
    files += [f"{root}/statistics.nc", f"{root}/laws.nc"]
    return files + [f"{root}/figures/{f}.{ext}" for f in figure_names for ext in ("pdf", "png")]


def study_minutes(study, us_per_step: float) -> int:
    """Minutes a group job of ``study`` may take on a cluster (:func:`cluster_minutes`)."""
    settings = study.settings
    orbits = study.per_job * study.lanes * (1 + 0.4 * (settings.gali_order - 1) * settings.alignment)
    N = study.spec["lattice"].get("N") or 40  # a chain file may not exist yet
    return cluster_minutes(orbits * max(1.0, N / 40), settings.t_final, settings.dt, us_per_step)


def kept_product(keep, study_names) -> str | None:
    """The kept result config ``keep`` asks this run to make: one of :data:`KEPT_PRODUCTS`, a
    study's name (its kept groups), or None.

    Raises
    ------
    ValueError
        Naming the value and what is allowed.
    """
    if keep in (None, ""):
        return None
    if keep in KEPT_PRODUCTS or keep in study_names:
        return str(keep)
    raise ValueError(f"config keep is {keep!r}: one of {', '.join(KEPT_PRODUCTS)} or a study of studies/ "
                     f"({', '.join(study_names)})")


def kept_targets(keep: str | None, config: dict, study=None) -> list[str]:
    """The files the target ``keep`` makes for config ``keep`` (:func:`kept_product`):
    an archive's path, or every kept group of the study ``study`` and its statistics, whose job
    checks every group against the study (a group kept before with other settings, which no run
    remakes, stops the run there, naming it).

    Raises
    ------
    ValueError
        When ``keep`` is empty, or names an archive whose config key is empty.
    """
    from chainchaos.studies.study.spec import kept_group_path

    if keep is None:
        raise ValueError(f"the target keep needs --config keep=<what>: {', '.join(KEPT_PRODUCTS)} or a study")
    if keep in KEPT_PRODUCTS:
        name = "search_full" if keep == "search_rejudge" else keep
        path = archive_path(name, config)
        if not path:
            raise ValueError(f"config {ARCHIVE_KEYS[name]} is empty: keep={keep} writes its result there (e.g. "
                             f"data/{'disorder/disorder_full' if name == 'disorder_full' else 'search/search_full'}.nc)")
        return [path]
    groups = [str(kept_group_path(keep, g, config["kept_studies"])) for g in range(study.n_groups)]
    return [*groups, f"{config['results']}/studies/{keep}/statistics.nc"]


def beyond_inputs(results: str, shown: dict) -> dict[str, str]:
    """The manuscript's inputs for the section Beyond the paper: its generated body and the figures
    it shows (``shown``: study -> figures), keyed as the manuscript task reads them."""
    from chainchaos.output.beyond import figure_key

    if not shown:
        return {}
    files = {"beyond_body": f"{results}/tables/beyond_the_paper.tex"}
    for name, figures in shown.items():
        files.update({f"beyond_{figure_key(name, f)}": f"{results}/studies/{name}/figures/{f}.pdf" for f in figures})
    return files


def own_models(study) -> list[list[str]]:
    """[reference, directory] of each model of one's own that ``study`` names (``module:NAME``,
    ``file.py:NAME``): what a job that only draws must load to know the model's label and colour."""
    model = study.spec["lattice"]["model"]
    return [[m, study.directory] for m in ([model] if isinstance(model, str) else model) if ":" in m]


def study_spec(study) -> dict:
    """The keys of a study as its jobs see them (a changed key reruns them)."""
    return {"name": study.name, "directory": study.directory, **study.spec}


def group_spec(study) -> dict:
    """The keys of a study its groups' numbers depend on, with the title their files state: a
    changed figure, comparison or law reruns no group."""
    from chainchaos.studies.study.runs import numbers_spec

    return {"name": study.name, "directory": study.directory, "title": study.spec["title"], **numbers_spec(study)}


def rejudge_files(config: dict, search_full_plan, n_candidates: int, stage: str) -> list[str]:
    """The stage files (``filter`` or ``score``) of re-judging the kept full search of
    ``n_candidates`` candidates for the statements config ``rejudge`` names, kept beside the
    archive (``<archive dir>/rejudge/<stage>/<k>.nc``)."""
    from chainchaos.studies.search import rejudge

    search_plan = search_full_plan
    if stage == "filter":
        search_plan = rejudge.filter_plan(search_plan, rejudge.check_ids(config.get("rejudge") or []))
    root = Path(config["search"]["archive"]).parent / "rejudge" / stage
    jobs = search_plan.n_filter_jobs(n_candidates) if stage == "filter" else search_plan.n_score_jobs(n_candidates)
    return [str(root / f"{k:03d}.nc") for k in range(jobs)]


def still_to_make(paths) -> str:
    """A wildcard constraint that matches the stems of those of ``paths`` that do not exist yet
    (``(?!)``, which matches nothing, when all exist).

    The rules that make kept files take it for the wildcard that numbers them: a file kept
    already then has no rule that makes it, so no run redoes it, whatever its checkout time says
    against the rule's script (Snakemake reruns a job whose output is older than its script)."""
    import re

    stems = [Path(p).stem for p in paths if not Path(p).exists()]
    return "|".join(re.escape(s) for s in stems) or "(?!)"
