"""The full realization search kept as data (config ``search.archive``, ``data/search/search_full.nc``).

``snakemake --cores 2 keep --config keep=search_full`` runs the search over many more chains
than ``all`` does (config block ``search_full``) and writes its merged result (:func:`stages.merge`)
here, with what it cost (the jobs' wall and CPU seconds from their Snakemake benchmark files) and
the commits and CPUs its stages ran on. ``all``, whose config names it, reads the population of
candidates and the chosen chain from this file and never reruns the search.
"""

import csv
import json
from dataclasses import asdict, fields
from pathlib import Path

import xarray as xr

from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.run.orbits import OrbitSettings
from chainchaos.studies.search.selection import SelectionCriteria
from chainchaos.studies.search.stages import SearchPlan

#: The rules of a search, in the order they run (workflow/rules/search.smk; ``study_group``: the
#: groups of its filter and score studies, ``<search>-<stage>-<model>``).
STAGES = ("search_seeds", "search_candidates", "study_group", "search_filter", "search_merge")
#: The rules that re-judge a kept search (``rejudge``).
REJUDGE_STAGES = ("search_rejudge_filter", "search_rejudge_score")

#: Settings that say how the work is cut, not what it computes (the engines, batches and chunks
#: give identical numbers): left out of the settings that key the kept search.
SCHEDULING_KEYS = ("engine", "batch_size", "seeds_per_job", "candidates_per_job", "pinned_seed")


def statements_data() -> list[dict]:
    """The paper's statements (``paper.statements.STATEMENTS``) as plain data: what each is about
    and how it is judged (its wording, which decides nothing, left out)."""
    return [{"id": s.id, "model": s.scene.model, "energy": float(s.scene.energy), "kind": s.kind,
             "value": s.value, "until": s.until, "early": bool(s.early)} for s in statements.STATEMENTS]


def search_settings(params: dict) -> dict:
    """The settings that determine a search's answer (its key as a kept result,
    ``chainchaos.records.kept``), from the parameters its rules get
    (``chainchaos.workflow.plan.search_params``): ``search`` (the block with its orbit
    ``settings``), ``chain`` (with its ``selection``), ``claims`` and ``site``.

    ``chain``: the linear rule and the seeds it scans (``SelectionCriteria``); ``search``: the
    sizes of the search (``SearchPlan``); ``orbit``: the orbits' integration and sampling
    (``OrbitSettings``); ``site``: the excited bead; ``statements``: :func:`statements_data`;
    ``criteria``: the claims' criteria they are judged by (``Criteria``, defaults filled in).
    Scheduling keys (:data:`SCHEDULING_KEYS`) are left out."""
    chain = params["chain"]
    selection = SelectionCriteria(alpha=float(chain["alpha"]), N=int(chain["N"]), **chain.get("selection", {}))
    plan = SearchPlan.from_config(params["search"])
    orbit = asdict(OrbitSettings.from_config(params["search"]["settings"]))
    return {
        "chain": asdict(selection),
        "search": {f.name: getattr(plan, f.name) for f in fields(plan) if f.name not in SCHEDULING_KEYS},
        "orbit": {k: v for k, v in orbit.items() if k not in SCHEDULING_KEYS},
        "site": int(params["site"]),
        "statements": statements_data(),
        "criteria": asdict(Criteria.from_config(params.get("claims"))),
    }


def chosen_seed(path) -> int:
    """The seed of the chain the archived search chose."""
    with xr.open_dataset(path) as ds:
        return int(ds.attrs["chosen_seed"])


def _benchmark_rows(path: Path) -> list[dict]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f, delimiter="\t"))


