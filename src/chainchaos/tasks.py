"""One function per workflow rule: what the rule's script runs, with its inputs, outputs and params.

A workflow script is two lines (``from chainchaos.tasks import run_rule; run_rule(snakemake)``):
:func:`run_rule` sends stderr to the rule's log and calls the function named like the rule.
Everything here reads and writes files and calls into the package; the physics is elsewhere.
"""

import contextlib
import sys
import time
import traceback

import xarray as xr

from chainchaos import search
from chainchaos.criteria import Criteria
from chainchaos.io import read_chain, write_netcdf
from chainchaos.orbits import OrbitSettings
from chainchaos.provenance import provenance_attrs
from chainchaos.search import SearchPlan
from chainchaos.selection import SelectionCriteria, candidate_row


def run_rule(smk) -> None:
    """Run ``TASKS[smk.rule]`` with stderr in the rule's log (the first ``log:`` file)."""
    task = TASKS[smk.rule]
    with open(smk.log[0], "w") as log, contextlib.redirect_stderr(log):
        try:
            task(dict(smk.input.items()), dict(smk.output.items()), dict(smk.params.items()),
                 dict(smk.wildcards.items()))
        except BaseException:
            traceback.print_exc()  # into the log, which Snakemake shows for a failed job
            raise


def _progress(label: str):
    start = time.perf_counter()

    def report(done, total):
        print(f"[{label}] {done}/{total} orbits, {time.perf_counter() - start:.1f} s", file=sys.stderr, flush=True)

    return report


def _selection(params: dict) -> SelectionCriteria:
    chain = params["chain"]
    return SelectionCriteria(alpha=float(chain["alpha"]), N=int(chain["N"]), **chain.get("selection", {}))


def _search_parts(params: dict):
    block = params["search"]
    return (_selection(params), SearchPlan.from_config(block), OrbitSettings.from_config(block["settings"]),
            Criteria.from_config(params.get("claims")), int(params["site"]))


def _write_search_product(ds, params: dict, selection: SelectionCriteria, path) -> None:
    ds.attrs.update(provenance_attrs({"search": params["search"], "selection": vars(selection)}))
    write_netcdf(ds, path)


def search_candidates(inputs, outputs, params, wildcards) -> None:
    """Stage 0 of the realization search: the candidates, by the linear rule (or the pinned seed)."""
    selection, plan, *_ = _search_parts(params)
    ds = search.candidates(selection, plan)
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
    selection, plan, settings, criteria, site = _search_parts(params)
    found = xr.load_dataset(inputs["candidates"])
    filters = [xr.load_dataset(p) for p in _as_list(inputs.get("filters"))]
    scores = [xr.load_dataset(p) for p in _as_list(inputs["scores"])]
    ds = search.merge(selection, plan, settings, criteria, found, filters, scores)
    print(f"chose seed {ds.attrs['chosen_seed']} (score {ds.attrs['chosen_score']:.3f} of "
          f"{ds.attrs['n_statements']})", file=sys.stderr)
    _write_search_product(ds, params, selection, outputs["result"])


def select_chain(inputs, outputs, params, wildcards) -> None:
    """The chain file of the realization the search chose (or the pinned seed)."""
    from chainchaos.chain import random_chain
    from chainchaos.io import chain_dataset

    selection = _selection(params)
    found = xr.load_dataset(inputs["search"])
    seed = int(found.attrs["chosen_seed"])
    chain = random_chain(seed, selection.alpha, selection.N, float(params["chain"].get("wall_radius", 1.0)))
    row = search.candidate_rows(found)[int(found.attrs["chosen_candidate"])]
    passes = bool(candidate_row(seed, selection)["qualifies"])
    record = {
        "selection_seed": seed,
        "selection_candidates": int(found.attrs["n_qualifying"]),
        "selection_seeds_scanned": selection.n_seeds,
        "selection_mode": selection.mode,
        "selection_site": selection.site,
        "selection_linear_rule": int(passes),
        "selection_pinned": int(found.attrs["pinned"]),
        "selection_search_score": float(found.attrs["chosen_score"]),
        "selection_search_candidates": int(found.attrs["n_candidates"]),
        "selection_rule": ("the linear rule (selection module) as a first filter, then the chain whose orbits "
                           "satisfy the most of the paper's qualitative statements (search module)"),
    }
    record.update(selection_score=row["score"], selection_mode_participation=row["mode_participation"],
                  selection_overlap_left=row["overlap_left"], selection_overlap_right=row["overlap_right"])
    print(f"chose seed {seed}", file=sys.stderr)
    write_netcdf(chain_dataset(chain, record), outputs["chain"])


