"""Tasks of workflow/rules/search.smk: the realization search, its figure, and the ensemble verdicts
of the chosen chain."""

import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

from chainchaos.errors import require
from chainchaos.output import kept
from chainchaos.output.io import read_chain, write_netcdf
from chainchaos.output.provenance import provenance_attrs
from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.verdicts import verdict_dataset
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
from chainchaos.studies.search import archive
from chainchaos.studies.search import stages as search
from chainchaos.studies.search.selection import SelectionCriteria
from chainchaos.studies.search.stages import SEARCH_RESULT_VERSION, SearchPlan
from chainchaos.workflow.tasks.chain import selection_criteria


def _progress(label: str):
    start = time.perf_counter()

    def report(done, total):
        print(f"[{label}] {done}/{total} orbits, {time.perf_counter() - start:.1f} s", file=sys.stderr, flush=True)

    return report


def _plan(params: dict) -> tuple[SelectionCriteria, SearchPlan]:
    """The linear rule and the sizes of a search: all that stage 0 needs."""
    return selection_criteria(params), SearchPlan.from_config(params["search"])


def _search_parts(params: dict):
    settings = OrbitSettings.from_config(params["search"]["settings"])
    return (*_plan(params), settings, Criteria.from_config(params.get("claims")), int(params["site"]))


def _write_search_product(ds, params: dict, selection: SelectionCriteria, path) -> None:
    ds.attrs.update(provenance_attrs({"search": params["search"], "selection": vars(selection)}))
    write_netcdf(ds, path)


def _as_list(value) -> list:
    if value is None:
        return []
    return [value] if isinstance(value, str) else list(value)


def search_seeds(inputs, outputs, params, wildcards) -> None:
    """Stage 0 of the realization search for one chunk of seeds: the chains that pass the linear rule."""
    selection, plan = _plan(params)
    ds = search.seed_chunk(selection, plan, int(wildcards["chunk"]))
    print(f"{ds.sizes['candidate']} of the {ds.attrs['seeds_scanned']} seeds from {ds.attrs['first_seed']} "
          "pass the linear rule", file=sys.stderr)
    _write_search_product(ds, params, selection, outputs["result"])


def search_candidates(inputs, outputs, params, wildcards) -> None:
    """Stage 0 of the realization search: the candidates, by the linear rule (or the pinned seed)."""
    selection, plan = _plan(params)
    ds = search.candidates(selection, plan, [xr.load_dataset(p) for p in _as_list(inputs["seeds"])])
    print(f"{ds.attrs['n_qualifying']} of {selection.n_seeds} seeds pass the linear rule; "
          f"{ds.sizes['candidate']} candidates", file=sys.stderr)
    _write_search_product(ds, params, selection, outputs["result"])


def search_filter(inputs, outputs, params, wildcards) -> None:
    """Stage 1 of the realization search for one group of candidates."""
    selection, plan, settings, criteria, site = _search_parts(params)
    rows = search.candidate_rows(xr.load_dataset(inputs["candidates"]))
    group = int(wildcards["group"])
    ds = search.filter_group(selection, plan, settings, criteria, rows, group, site, _progress(f"filter {group}"))
    _write_search_product(ds, params, selection, outputs["result"])


def search_score(inputs, outputs, params, wildcards) -> None:
    """Stage 2 of the realization search for the survivor of the given rank."""
    selection, plan, settings, criteria, site = _search_parts(params)
    rows = search.candidate_rows(xr.load_dataset(inputs["candidates"]))
    filters = [xr.load_dataset(p) for p in _as_list(inputs.get("filters"))]
    rank = int(wildcards["rank"])
    candidate = int(search.survivors(filters, plan)[rank])
    print(f"survivor {rank}: candidate {candidate}", file=sys.stderr)
    ds = search.score_candidate(selection, plan, settings, criteria, rows, candidate, site,
                                _progress(f"score {rank}"))
    _write_search_product(ds, params, selection, outputs["result"])


def search_merge(inputs, outputs, params, wildcards) -> None:
    """The search's candidates, scores and choice as one file."""
    selection, plan, settings, criteria, _ = _search_parts(params)
    found = xr.load_dataset(inputs["candidates"])
    filters = [xr.load_dataset(p) for p in _as_list(inputs.get("filters"))]
    scores = [xr.load_dataset(p) for p in _as_list(inputs["scores"])]
    ds = search.merge(selection, plan, settings, criteria, found, filters, scores)
    print(f"chose seed {ds.attrs['chosen_seed']} (score {ds.attrs['chosen_score']:.3f} of "
          f"{ds.attrs['n_statements']})", file=sys.stderr)
    _write_search_product(ds, params, selection, outputs["result"])


