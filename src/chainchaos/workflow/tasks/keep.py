"""Tasks of workflow/rules/keep.smk: the results kept in the repository (data/), each written with
the key of the settings it was made with (chainchaos.records.kept)."""

import sys
from pathlib import Path

import xarray as xr

from chainchaos.errors import KeptFileError, require
from chainchaos.records import kept
from chainchaos.records.io import write_netcdf, write_text
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run.progress import OrbitProgress
from chainchaos.studies.scan import merge, runs
from chainchaos.studies.search import archive
from chainchaos.studies.search.stages import SEARCH_RESULT_VERSION
from chainchaos.workflow.tasks.search import (
    as_list,
    search_parts,
    write_search_product,
)
from chainchaos.workflow.tasks.study import study_group


def search_full(inputs, outputs, params, wildcards) -> None:
    """The full search's merged result, with its cost and provenance, kept at config search.archive
    and keyed by its settings (``archive.search_settings`` of the full search's parameters) and
    result version (``chainchaos.records.kept``)."""
    target = outputs["archive"]
    merged = Path(inputs["search"])
    stage_files = [*as_list(inputs["stages"]), merged]
    ds = archive.archive_dataset(xr.load_dataset(merged), archive.job_costs(Path(params["benchmarks"])),
                                 archive.stage_machines(stage_files))
    ds.attrs.update(kept.kept_attrs(archive.search_settings(params), SEARCH_RESULT_VERSION))
    write_netcdf(ds, target, seal=True)
    print(f"{target}: chose seed {ds.attrs['chosen_seed']} among {ds.sizes['candidate']} candidates; "
          f"{ds.attrs['cost_total_jobs']} jobs, {ds.attrs['cost_total_cpu_seconds'] / 60:.1f} CPU-min", file=sys.stderr)


def disorder_full(inputs, outputs, params, wildcards) -> None:
    """The full disorder statistics, with their cost and provenance, kept at config
    ``scan.disorder.archive`` and keyed by their settings (``runs.disorder_settings``) and result
    version (``chainchaos.records.kept``)."""
    target = outputs["archive"]
    groups = merge.scan_groups([xr.load_dataset(f) for f in inputs["groups"]])
    ds = merge.merge_disorder(groups, params["scan"])
    costs = archive.job_costs(Path(params["benchmarks"]), "disorder_full", stages=("study_group",))
    ds = archive.archive_dataset(ds, costs, archive.stage_machines(list(inputs["groups"])),
                                 title="Disorder statistics at full scale: delocalization and chaos by two indicators")
    ds.attrs.update(kept.kept_attrs(runs.disorder_settings(params["scan"], params["N"]), runs.DISORDER_RESULT_VERSION))
    write_netcdf(ds, target, seal=True)
    print(f"{target}: {ds.sizes['realization']} realizations x {ds.sizes['energy']} energies; "
          f"{ds.attrs['cost_total_jobs']} jobs, {ds.attrs['cost_total_cpu_seconds'] / 60:.1f} CPU-min", file=sys.stderr)


def _kept_search(params: dict) -> xr.Dataset:
    """The kept full search to re-judge: made with the full search's settings as this run has
    them (only the code that judges statements may differ) by older code."""
    path = params["archive"]
    settings = archive.search_settings(params)
    why = kept.why_not_usable(path, settings, SEARCH_RESULT_VERSION, "snakemake --cores 2 keep --config keep=search_full")
    recorded, version = kept.read_key(path, "snakemake --cores 2 keep --config keep=search_full")
    require(kept.digest(recorded) == kept.digest(settings), "kept search settings", why,
            "those of this run's full search (re-judging reuses its orbits: remake it with keep=search_full)")
    require(version < SEARCH_RESULT_VERSION, "kept search result_version", version,
            f"older than this code's {SEARCH_RESULT_VERSION} (it is current: nothing to re-judge)")
    kept.check_data(path, "snakemake --cores 2 keep --config keep=search_full")
    return xr.load_dataset(path)


