"""A study's orbits integrated in groups (one job each) and put together on their grid.

:func:`run_group` integrates one job's orbits (``orbits.integrate``: the batch engine, every
model, energy, realization and lane of the group as lanes of its SIMD blocks) and reduces each to
the series the study keeps and the verdicts of its criteria. :func:`merge_groups` puts the groups
on the grid (model, energy, realization, lane[, time]); :func:`scene_dataset` is one (model,
energy) of it, the file the workflow writes per model and energy. Numbers do not depend on how
the orbits are cut into groups.
"""

import json
import math

import numpy as np
import xarray as xr

from chainchaos.observe.registry import REGISTRY
from chainchaos.records import kept
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run.orbits import integrate, map_samples
from chainchaos.studies.study.orbits import (
    EXCITATION,
    EXCITATION_PICKS,
    SCALARS,
    criteria_attrs,
    reduce_orbit,
)
from chainchaos.system.models import MODELS

#: What each orbit of a group file is: its place on the study's grid.
ORBIT_INDEX = {"model": "model of the bond law", "energy_index": "index of the orbit's energy in excitation.energies",
               "realization": "index of the orbit's realization", "lane": "lane of the orbit (0: unperturbed)"}
TIME_COMMENT = "nondimensional time, unit 1/omega_max of the homogeneous linear chain"
KG_TIME_COMMENT = ("nondimensional time of the Klein-Gordon Hamiltonian H = sum p^2/2 + eps_l u^2/2 + u^4/4 + "
                   "(u_l+1 - u_l)^2/(2W) (masses 1), not 1/omega_max")
DNLS_TIME_COMMENT = ("nondimensional time of the DNLS Hamiltonian H = sum eps_l |psi_l|^2 + beta |psi_l|^4 / 2 - "
                     "(psi_l+1 psi_l^* + c.c.) (hopping 1), not 1/omega_max")


def time_comment(study) -> str:
    """The unit of time of ``study``'s files: bead chains use 1/omega_max of the homogeneous
    chain, Klein-Gordon and DNLS lattices the time of their Hamiltonian."""
    comments = {"beads": TIME_COMMENT, "kg": KG_TIME_COMMENT, "dnls": DNLS_TIME_COMMENT}
    kinds = [k for k in comments if any(MODELS[m].lattice == k for m in study.models)]
    if len(kinds) == 1:
        return comments[kinds[0]]
    names = {"beads": "bead models", "kg": "Klein-Gordon models", "dnls": "DNLS models"}
    return "; ".join(f"{names[k]}: {comments[k]}" for k in kinds)

#: Version of the numbers a study group computes (kept groups record it, chainchaos.records.kept):
#: bump only when a change of code changes them (a bit-identity test tells).
STUDY_RESULT_VERSION = 1
#: Keys of a study that say how it is shown and read, not what its orbits compute.
_PRESENTATION = ("title", "extends", "figures", "compare_with", "laws")


#: Keys added to the study schema after studies were first kept, with their defaults: a key at its
#: default is left out of the numbers' key, so that a file kept before the key existed (whose
#: numbers are those of the default) stays usable.
ADDED_DEFAULTS = {("lattice", "beta"): 1.0, ("excitation", "phases"): "alternating", ("lattice", "shape"): None,
                  ("lattice", "boundary"): None,
                  ("integration", "map_times"): None, ("integration", "deviation_start"): "all"}


def numbers_spec(study) -> dict:
    """The keys of ``study`` its orbits' numbers depend on: all but those of its presentation,
    and but the :data:`ADDED_DEFAULTS` at their defaults."""
    spec = {k: dict(v) if isinstance(v, dict) else v for k, v in study.spec.items() if k not in _PRESENTATION}
    for (block, key), default in ADDED_DEFAULTS.items():
        if spec.get(block, {}).get(key, default) == default:
            spec.get(block, {}).pop(key, None)
    return spec


def group_settings(study, group: int) -> dict:
    """What determines the numbers of one group of ``study``: :func:`numbers_spec` and the
    group's index (with ``jobs``, which orbits it holds)."""
    return {**numbers_spec(study), "group": int(group)}


def _fill(dtype: str):
    """The value of a per-orbit number where the grid has no orbit."""
    return np.nan if dtype == "f8" else -1


