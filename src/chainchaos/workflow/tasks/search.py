"""Tasks of workflow/rules/search.smk: the realization search, its figure, and the ensemble verdicts
of the chosen chain."""

import sys

import xarray as xr

from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.ensembles import study_runs
from chainchaos.paper.verdicts import verdict_dataset
from chainchaos.records import kept
from chainchaos.records.io import read_chain, write_netcdf
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run.orbits import OrbitSettings
from chainchaos.studies.search import stages as search
from chainchaos.studies.search.selection import SelectionCriteria
from chainchaos.studies.search.stages import SearchPlan
from chainchaos.workflow.tasks.chain import selection_criteria


def _plan(params: dict) -> tuple[SelectionCriteria, SearchPlan]:
    """The linear rule and the sizes of a search: all that stage 0 needs."""
    return selection_criteria(params), SearchPlan.from_config(params["search"])


def search_parts(params: dict):
    settings = OrbitSettings.from_config(params["search"]["settings"])
    return (*_plan(params), settings, Criteria.from_config(params.get("claims")), int(params["site"]))


def write_search_product(ds, params: dict, selection: SelectionCriteria, path, seal: bool = False) -> None:
    """``ds`` with the search's provenance, written to ``path`` (``seal``: a kept file, with the
    checksum of its data)."""
    ds.attrs.update(provenance_attrs({"search": params["search"], "selection": vars(selection)}))
    write_netcdf(ds, path, seal=seal)


def as_list(value) -> list:
    if value is None:
        return []
    return [value] if isinstance(value, str) else list(value)


def search_seeds(inputs, outputs, params, wildcards) -> None:
    """Stage 0 of the realization search for one chunk of seeds: the chains that pass the linear rule."""
    selection, plan = _plan(params)
    ds = search.seed_chunk(selection, plan, int(wildcards["chunk"]))
    print(f"{ds.sizes['candidate']} of the {ds.attrs['seeds_scanned']} seeds from {ds.attrs['first_seed']} "
          "pass the linear rule", file=sys.stderr)
    write_search_product(ds, params, selection, outputs["result"])


def search_candidates(inputs, outputs, params, wildcards) -> None:
    """Stage 0 of the realization search: the candidates, by the linear rule (or the pinned seed)."""
    selection, plan = _plan(params)
    ds = search.candidates(selection, plan, [xr.load_dataset(p) for p in as_list(inputs["seeds"])])
    print(f"{ds.attrs['n_qualifying']} of {selection.n_seeds} seeds pass the linear rule; "
          f"{ds.sizes['candidate']} candidates", file=sys.stderr)
    write_search_product(ds, params, selection, outputs["result"])


def study_groups(paths) -> dict[str, list[xr.Dataset]]:
    """The groups of a search stage's studies (``paths``), by model."""
    groups: dict[str, list[xr.Dataset]] = {}
    for path in as_list(paths):
        ds = xr.load_dataset(path)
        groups.setdefault(str(ds["model"].values[0]), []).append(ds)
    return groups


def search_filter(inputs, outputs, params, wildcards) -> None:
    """Stage 1 of the realization search judged on its studies' groups: every candidate's
    outcomes, and the survivors."""
    selection, plan, settings, criteria, _ = search_parts(params)
    found = xr.load_dataset(inputs["candidates"])
    ds = search.filter_dataset(plan, settings, criteria, found, study_groups(inputs.get("groups")))
    print(f"survivors: candidates {', '.join(str(int(c)) for c in ds['survivor'].values)}", file=sys.stderr)
    write_search_product(ds, params, selection, outputs["result"])


def search_merge(inputs, outputs, params, wildcards) -> None:
    """Stage 2 of the realization search judged on its studies' groups; the candidates, scores
    and choice as one file."""
    selection, plan, settings, criteria, _ = search_parts(params)
    found = xr.load_dataset(inputs["candidates"])
    filters = [xr.load_dataset(p) for p in as_list(inputs.get("filters"))]
    ranked = filters[0]["survivor"].values if filters else search.survivors([], plan)
    scores = search.score_datasets(plan, settings, criteria, found, ranked, study_groups(inputs["groups"]))
    ds = search.merge(selection, plan, settings, criteria, found, filters, scores)
    print(f"chose seed {ds.attrs['chosen_seed']} (score {ds.attrs['chosen_score']:.3f} of "
          f"{ds.attrs['n_statements']})", file=sys.stderr)
    write_search_product(ds, params, selection, outputs["result"])


def plot_search(inputs, outputs, params, wildcards) -> None:
    """The search's figures: how many candidates satisfy each statement, and every candidate
    (``pdf``, ``png``); the statements that hold together, the scores, and Hertz H = 1.8's onset
    of chaos against its level, with the claims' tolerances on the paper's values (``joint_pdf``,
    ``joint_png``)."""
    # matplotlib: only in the plotting jobs
    from chainchaos.output.plotting.search import plot_search as draw
    from chainchaos.output.plotting.search import plot_search_joint

    # the kept full search when `all` uses it: a damaged one stops this job, naming it
    kept.check_data(inputs["search"], "snakemake --cores 2 keep --config keep=search_full")
    ds = xr.load_dataset(inputs["search"])
    dpi = int(params.get("dpi", 200))
    draw(ds, outputs["pdf"], outputs["png"], dpi)
    tol = Criteria.from_config(params.get("claims")).tolerance
    plot_search_joint(ds, outputs["joint_pdf"], outputs["joint_png"], dpi, time_factor=tol.time_factor,
                      level_factor=tol.mlce_factor)


def ensemble_verdicts(inputs, outputs, params, wildcards) -> None:
    """The verdicts of scene ``wildcards["scene"]``'s statements from the study of its model's
    scenes on the chosen chain (``paper.ensembles.verdict_study``, its groups ``groups``)."""
    block = params["verdicts"]
    settings = OrbitSettings.from_config(block["settings"])
    criteria = Criteria.from_config(params.get("claims"))
    chain = read_chain(inputs["chain"])
    name = wildcards["scene"]
    scene = statements.statement_scenes()[name]
    k = statements.statement_scenes_by_model()[scene.model].index(name)  # the study's energy index
    t, runs = study_runs([xr.load_dataset(p) for p in as_list(inputs["groups"])])
    attrs = provenance_attrs({"verdicts": block, "scene": name})
    if settings.alignment:
        attrs.update(gali_order=int(settings.gali_order))
    attrs.update(model=scene.model, energy=float(scene.energy), dt=float(settings.dt),
                 t_final=float(settings.t_final), integrator=settings.integrator, lanes=int(block["lanes"]),
                 perturbation=float(settings.perturbation), seed=-1 if chain.seed is None else int(chain.seed))
    ds = verdict_dataset(name, t, runs[k, 0], criteria, attrs)
    for st, frac, v in zip(ds.statement.values, ds["fraction"].values, ds["verdict"].values):
        print(f"{name:14s} {st:28s} fraction {frac:.3f} verdict {v}", file=sys.stderr)
    write_netcdf(ds, outputs["verdicts"])