def _stage_files(paths, kept_search: xr.Dataset, ids) -> list[xr.Dataset]:
    """The re-judging's kept stage files, each made from ``kept_search`` for the statements ``ids``
    by code of this result version (``rejudge.stage_settings``)."""
    from chainchaos.studies.search import rejudge

    remake = "snakemake --cores 2 keep --config keep=search_rejudge"
    settings = rejudge.stage_settings(kept_search, ids)
    for path in as_list(paths):
        why = kept.why_not_usable(path, settings, SEARCH_RESULT_VERSION, remake)
        require(why is None, "re-judging stage file", why, f"one made for this re-judging ({remake})")
        kept.check_data(path, remake)
    return [xr.load_dataset(p) for p in as_list(paths)]


def search_rejudge_filter(inputs, outputs, params, wildcards) -> None:
    """Stage 1 again, on the scenes of the re-judged statements, for one group of candidates."""
    from chainchaos.studies.search import rejudge

    selection, plan, settings, criteria, site = search_parts(params)
    group = int(wildcards["group"])
    ds = rejudge.filter_group(_kept_search(params), selection, plan, settings, criteria,
                              rejudge.check_ids(params["rejudge"]), group, site, OrbitProgress(f"rejudge filter {group}"))
    write_search_product(ds, params, selection, outputs["result"], seal=True)


def search_rejudge_score(inputs, outputs, params, wildcards) -> None:
    """Stage 2 again for the survivor of the given rank of the re-judged filter."""
    from chainchaos.studies.search import rejudge

    selection, plan, settings, criteria, site = search_parts(params)
    ids = rejudge.check_ids(params["rejudge"])
    kept_search = _kept_search(params)
    filtered = rejudge.rejudged_filter(kept_search, _stage_files(inputs["filters"], kept_search, ids), ids, plan)
    rank = int(wildcards["rank"])
    candidate = rejudge.survivor(kept_search, filtered, plan, rank)
    print(f"survivor {rank}: candidate {candidate}", file=sys.stderr)
    ds = rejudge.score_candidate(kept_search, selection, plan, settings, criteria, ids, candidate, site,
                                 OrbitProgress(f"rejudge score {rank}"))
    write_search_product(ds, params, selection, outputs["result"], seal=True)


def search_rejudge(inputs, outputs, params, wildcards) -> None:
    """The kept full search with the re-judged statements, written over it (keyed by this code's
    result version), with what the re-judging cost and where it ran beside the original's."""
    from chainchaos.studies.search import rejudge

    selection, plan, settings, criteria, _ = search_parts(params)
    ids = rejudge.check_ids(params["rejudge"])
    old = _kept_search(params)
    filtered = rejudge.rejudged_filter(old, _stage_files(inputs["filters"], old, ids), ids, plan)
    merged = rejudge.rejudged_search(old, selection, plan, settings, criteria, filtered,
                                     _stage_files(inputs["scores"], old, ids))
    stage_files = as_list(inputs["filters"]) + as_list(inputs["scores"])
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
    write_netcdf(merged, outputs["archive"], seal=True)
    print(f"{outputs['archive']}: re-judged {', '.join(ids)}; chose seed {merged.attrs['chosen_seed']} "
          f"(was {old.attrs['chosen_seed']}); {costs['total']['jobs']} jobs, "
          f"{costs['total']['cpu_seconds'] / 60:.1f} CPU-min", file=sys.stderr)


def keep_study_group(inputs, outputs, params, wildcards) -> None:
    """One group of a study, computed straight into its kept file (its key is in it)."""
    study_group(inputs, outputs, params, wildcards)


def check_kept_archive(inputs, outputs, params, wildcards) -> None:
    """A kept archive the config chose to use (``plan.archive_check``), checked against this run's
    settings, result version and the checksum of its data, and against the attributes the plan
    took from the config (the full search's chosen seed): the record says which file was used
    with which settings digest; a mismatch stops this job with one line and the two ways out."""
    check, path = params["check"], inputs["archive"]
    attrs = kept.check_kept(path, check["settings"], check["version"], check["remake"], check["compute"],
                            check["keys"])
    for name, (key, expected) in check["attrs"].items():
        found = attrs.get(name)
        if found is None or int(found) != int(expected):
            raise KeptFileError(f"kept file {path}: {name} is {found} in the file, {expected} in config {key}; "
                                f"set {key}: {found}, or {check['compute']}")
    write_text(f"{path}\tsettings digest {attrs[kept.DIGEST_ATTR]}\tused\n", outputs["record"])