def kept_series(study) -> list[str]:
    """The series a study's files hold per orbit: the ones asked for, then those its verdicts
    read, then the energy error (and a split model's norm error)."""
    split = any(MODELS[m].is_split for m in study.models)
    return list(dict.fromkeys([*study.observables, "participation", "log_growth", "energy_error",
                               *(["norm_error"] if split else [])]))


#: The attributes of a density map and of its times.
DENSITY_MAP = {"units": "1", "long_name": "the density P and m2 are measured on (h_n, or a split model's z_n), "
               "at the map's time; site n = j Nx + i on a square lattice (float32)"}
MAP_TIME = {"units": "1", "long_name": "time of a density map: the sample nearest in log t to one of integration.map_times"}


def run_group(study, group: int, progress=None) -> xr.Dataset:
    """Integrate one job's orbits of ``study`` (``Study.group_items``) and keep their series and
    verdicts, on the dimension ``orbit`` (with its model, energy index, realization and lane)."""
    items = study.group_items(group)
    orbits = study.orbits(items)
    settings = study.settings
    gali_stop = math.log(settings.gali_threshold) if settings.alignment else None
    times, runs = integrate(orbits, settings, progress, gali_stop=gali_stop, series=study.series, window=study.window,
                            deviation_start=study.spec["integration"]["deviation_start"])
    index = {"model": [o.model for o in orbits],
             "energy_index": [e for _, e, _ in items for _ in range(study.lanes)],
             "realization": [r for _, _, r in items for _ in range(study.lanes)],
             "lane": [o.lane for o in orbits]}
    data = {key: ("orbit", np.array(values, dtype=object if key == "model" else np.int32), {"long_name": ORBIT_INDEX[key], **({} if key == "model" else {"units": "1"})})
            for key, values in index.items()}
    reduced = [reduce_orbit(times, run, settings) for run in runs]
    bound = study.spec["criteria"]["max_edge_energy"]
    if bound is not None and "edge_energy" in study.observables:  # a packet at the walls: not valid
        for r, run in zip(reduced, runs):
            r["valid"] = r["valid"] and not bool(np.nanmax(run["edge_energy"]) > bound)
    for key, (long_name, dtype) in SCALARS.items():
        data[key] = ("orbit", np.array([r[key] for r in reduced]).astype(dtype), {"units": "1", "long_name": long_name})
    for name in kept_series(study):
        values = np.stack([run[name] for run in runs])
        data[name] = (("orbit", "time"), values, {"units": "1", "long_name": REGISTRY[name].long_name})
    if study.selected:  # the rule's pick in each orbit's realization, as the scan's group files hold it
        for key, (pick, dtype) in EXCITATION_PICKS.items():
            data[key] = ("orbit", np.array([study.picks[r][pick] for r in index["realization"]], dtype=dtype),
                         EXCITATION[key])
    coords = {"time": ("time", times, {"units": "1", "long_name": "time", "comment": time_comment(study)})}
    if study.map_times:
        at = map_samples(times, study.map_times)
        data["density_map"] = (("orbit", "map_time", "site"), np.stack([run["density"][at] for run in runs]).astype(np.float32),
                               DENSITY_MAP)
        coords["map_time"] = ("map_time", times[at], MAP_TIME)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(study_attrs(study), group=int(group), title=f"{study.title}: one job's orbits",
                    **kept.kept_attrs(group_settings(study, group), STUDY_RESULT_VERSION))
    return ds


def orbit_runs(group: xr.Dataset, series, orbits=None) -> list[dict]:
    """Orbits of a group file (:func:`run_group`) as ``orbits.integrate`` returns them, for a step
    that judges them (the paper's verdicts, the realization search).

    Parameters
    ----------
    group : xarray.Dataset
        A group of a study, on the dimension ``orbit``.
    series : sequence of str
        The series to read, in this order (each kept by the study: ``kept_series``).
    orbits : array of int, optional
        Indices of the orbits to read, in this order; default all.

    Returns
    -------
    list of dict
        Per orbit: each series (array on ``time``), ``u0`` (float), ``max_gaps`` (int, -1 for a
        model without gaps) and ``valid`` (bool).
    """
    index = np.arange(group.sizes["orbit"]) if orbits is None else np.asarray(orbits)
    values = {name: group[name].values for name in series}
    u0, gaps, valid = group["u0"].values, group["max_gaps"].values, group["valid"].values
    return [{**{name: values[name][i] for name in series}, "u0": float(u0[i]), "max_gaps": int(gaps[i]),
             "valid": bool(valid[i])} for i in index]