def search_full(inputs, outputs, params, wildcards) -> None:
    """The full search's merged result, with its cost and provenance, kept at config search.archive
    and keyed by its settings (``archive.search_settings`` of the full search's parameters) and
    result version (``chainchaos.output.kept``)."""
    target = params.get("archive")
    require(bool(target), "search.archive", target,
            "the path of the archived full search (e.g. data/search/search_full.nc)")
    merged = Path(inputs["search"])
    stage_files = sorted(merged.parent.glob("*/*.nc")) + [merged.parent / "candidates.nc", merged]
    ds = archive.archive_dataset(xr.load_dataset(merged), archive.job_costs(Path(params["benchmarks"])),
                                 archive.stage_machines(stage_files))
    ds.attrs.update(kept.kept_attrs(archive.search_settings(params), SEARCH_RESULT_VERSION))
    write_netcdf(ds, target)
    print(f"{target}: chose seed {ds.attrs['chosen_seed']} among {ds.sizes['candidate']} candidates; "
          f"{ds.attrs['cost_total_jobs']} jobs, {ds.attrs['cost_total_cpu_seconds'] / 60:.1f} CPU-min", file=sys.stderr)


def _kept_search(params: dict) -> xr.Dataset:
    """The kept full search to re-judge: made with the full search's settings as this run has
    them (only the code that judges statements may differ) by older code."""
    path = params["archive"]
    settings = archive.search_settings(params)
    why = kept.why_not_usable(path, settings, SEARCH_RESULT_VERSION, "snakemake --cores 2 search_full")
    recorded, version = kept.read_key(path, "snakemake --cores 2 search_full")
    require(kept.digest(recorded) == kept.digest(settings), "kept search settings", why,
            "those of this run's full search (re-judging reuses its orbits: remake it with search_full)")
    require(version < SEARCH_RESULT_VERSION, "kept search result_version", version,
            f"older than this code's {SEARCH_RESULT_VERSION} (it is current: nothing to re-judge)")
    return xr.load_dataset(path)


def _stage_files(paths, kept_search: xr.Dataset, ids) -> list[xr.Dataset]:
    """The re-judging's kept stage files, each made from ``kept_search`` for the statements ``ids``
    by code of this result version (``rejudge.stage_settings``)."""
    from chainchaos.studies.search import rejudge

    remake = "delete it and run search_rejudge again"
    settings = rejudge.stage_settings(kept_search, ids)
    for path in _as_list(paths):
        why = kept.why_not_usable(path, settings, SEARCH_RESULT_VERSION, remake)
        require(why is None, "re-judging stage file", why, f"one made for this re-judging ({remake})")
    return [xr.load_dataset(p) for p in _as_list(paths)]


def search_rejudge_filter(inputs, outputs, params, wildcards) -> None:
    """Stage 1 again, on the scenes of the re-judged statements, for one group of candidates."""
    from chainchaos.studies.search import rejudge

    selection, plan, settings, criteria, site = _search_parts(params)
    group = int(wildcards["group"])
    ds = rejudge.filter_group(_kept_search(params), selection, plan, settings, criteria,
                              rejudge.check_ids(params["rejudge"]), group, site, _progress(f"rejudge filter {group}"))
    _write_search_product(ds, params, selection, outputs["result"])


def search_rejudge_score(inputs, outputs, params, wildcards) -> None:
    """Stage 2 again for the survivor of the given rank of the re-judged filter."""
    from chainchaos.studies.search import rejudge

    selection, plan, settings, criteria, site = _search_parts(params)
    ids = rejudge.check_ids(params["rejudge"])
    kept_search = _kept_search(params)
    filtered = rejudge.rejudged_filter(kept_search, _stage_files(inputs["filters"], kept_search, ids), ids, plan)
    rank = int(wildcards["rank"])
    candidate = rejudge.survivor(kept_search, filtered, plan, rank)
    print(f"survivor {rank}: candidate {candidate}", file=sys.stderr)
    ds = rejudge.score_candidate(kept_search, selection, plan, settings, criteria, ids, candidate, site,
                                 _progress(f"rejudge score {rank}"))
    _write_search_product(ds, params, selection, outputs["result"])


