"""The full realization search kept as data (config ``search.archive``, ``data/search/search_full.nc``).

``snakemake search_full`` runs the search over many more chains than ``all`` does (config block
``search_full``) and writes its merged result (:func:`stages.merge`) here, with what it cost
(the jobs' wall and CPU seconds from their Snakemake benchmark files) and the commits and CPUs
its stages ran on. ``all`` reads the chosen seed and the population of candidates from this file
and never reruns the search.
"""

import csv
from pathlib import Path

import xarray as xr

#: The rules of a search, in the order they run (workflow/rules/search.smk).
STAGES = ("search_seeds", "search_candidates", "search_filter", "search_score", "search_merge")


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
