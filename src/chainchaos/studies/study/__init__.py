"""Studies of one's own from one file (``studies/<name>.yaml``): chains, models, an excitation at
several energies, observables per orbit, perturbed lanes per realization, the ensemble statistics
the disordered-lattice literature uses and standard figures. ``spec`` reads and checks the file,
``runs`` integrates groups of orbits and merges them, ``statistics`` averages over realizations,
``plots`` draws; :func:`run_study` does all of it in one process, the workflow's ``study`` target
in resumable jobs, with the same numbers."""

import xarray as xr


def study_dataset(study, groups: list[xr.Dataset]) -> xr.Dataset:
    """The merged groups of ``study`` with its ensemble statistics, in one Dataset.

    Parameters
    ----------
    study : Study
        The study.
    groups : list of xarray.Dataset
        Its groups' Datasets (``runs.run_group``), every group once.

    Returns
    -------
    xarray.Dataset
        What :func:`run_study` returns.
    """
    from chainchaos.studies.study.runs import merge_groups

    return with_statistics(study, merge_groups(study, groups))


def with_statistics(study, merged: xr.Dataset) -> xr.Dataset:
    """``merged`` (the study's grid, or a part of it: the statistics of a (model, energy) read
    its own orbits only) with the ensemble statistics, in one Dataset.

    Parameters
    ----------
    study : Study
        The study (its ``criteria.slope_window_decades``).
    merged : xarray.Dataset
        Its per-orbit series, merged.

    Returns
    -------
    xarray.Dataset
        ``merged`` with the statistics' variables and attributes.
    """
    from chainchaos.studies.study.statistics import statistics

    stats = statistics(merged, float(study.spec["criteria"]["slope_window_decades"]))
    out = xr.merge([merged, stats], combine_attrs="override")
    out.attrs.update(stats.attrs)
    return out


def run_study(source, progress=None) -> xr.Dataset:
    """Run a study in this process and return every orbit and the ensemble statistics.

    Parameters
    ----------
    source : str, path or dict
        A study name (``studies/<name>.yaml``), the path of a study file, or a dict of the
        file's keys (``studies/README.md``).
    progress : callable, optional
        Called as ``progress(done, total)`` with the orbits integrated so far.

    Returns
    -------
    xarray.Dataset
        One Dataset, every shape fixed by the study: the per-orbit series on (model, energy,
        realization, lane, time), the per-orbit verdicts on (model, energy, realization, lane),
        and the statistics on (model, energy[, quantile], time) (``studies.study.statistics``).

    Raises
    ------
    KeptFileError
        For a kept group with this study's settings that cannot be read or whose data do not
        match the checksum it records (``chainchaos.records.kept.check_data``): the message names
        it and how to restore it.

    Examples
    --------
    >>> from chainchaos import run_study
    >>> ds = run_study({"lattice": {"model": "fput", "N": 16, "realizations": 2},
    ...                 "excitation": {"energies": [0.5]},
    ...                 "integration": {"dt": 0.05, "t_final": 10.0}})
    >>> dict(ds["participation"].sizes)
    {'model': 1, 'energy': 1, 'realization': 2, 'lane': 1, 'time': 31}

    A group kept in the repository (``data/studies/<name>/groups/``, ``snakemake --cores 2 keep
    --config keep=<name>``) with this study's settings and the code's result version is read, not
    integrated again, so ``run_study("kg_weak_chaos")`` returns the kept Klein-Gordon archive in
    seconds.
    """
    from chainchaos.records import kept
    from chainchaos.studies.study.runs import (
        STUDY_RESULT_VERSION,
        group_settings,
        run_group,
    )
    from chainchaos.studies.study.spec import kept_group_path, load_study

    study = load_study(source)
    total = len(study.items()) * study.lanes
    done = 0

    def group_progress(n, _):
        if progress is not None:
            progress(done + n, total)

    groups = []
    for g in range(study.n_groups):
        path = kept_group_path(study.name, g)
        remake = f"snakemake --cores 2 keep --config keep={study.name}"
        if path is not None and path.exists() and kept.why_not_usable(path, group_settings(study, g), STUDY_RESULT_VERSION,
                                                                       remake) is None:
            kept.check_data(path, remake)  # a kept group damaged inside its data: KeptFileError, naming it
            groups.append(xr.load_dataset(path))
        else:
            groups.append(run_group(study, g, group_progress))
        done += groups[-1].sizes["orbit"]
    return study_dataset(study, groups)
