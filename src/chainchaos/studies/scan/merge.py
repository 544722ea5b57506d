"""The groups of a scan merged into one file: the energy scan on its (model, energy) grid, the
disorder statistics with the fraction of realizations delocalized and chaotic per energy (Wilson
95% intervals) and the quantiles of the onset times.

The groups are the group files of the scan's study (``runs.scan_study``, run by
``chainchaos.studies.study.runs.run_group``), read along their orbits as the scan's trajectories
(:func:`scan_groups`)."""


import numpy as np
import xarray as xr

from chainchaos.paper import panels
from chainchaos.records.provenance import provenance_attrs
from chainchaos.studies.scan.runs import (
    REALIZATION,
    SERIES,
    selection_kwargs,
    settings_for,
)
from chainchaos.studies.study.orbits import (
    EXCITATION,
    SCALARS,
    SELECTION_RULE,
    criteria_attrs,
    energy_grid,
)
from chainchaos.studies.study.statistics import wilson_interval
from chainchaos.system.chain import GENERATOR


def scan_groups(study_groups: list[xr.Dataset]) -> list[xr.Dataset]:
    """The group files of a scan's study, their dimension ``orbit`` read as the scan's
    ``trajectory`` (one lane per orbit)."""
    return [g.rename(orbit="trajectory") for g in study_groups]


def _grid_array(groups, key, shape, index_fn, fill):
    dtype = groups[0][key].dtype
    out = np.full(shape, fill, dtype=float if np.issubdtype(dtype, np.floating) else dtype)
    for ds in groups:
        for t in range(ds.sizes["trajectory"]):
            out[index_fn(ds, t)] = ds[key].values[t]
    return out


def merge_energy_scan(groups: list[xr.Dataset], scan_cfg: dict, chain=None) -> xr.Dataset:
    """The energy scan of all groups on the grid (model, energy), series on (model, energy, time)."""
    block = scan_cfg["energy_scan"]
    grid = energy_grid(block)
    models = list(block.get("models", panels.models()))
    settings = settings_for("energy_scan", scan_cfg)
    mi = {m: i for i, m in enumerate(models)}

    def idx(ds, t):
        return mi[str(ds["model"].values[t])], int(ds["energy_index"].values[t])

    data = {}
    shape = (len(models), grid.size)
    for key, (long_name, dtype) in SCALARS.items():
        fill = np.nan if dtype == "f8" else -1
        data[key] = (("model", "energy"), _grid_array(groups, key, shape, idx, fill),
                     {**groups[0][key].attrs})
    times = groups[0]["time"].values
    for key in SERIES:
        arr = np.full(shape + (times.size,), np.nan)
        for ds in groups:
            for t in range(ds.sizes["trajectory"]):
                arr[idx(ds, t)] = ds[key].values[t]
        data[key] = (("model", "energy", "time"), arr, {**groups[0][key].attrs})
    ds = xr.Dataset(data, coords={"model": models, "energy": grid, "time": times})
    ds.energy.attrs.update(units="1", long_name="total energy H (units of the reference contact energy scale)")
    ds.time.attrs.update(groups[0].time.attrs)
    ds.attrs.update(provenance_attrs({"kind": "energy_scan", "scan": scan_cfg}))
    ds.attrs.update(criteria_attrs(settings))
    ds.attrs.update(title="Energy scan: delocalization and chaos of a single-site excitation",
                    integrator=settings.integrator, dt=float(settings.dt), t_final=float(settings.t_final),
                    K4_sign=float(settings.k4_sign), excited_site=int(block.get("site", 21)),
                    seed=-1 if chain is None or chain.seed is None else int(chain.seed), n_groups=len(groups))
    if chain is not None:
        ds.attrs.update(alpha=float(chain.alpha))
    return ds


