"""Every kind of NetCDF product passes the IOOS compliance checker's CF suite without errors, and
writing a file in those conventions (chainchaos.records.cf) keeps every value."""

import fnmatch
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from compliance_checker.base import BaseCheck
from compliance_checker.runner import CheckSuite

from chainchaos.records import cf
from chainchaos.records.io import write_netcdf

ROOT = Path(__file__).resolve().parents[2]

#: the newest CF version compliance-checker 6.1 checks
CF_SUITE = "cf:1.11"

#: One pattern per kind of product of the quick run (paths inside its results directory); the first
#: file of each, by name, is checked. Scenes of the two models hold different variables.
PRODUCT_KINDS = {
    "chain": "chain/chain.nc",
    "ensemble": "ensemble/participation_stats.nc",
    "Hertz scene": "scenes/hertz_*.nc",
    "FPUT scene": "scenes/fput_*.nc",
    "energy-scan group": "studies/energy_scan/groups/*.nc",
    "disorder group": "studies/disorder/groups/*.nc",
    "kept study statistics": "studies/*/statistics.nc",  # the studies of the manuscript's Beyond the paper
    "kept study laws": "studies/*/laws.nc",
    "energy scan": "scan/energy_scan.nc",
    "disorder statistics": "scan/disorder_statistics.nc",
    "search seed job": "search/seeds/*.nc",
    "search candidates": "search/candidates.nc",
    "search filter": "search/filter.nc",
    "search filter group": "studies/search-filter-*/groups/*.nc",
    "search score group": "studies/search-score-*/groups/*.nc",
    "verdict group": "studies/verdicts_*/groups/*.nc",
    "search": "search/search.nc",
    "verdicts": "verdicts/*.nc",
    "Lyapunov spectrum": "indicators/spectrum_*.nc",
    "work-precision model": "numerics/work_precision/*.nc",
    "work precision": "numerics/work_precision.nc",
    "stability": "numerics/stability.nc",
    "energy drift": "numerics/energy_drift.nc",
    "Taylor sign": "numerics/taylor_sign.nc",
    "step advice": "numerics/step_advice.nc",
}

#: compliance-checker 6.1 (check_spatiotemporal_dims_have_coordinate_vars) asks every dimension named
#: "time" for standard_name "time", and that standard name for units "<unit> since <epoch>". The
#: model's time is dimensionless (unit 1/omega_max): its units are "1", it carries no standard name,
#: and CF does not give a dimension's name a meaning. Upstream: ioos/compliance-checker#1245 and
#: PR #1353, which drops this demand. Tolerated only for a `time` in units "1" without standard_name.
DIMENSIONLESS_TIME = "Coordinate variable 'time' should have standard_name='time', found: 'None'"


def _failures(results) -> list[str]:
    """The messages of the failed results (and of their failed children)."""
    out = []
    for r in results:
        if r.value is not None and r.value[0] < r.value[1]:
            out += [f"{r.name}: {m}" for m in r.msgs]
            out += _failures(r.children)
    return out


def cf_problems(path) -> list[str]:
    """The checker's errors on the file at ``path`` (less DIMENSIONLESS_TIME for a time in units
    "1" without standard name) and the checks that raised instead of reporting."""
    suite = CheckSuite()
    suite.load_all_available_checkers()
    ds = suite.load_dataset(str(path))
    try:
        groups, raised = suite.run_all(ds, [CF_SUITE])[CF_SUITE]
        time = ds.variables.get("time")
        dimensionless_time = time is not None and getattr(time, "units", None) == "1" and \
            "standard_name" not in time.ncattrs()
    finally:
        ds.close()
    errors = _failures(suite.build_structure(CF_SUITE, groups, str(path), limit=BaseCheck.HIGH)["high_priorities"])
    if dimensionless_time:
        errors = [e for e in errors if not e.endswith(DIMENSIONLESS_TIME)]
    return errors + [f"check {name} raised {err[0]!r}" for name, err in raised.items()]


#: kinds that a run whose realization is pinned (by the archived full search or the config) does not
#: write; the small full search of tests/studies/search/test_search_full.py checks them
NOT_WHEN_PINNED = {"search filter", "search filter group"}


def product_files(results) -> dict:
    files = sorted(p.relative_to(results).as_posix() for p in results.rglob("*.nc"))
    unknown = [f for f in files if not any(fnmatch.fnmatch(f, pat) for pat in PRODUCT_KINDS.values())]
    assert not unknown, f"NetCDF products of no kind in PRODUCT_KINDS: {unknown}"
    chosen = {kind: next((f for f in files if fnmatch.fnmatch(f, pat)), None) for kind, pat in PRODUCT_KINDS.items()}
    with xr.open_dataset(results / PRODUCT_KINDS["search"]) as search:
        pinned = bool(int(search.attrs["pinned"]))
    if pinned:
        chosen = {kind: f for kind, f in chosen.items() if kind not in NOT_WHEN_PINNED}
    missing = [kind for kind, f in chosen.items() if f is None]
    assert not missing, f"the quick run wrote no file of the kinds {missing}"
    return chosen


@pytest.mark.pipeline
def test_every_kind_of_product_passes_the_cf_checker(quick):
    problems = {f"{kind} ({name})": cf_problems(quick / name) for kind, name in product_files(quick).items()}
    problems = {where: msgs for where, msgs in problems.items() if msgs}
    assert not problems, "\n".join(f"{where}:\n  " + "\n  ".join(msgs) for where, msgs in problems.items())


@pytest.mark.parametrize("archive", ["search/search_full.nc", "disorder/disorder_full.nc"])
def test_the_archived_computations_pass_the_cf_checker(archive):
    """The full search and the full disorder statistics, kept in the repository as data."""
    path = ROOT / "data" / archive
    if not path.exists():
        pytest.skip(f"no archive at {path}")
    assert cf_problems(path) == []


def test_conventions_keep_the_values_and_the_dataset(tmp_path, monkeypatch):
    """String, int64 and dimensionless-time coordinates written in the conventions of chainchaos.records.cf
    read back with the same values and index; the Dataset written is not changed."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    ds = xr.Dataset(
        {"x": (("model", "time"), np.arange(6.0).reshape(2, 3), {"units": "1", "long_name": "x"}),
         "big": ("model", np.array([1, 2**40], dtype=np.int64), {"units": "1", "long_name": "needs 64 bits"})},
        coords={"model": ("model", ["hertz", "fput"], {"long_name": "model"}),
                "time": ("time", [0.0, 0.5, 1.0], {"units": "1", "standard_name": "time", "long_name": "time"}),
                "lane": ("lane", np.arange(4), {"units": "1", "long_name": "lane"})},
        attrs={"title": "test product"})
    before = ds.copy(deep=True)
    path = write_netcdf(ds, tmp_path / "p.nc")
    assert ds.identical(before)
    back = xr.load_dataset(path)
    for name in ds.variables:
        assert np.array_equal(back[name].values, ds[name].values), name
    assert back.sel(model="fput")["x"].values.tolist() == [3.0, 4.0, 5.0]
    assert back["lane"].dtype == np.int32 and back["big"].dtype == np.int64  # int32 only when lossless
    assert "standard_name" not in back["time"].attrs and "_FillValue" not in back["time"].encoding
    assert back.attrs["Conventions"] == cf.CONVENTIONS and back.attrs["date_created"] == "2023-11-14T22:13:20Z"
    assert back.attrs["history"].startswith("2023-11-14T22:13:20Z ") and back.attrs["title"] == "test product"
    assert "Ngapasare" in back.attrs["references"] and back.attrs["summary"] == cf.SUMMARY
    assert cf_problems(path) == []