def _excitation_text(study, exc) -> str:
    """What a study excites, in words: a rule, a mode, the beads of a chain or a block's sites."""
    where = ("the bead of the paper's excitation rule" if study.selected else f"mode {exc.mode}" if exc.kind == "mode"
             else f"beads {exc.beads()[0]}..{exc.beads()[1]}" if study.geometry.dimension == 1
             else f"{exc.width if exc.kind == 'block' else 1}^2 sites centred on (i, j) = {exc.site}")
    return f"{exc.kind} {exc.variable}: {where}"


def study_attrs(study) -> dict:
    """The provenance, settings and criteria every file of a study states."""
    settings = study.settings
    exc = study.excitation()
    attrs = provenance_attrs({"study": study.name, **study.spec})
    attrs.update(criteria_attrs(settings))
    attrs.update(study=study.name, study_title=study.title, study_settings=json.dumps(study.spec, sort_keys=True),
                 N=int(study.N), **study.geometry.as_attrs(), excitation=_excitation_text(study, exc),
                 integrator=settings.integrator, dt=float(settings.dt), t_final=float(settings.t_final),
                 lanes=int(study.lanes), perturbation=float(settings.perturbation),
                 time_units=time_comment(study))
    return attrs


def merge_groups(study, groups: list[xr.Dataset]) -> xr.Dataset:
    """Every group of ``study`` on the grid (model, energy, realization, lane[, time])."""
    models, energies = study.models, study.energies
    R, L = study.realizations, study.lanes
    times = groups[0]["time"].values
    shape = (len(models), energies.size, R, L)
    data = {}
    for key, (long_name, dtype) in SCALARS.items():
        data[key] = (("model", "energy", "realization", "lane"), np.full(shape, _fill(dtype), dtype=dtype),
                     {"units": "1", "long_name": long_name})
    for name in kept_series(study):
        data[name] = (("model", "energy", "realization", "lane", "time"), np.full(shape + (times.size,), np.nan),
                      {"units": "1", "long_name": REGISTRY[name].long_name})
    maps = "density_map" in groups[0]
    if maps:
        data["density_map"] = (("model", "energy", "realization", "lane", "map_time", "site"),
                               np.full(shape + groups[0]["density_map"].shape[1:], np.nan, dtype=np.float32), DENSITY_MAP)
    mi = {m: i for i, m in enumerate(models)}
    for g in groups:
        at = (np.array([mi[str(m)] for m in g["model"].values]), g["energy_index"].values, g["realization"].values,
              g["lane"].values)
        for key in data:
            data[key][1][at] = g[key].values
    coords = {
        "model": ("model", models, {"long_name": "model of the bond law"}),
        "energy": ("energy", energies, {"units": "1", "long_name": "total energy H of the excitation"}),
        "realization": ("realization", np.arange(R), {"units": "1", "long_name": "realization r, of seed seed[r]"}),
        "lane": ("lane", np.arange(L), {"units": "1", "long_name": "lane j: the initial state times 1 + perturbation xi_j"
                                                                    " (lane 0 unperturbed)"}),
        "time": ("time", times, {"units": "1", "long_name": "time", "comment": time_comment(study)}),
        **({"map_time": ("map_time", groups[0]["map_time"].values, MAP_TIME)} if maps else {}),
    }
    ds = xr.Dataset(data, coords=coords)
    ds["seed"] = ("realization", np.array(study.seeds, dtype=np.int64),
                  {"units": "1", "long_name": "seed of the realization's chain (numpy.random.default_rng)"})
    if study.selected:
        for key, (pick, dtype) in EXCITATION_PICKS.items():
            ds[key] = ("realization", np.array([p[pick] for p in study.picks], dtype=dtype), EXCITATION[key])
    ds.attrs.update(study_attrs(study), title=f"{study.title}", n_groups=len(groups))
    return ds


def scene_dataset(merged: xr.Dataset, model: str, energy: float) -> xr.Dataset:
    """One (model, energy) of a merged study: every realization and lane, and its statistics."""
    ds = merged.sel(model=model, energy=energy, drop=True)
    ds.attrs.update(merged.attrs, model=model, energy=float(energy),
                    title=f"{merged.attrs['title']}: {model} at H = {energy:g}")
    return ds


def scene_name(model: str, energy: float) -> str:
    """The file stem of one (model, energy) of a study: ``<model>_H<energy>``."""
    return f"{model}_H{float(energy):g}"