def search_rejudge(inputs, outputs, params, wildcards) -> None:
    """The kept full search with the re-judged statements, written over it (keyed by this code's
    result version), with what the re-judging cost and where it ran beside the original's."""
    from chainchaos.studies.search import rejudge

    selection, plan, settings, criteria, _ = _search_parts(params)
    ids = rejudge.check_ids(params["rejudge"])
    old = _kept_search(params)
    filtered = rejudge.rejudged_filter(old, _stage_files(inputs["filters"], old, ids), ids, plan)
    merged = rejudge.rejudged_search(old, selection, plan, settings, criteria, filtered,
                                     _stage_files(inputs["scores"], old, ids))
    stage_files = _as_list(inputs["filters"]) + _as_list(inputs["scores"])
    machines = archive.stage_machines(stage_files)
    costs = archive.job_costs(Path(params["benchmarks"]), stages=archive.REJUDGE_STAGES)
    merged.attrs = {
        **{k: v for k, v in old.attrs.items() if k.startswith(("cost_", "stage_")) or k in ("git_commit",)},
        **merged.attrs,
        "title": old.attrs["title"],
        "rejudged_statements": " ".join(ids),
        "rejudged_from_version": int(old.attrs[kept.VERSION_ATTR]),
        "rejudged_from_chosen_seed": int(old.attrs["chosen_seed"]),
        **{f"rejudge_cost_{stage}_{key}": (int(v) if key == "jobs" else float(v))
           for stage, cost in costs.items() for key, v in cost.items()},
        **{f"rejudge_{k}": v for k, v in machines.items()},
    }
    merged.attrs.update(provenance_attrs({"search": params["search"], "selection": vars(selection)}))
    merged.attrs.update(kept.kept_attrs(archive.search_settings(params), SEARCH_RESULT_VERSION))
    write_netcdf(merged, params["archive"])
    print(f"{params['archive']}: re-judged {', '.join(ids)}; chose seed {merged.attrs['chosen_seed']} "
          f"(was {old.attrs['chosen_seed']}); {costs['total']['jobs']} jobs, "
          f"{costs['total']['cpu_seconds'] / 60:.1f} CPU-min", file=sys.stderr)


def plot_search(inputs, outputs, params, wildcards) -> None:
    """The search's figures: how many candidates satisfy each statement, and every candidate
    (``pdf``, ``png``); the statements that hold together, the scores, and Hertz H = 1.8's onset
    of chaos against its level, with the claims' tolerances on the paper's values (``joint_pdf``,
    ``joint_png``)."""
    # matplotlib: only in the plotting jobs
    from chainchaos.studies.search.plots import plot_search as draw
    from chainchaos.studies.search.plots import plot_search_joint

    ds = xr.load_dataset(inputs["search"])
    dpi = int(params.get("dpi", 200))
    draw(ds, outputs["pdf"], outputs["png"], dpi)
    tol = Criteria.from_config(params.get("claims")).tolerance
    plot_search_joint(ds, outputs["joint_pdf"], outputs["joint_png"], dpi, time_factor=tol.time_factor,
                      level_factor=tol.mlce_factor)


def ensemble_verdicts(inputs, outputs, params, wildcards) -> None:
    """The ensembles of perturbed orbits of a model's scenes (params ``scenes``) on the chosen
    chain, integrated together, and each scene's statements' verdicts in its own file (output
    keyed by the scene's name)."""
    block = params["verdicts"]
    lanes = int(block["lanes"])
    settings = OrbitSettings.from_config(block["settings"])
    criteria = Criteria.from_config(params.get("claims"))
    chain = read_chain(inputs["chain"])
    of = statements.statement_scenes()
    scenes = {name: of[name] for name in params["scenes"]}
    orbits = [Orbit(scene.model, scene.energy, chain, int(params["site"]), lane)
              for scene in scenes.values() for lane in range(lanes)]
    t, runs = integrate(orbits, settings, _progress(f"verdicts {', '.join(scenes)}"),
                        gali_stop=np.log(criteria.gali_threshold))
    for k, (name, scene) in enumerate(scenes.items()):
        attrs = provenance_attrs({"verdicts": block, "scene": name})
        if settings.alignment:
            attrs.update(gali_order=int(settings.gali_order))
        attrs.update(model=scene.model, energy=float(scene.energy), dt=float(settings.dt),
                     t_final=float(settings.t_final), integrator=settings.integrator, lanes=lanes,
                     perturbation=float(settings.perturbation), seed=-1 if chain.seed is None else int(chain.seed))
        ds = verdict_dataset(name, t, runs[k * lanes:(k + 1) * lanes], criteria, attrs)
        for st, frac, v in zip(ds.statement.values, ds["fraction"].values, ds["verdict"].values):
            print(f"{name:14s} {st:28s} fraction {frac:.3f} verdict {v}", file=sys.stderr)
        write_netcdf(ds, outputs[name])