def ensemble_verdicts(inputs, outputs, params, wildcards) -> None:
    """One scene's ensemble of perturbed orbits on the chosen chain, and its statements' verdicts."""
    from chainchaos import paper
    from chainchaos.orbits import Orbit, integrate
    from chainchaos.verdicts import verdict_dataset

    name = wildcards["scene"]
    scene = paper.statement_scenes()[name]
    block = params["verdicts"]
    settings = OrbitSettings.from_config(block["settings"])
    criteria = Criteria.from_config(params.get("claims"))
    chain = read_chain(inputs["chain"])
    orbits = [Orbit(scene.model, scene.energy, chain, int(params["site"]), lane) for lane in range(int(block["lanes"]))]
    t, runs = integrate(orbits, settings, _progress(f"verdicts {name}"))
    attrs = provenance_attrs({"verdicts": block, "scene": name})
    attrs.update(model=scene.model, energy=float(scene.energy), dt=float(settings.dt),
                 t_final=float(settings.t_final), integrator=settings.integrator, lanes=int(block["lanes"]),
                 perturbation=float(settings.perturbation), seed=-1 if chain.seed is None else int(chain.seed))
    ds = verdict_dataset(name, t, runs, criteria, attrs)
    for st, frac, v in zip(ds.statement.values, ds["fraction"].values, ds["verdict"].values):
        print(f"{st:28s} fraction {frac:.3f} verdict {v}", file=sys.stderr)
    write_netcdf(ds, outputs["result"])


def simulate_scenes(inputs, outputs, params, wildcards) -> None:
    """The scenes of one batch integrated together; each scene's Dataset a group of one file."""
    from chainchaos.io import atomic_output
    from chainchaos.simulate import ProgressReporter, SceneParameters
    from chainchaos.simulate import simulate_scenes as integrate_scenes

    scenes = [SceneParameters(**{**p, "observables": tuple(p["observables"])}) for p in params["scenes"]]
    chain = read_chain(inputs["chain"])
    datasets = integrate_scenes(chain, scenes, ProgressReporter(wildcards["batch"], scenes[0].t_final, every=10.0))
    with atomic_output(outputs["batch"]) as tmp:
        for i, (scene, ds) in enumerate(zip(scenes, datasets)):
            ds.to_netcdf(tmp, mode="w" if i == 0 else "a", group=scene.name, engine="netcdf4")


def simulate_scene(inputs, outputs, params, wildcards) -> None:
    """One scene's file, taken from the batch it was integrated in."""
    with xr.open_dataset(inputs["batch"], group=wildcards["scene"], engine="netcdf4") as ds:
        write_netcdf(ds.load(), outputs["scene"])


def plot_search(inputs, outputs, params, wildcards) -> None:
    """The search figure: how many candidates satisfy each statement, and every candidate."""
    from chainchaos.search_plots import plot_search as draw

    draw(xr.load_dataset(inputs["search"]), outputs["pdf"], outputs["png"], int(params.get("dpi", 200)))


def _as_list(value) -> list:
    if value is None:
        return []
    return [value] if isinstance(value, str) else list(value)


TASKS = {f.__name__: f for f in (search_candidates, search_filter, search_score, search_merge, select_chain, ensemble_verdicts,
                                  simulate_scenes, simulate_scene, plot_search)}
