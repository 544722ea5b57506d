"""Tasks of workflow/rules/study.smk: a study's groups of orbits, its files per model and energy,
its statistics and its figures."""

import sys
import time
from pathlib import Path

import xarray as xr

from chainchaos.records import kept
from chainchaos.records.io import write_netcdf


def study_from_spec(spec: dict):
    """The study whose keys a rule passes as its param ``spec`` (``plan.study_spec``,
    ``plan.group_spec``)."""
    from chainchaos.studies.study.spec import load_study

    spec = dict(spec)
    return load_study({"name": spec.pop("name"), **{k: v for k, v in spec.items() if k != "extends"}})



def _check_groups(study, paths, check: dict) -> None:
    """Stop at the first group of ``paths`` (in group order) that is damaged or, for a kept study
    (``check``: its ways out, ``plan.kept_study_check``), made with other settings than the
    study's as they are now, with one line naming it (``records.kept.check_kept``)."""
    from chainchaos.studies.study.runs import STUDY_RESULT_VERSION, group_settings

    for group, path in enumerate([paths] if isinstance(paths, str) else paths):
        if check:
            kept.check_kept(path, group_settings(study, group), STUDY_RESULT_VERSION, check["remake"],
                            check["compute"])
        else:
            kept.check_data(path, f"snakemake --cores 2 keep --config keep={study.name}")


def study_group(inputs, outputs, params, wildcards) -> None:
    """One job's orbits of a study, with its progress in the log."""
    from chainchaos.studies.study.runs import run_group

    from chainchaos.run.progress import OrbitProgress

    study, group = study_from_spec(params["spec"]), int(wildcards["group"])
    start = time.perf_counter()
    cpu = time.process_time()
    ds = run_group(study, group, OrbitProgress(f"study {study.name} group {group} of {study.n_groups}"))
    elapsed = time.perf_counter() - start
    ds.attrs.update(wall_time_s=elapsed, cpu_time_s=time.process_time() - cpu,
                    seconds_per_orbit=elapsed / max(ds.sizes['orbit'], 1))
    print(f"[study {study.name} group {group}] {ds.sizes['orbit']} orbits in {elapsed:.1f} s; "
          f"invalid: {int((ds['valid'] == 0).sum())}", file=sys.stderr)
    write_netcdf(ds, outputs["group"], seal=True)  # it carries its key: kept as it is (keep_study_group)


def study_scene(inputs, outputs, params, wildcards) -> None:
    """Every realization and lane of one model and energy, with their statistics."""
    from chainchaos.studies.study import with_statistics
    from chainchaos.studies.study.runs import merge_groups, scene_dataset, scene_name

    study = study_from_spec(params["spec"])
    for model in study.models:
        for energy in study.energies:
            if scene_name(model, energy) == f"{wildcards['model']}_H{wildcards['energy']}":
                _check_groups(study, inputs["groups"], params["check"])
                # the statistics of this model and energy only (each reads its own orbits)
                merged = merge_groups(study, [xr.load_dataset(f) for f in inputs["groups"]])
                ds = with_statistics(study, merged.sel(model=[model], energy=[energy]))
                write_netcdf(scene_dataset(ds, model, energy), outputs["scene"])
                return
    raise ValueError(f"study {study.name}: no model and energy {wildcards['model']}_H{wildcards['energy']}")


def study_statistics(inputs, outputs, params, wildcards) -> None:
    """The ensemble statistics of every model and energy of a study, and the power laws its file
    names fitted with bootstrap intervals (studies.study.laws; none named: no law), from one read
    of its groups."""
    from chainchaos.records.provenance import provenance_attrs
    from chainchaos.studies.study.laws import laws
    from chainchaos.studies.study.runs import merge_groups
    from chainchaos.studies.study.statistics import statistics

    study = study_from_spec(params["spec"])
    _check_groups(study, inputs["groups"], params["check"])
    groups = [xr.load_dataset(f) for f in inputs["groups"]]
    merged = merge_groups(study, groups)
    stats = statistics(merged, float(study.spec["criteria"]["slope_window_decades"]))
    ds = laws(merged, study.spec, study.settings, study.N)
    bands = [name for name in ds.data_vars if "grid_time" in ds[name].dims]  # a crossover's band: drawn with
    if bands:  # the statistics, on their time axis
        stats = stats.merge(ds[bands].rename(grid_time="time").reindex(time=stats["time"]))
        stats["crossover_lines"] = ds["crossover_lines"]
        ds = ds.drop_vars([*bands, "grid_time"])
    mlce = [float(x) for x, series in zip(ds["expected"].values, ds["series"].values) if str(series) == "mlce"]
    if mlce:  # the chaos figure draws the study's published slope of <log10 Lambda>
        stats["published_slope_mlce"] = ((), mlce[0], {"units": "1", "long_name":
                                         "the published slope of <log10 Lambda> the study's laws name"})
    stats.attrs = {**merged.attrs, **stats.attrs, "title": f"{study.title}: ensemble statistics"}
    write_netcdf(stats, outputs["statistics"])
    # what the study's orbits cost: CPU time, or wall time where a group made before CPU time was kept
    cpu = all("cpu_time_s" in g.attrs for g in groups)
    ds.attrs.update(cost_s=float(sum(g.attrs["cpu_time_s" if cpu else "wall_time_s"] for g in groups)),
                    cost_kind="CPU" if cpu else "wall")
    ds.attrs.update(provenance_attrs({"study": study.name, **study.spec}), study=study.name,
                    study_title=study.title, title=f"{study.title}: power laws of the ensemble means")
    for m in ds["model"].values:
        for law in ds["law"].values:
            fit = ds.sel(model=m, law=law).isel(energy=0)
            print(f"[study {study.name}] {m} {law}: exponent {float(fit['exponent']):.3f} "
                  f"[{float(fit['lower']):.3f}, {float(fit['upper']):.3f}] over t = {float(fit['t_start']):.3g}.."
                  f"{float(fit['t_end']):.3g} (published {float(fit['expected']):.3g})", file=sys.stderr)
    write_netcdf(ds, outputs["laws"])


def plot_study(inputs, outputs, params, wildcards) -> None:
    """Figure ``wildcards["figure"]`` of study ``wildcards["study"]``: one its key ``figures`` names,
    or ``comparison``, its ensemble means beside those of the studies its ``compare_with`` names
    (``inputs``: each study's statistics by name, the study's own first)."""
    from chainchaos.engine.model_checks import load_model
    from chainchaos.output.plotting.style import (
        save_figure,  # matplotlib: only in the plotting jobs
    )
    from chainchaos.output.plotting.study import comparison_figure, study_figure

    for reference, directory in params.get("models", []):  # one's own models: their labels and colours
        load_model(reference, directory)
    named = {name: xr.load_dataset(path) for name, path in inputs.items()}
    study, figure = wildcards["study"], wildcards["figure"]
    if figure == "comparison":
        fig = comparison_figure(named, f"study {study} beside {', '.join(list(named)[1:])}")
    else:
        fig = study_figure(figure, named[study], named[study].attrs["study_title"])
    save_figure(fig, Path(outputs["pdf"]).with_suffix(""), dpi=params["dpi"])