def merge_disorder(groups: list[xr.Dataset], scan_cfg: dict) -> xr.Dataset:
    """Disorder statistics on (model, energy, realization) with probabilities of delocalization and
    chaos per (model, energy), Wilson 95% bands, and onset-time quantiles over the valid runs."""
    block = scan_cfg["disorder"]
    grid = energy_grid(block)
    models = list(block.get("models", panels.models()))
    R = int(block["realizations"])
    settings = settings_for("disorder", scan_cfg)
    mi = {m: i for i, m in enumerate(models)}

    def idx(ds, t):
        return (mi[str(ds["model"].values[t])], int(ds["energy_index"].values[t]), int(ds["realization"].values[t]))

    shape = (len(models), grid.size, R)
    data = {}
    for key, (long_name, dtype) in SCALARS.items():
        fill = np.nan if dtype == "f8" else -1
        data[key] = (("model", "energy", "realization"), _grid_array(groups, key, shape, idx, fill),
                     {**groups[0][key].attrs})
    for key in ("excited_mode", "excited_site", "excited_mode_participation", "selection_fallback"):
        # a property of the realization (the same for every model and energy)
        dtype = groups[0][key].dtype
        arr = np.full(R, np.nan if np.issubdtype(dtype, np.floating) else -1, dtype=dtype)
        for g in groups:
            arr[g["realization"].values] = g[key].values
        data[key] = ("realization", arr, EXCITATION[key])
    valid = data["valid"][1] == 1
    n = valid.sum(axis=-1)
    quantiles = np.array([0.1, 0.25, 0.5, 0.75, 0.9])
    flags = ("delocalized", "chaotic", *(("chaotic_gali",) if (data["chaotic_gali"][1] >= 0).any() else ()))
    for what in flags:
        k = ((data[what][1] == 1) & valid).sum(axis=-1)
        lo, hi = wilson_interval(k, n)
        with np.errstate(invalid="ignore", divide="ignore"):
            prob = np.where(n > 0, k / np.maximum(n, 1), np.nan)
        data[f"probability_{what}"] = (("model", "energy"), prob,
                                        {"units": "1", "long_name": f"fraction of valid realizations {what}"})
        data[f"probability_{what}_lower"] = (("model", "energy"), lo,
                                              {"units": "1", "long_name": "Wilson 95% interval, lower bound"})
        data[f"probability_{what}_upper"] = (("model", "energy"), hi,
                                              {"units": "1", "long_name": "Wilson 95% interval, upper bound"})
        data[f"count_{what}"] = (("model", "energy"), k.astype(np.int32),
                                 {"units": "1", "long_name": f"number of valid realizations {what}"})
    data["count_valid"] = (("model", "energy"), n.astype(np.int32), {"units": "1", "long_name": "valid realizations"})
    onsets = (("delocalization", "delocalization_onset", "delocalized"), ("chaos", "chaos_onset", "chaotic"),
              ("chaos_gali", "gali_onset", "chaotic_gali"))
    for what, key, flag in (o for o in onsets if o[2] in flags):
        # over the valid runs classified delocalized (chaotic) at t_final only
        onset = np.where(valid & (data[flag][1] == 1), data[key][1], np.nan)
        q = np.full((len(models), grid.size, quantiles.size), np.nan)
        for a in range(len(models)):
            for e in range(grid.size):
                x = onset[a, e][np.isfinite(onset[a, e])]
                if x.size:
                    q[a, e] = np.quantile(x, quantiles)
        data[f"{what}_onset_quantiles"] = (("model", "energy", "quantile"), q, {
            "units": "1", "long_name": f"quantiles of the {what} onset time over the valid realizations classified {flag}"})
    ds = xr.Dataset(data, coords={"model": models, "energy": grid, "realization": np.arange(R),
                                  "quantile": quantiles})
    ds.energy.attrs.update(units="1", long_name="total energy H")
    ds.realization.attrs.update(REALIZATION)
    ds["quantile"].attrs.update(units="1", long_name="probability of the quantile")
    ds.attrs.update(provenance_attrs({"kind": "disorder", "scan": scan_cfg}))
    ds.attrs.update(criteria_attrs(settings))
    ds.attrs.update(title="Disorder statistics of delocalization and chaos", generator=GENERATOR,
                    alpha=float(block.get("alpha", 5.0)), first_seed=int(block.get("first_seed", 0)),
                    integrator=settings.integrator, dt=float(settings.dt), t_final=float(settings.t_final),
                    K4_sign=float(settings.k4_sign), n_groups=len(groups),
                    selection_rule=SELECTION_RULE, **{f"selection_{k}": v for k, v in selection_kwargs(scan_cfg).items()},
                    confidence_interval="Wilson score interval, 95%")
    return ds