def job_costs(benchmarks: Path, search: str = "search_full", stages=STAGES) -> dict:
    """Per stage and in total: the number of jobs, their wall seconds and CPU seconds summed, read
    from the benchmark files ``<benchmarks>/<stage>/<search>[-<n>].tsv`` of the rules ``stages``
    (also the disorder statistics kept as data: ``scan.archive``); ``span_seconds``: from
    the first job's start to the last job's end (a resumed search includes its pause). A job whose
    run was killed just after writing its output may have left no benchmark file: its cost is
    missing from the sums."""
    costs, starts, ends = {}, [], []
    for stage in stages:
        files = sorted(Path(benchmarks, stage).glob(f"{search}.tsv")) + sorted(
            Path(benchmarks, stage).glob(f"{search}-*.tsv"))
        wall = cpu = 0.0
        for path in files:
            for row in _benchmark_rows(path):
                wall += float(row["s"])
                cpu += float(row["cpu_time"])
                ends.append(path.stat().st_mtime)
                starts.append(ends[-1] - float(row["s"]))
        costs[stage] = {"jobs": len(files), "wall_seconds": wall, "cpu_seconds": cpu}
    costs["total"] = {key: sum(c[key] for c in costs.values()) for key in ("jobs", "wall_seconds", "cpu_seconds")}
    costs["total"]["span_seconds"] = max(ends) - min(starts) if ends else 0.0
    return costs


def stage_machines(stage_files: list) -> dict:
    """The distinct commits and CPUs recorded by the stage files (``provenance_attrs``), each
    joined by "; ": a search resumed on another checkout or machine says so."""
    commits, cpus = set(), set()
    for path in stage_files:
        with xr.open_dataset(path) as ds:
            commits.add(str(ds.attrs.get("git_commit", "unknown")))
            cpus.add(f"{ds.attrs.get('cpu_model', '?')} ({ds.attrs.get('numba_target_cpu', '?')})")
    return {"stage_commits": "; ".join(sorted(commits)), "stage_cpus": "; ".join(sorted(cpus))}


def archive_dataset(search: xr.Dataset, costs: dict, machines: dict,
                    title: str = "Realization search at full scale: the paper's statements on every candidate chain",
                    ) -> xr.Dataset:
    """The merged search (or another computation kept as data) with its cost (attributes
    ``cost_<stage>_{jobs,wall_seconds,cpu_seconds}`` and ``cost_span_seconds``) and the commits
    and CPUs of its stages."""
    ds = search.copy()
    for stage, cost in costs.items():
        for key, value in cost.items():
            ds.attrs[f"cost_{stage}_{key}"] = int(value) if key == "jobs" else float(value)
    ds.attrs.update(machines)
    ds.attrs["title"] = title
    return ds


# ---- the key of a search kept before kept results recorded one ---------------------------------

def recorded_search_params(attrs: dict, config_at_commit: dict) -> dict:
    """The parameters (the shape of :func:`search_settings`' argument) an archived search ran with,
    from what the file records: its ``parameters`` JSON (``search``, with the orbit settings, and
    ``selection``); the keys it does not record, ``claims`` and the excited bead
    (``simulation.excited_site``), from ``config_at_commit``, the config/config.yaml of the commit
    the file records (``git_commit``; ``chainchaos.workflow.stamp`` reads it). The file's own attributes that repeat a setting
    (``agreement``, ``dt``, ``t_final``, ``lanes``, ...) are checked against the result; a
    difference raises ``ValueError``."""
    recorded = json.loads(attrs["parameters"])
    selection = dict(recorded["selection"])
    alpha, N = selection.pop("alpha"), selection.pop("N")
    params = {"search": recorded["search"], "chain": {"alpha": alpha, "N": N, "selection": selection},
              "claims": config_at_commit.get("claims", {}), "site": config_at_commit["simulation"]["excited_site"]}
    settings = search_settings(params)
    orbit, plan = settings["orbit"], settings["search"]
    expected = {"agreement": settings["criteria"]["agreement"], "dt": orbit["dt"], "t_final": orbit["t_final"],
                "integrator": orbit["integrator"], "perturbation": orbit["perturbation"], "lanes": plan["lanes"],
                "filter_t_final": plan["filter_t_final"], "gali_order": orbit["gali_order"] if orbit["alignment"] else 0,
                "seeds_scanned": settings["chain"]["n_seeds"], "alpha": settings["chain"]["alpha"]}
    for key, value in expected.items():
        if key in attrs and attrs[key] != value:
            raise ValueError(f"the file's attribute {key} = {attrs[key]!r} is not {value!r}, as its settings say")
    return params
