"""A scene file follows the data contract, holds only what was asked, and records provenance."""

import json
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from chainchaos.errors import ParameterError
from chainchaos.observe.registry import NORM, OBSERVABLES, needing
from chainchaos.records.io import write_netcdf
from chainchaos.run.scenes import SceneParameters, simulate


def test_only_requested_observables_are_written(tmp_path, chain):
    ds = simulate(chain, SceneParameters(model="fput", energy=0.5, t_final=10.0, dt=0.01, observables=("mlce", "eta")))
    path = write_netcdf(ds, tmp_path / "scene.nc")
    with xr.open_dataset(path) as back:
        assert set(back.data_vars) == {"mlce", "eta", "energy_error", "initial_deviation", "frequency"}
        for name in ("model", "energy", "u0", "dt", "integrator", "t_final", "K4_sign", "git_commit",
                     "chainchaos_version"):
            assert name in back.attrs
        params = json.loads(back.attrs["parameters"])
        assert params["observables"] == ["mlce", "eta", "energy_error"] and params["dt"] == 0.01
        assert back.mlce.attrs["units"] == "1" and "long_name" in back.mlce.attrs


def test_every_observable_of_the_contract(chain):
    """Every observable of a bond model (the norm's belong to split models: tests/engine/test_split.py)."""
    bond = tuple(o for o in OBSERVABLES if o not in needing(NORM))
    ds = simulate(chain, SceneParameters(model="hertz", energy=1.8, t_final=100.0, dt=0.01, observables=bond,
                                         exponents=4, gali_order=3))
    for name in bond + ("initial_deviation",):
        assert name in ds, name
    assert ds.lyapunov_spectrum.dims == ("time", "exponent") and list(ds.exponent.values) == [1, 2, 3, 4]
    assert np.array_equal(ds.lyapunov_spectrum.values[:, 0], ds.mlce.values, equal_nan=True)
    assert ds.log_gali.attrs["k"] == 3 and np.all(ds.sali.values[1:] <= np.sqrt(2.0))
    assert np.allclose(ds.energy_density.sum("site"), 1.0) and np.allclose(ds.dvd.sum("site"), 1.0)
    assert np.all((ds.gap_fraction >= 0) & (ds.gap_fraction <= 1))
    assert np.all(ds.n_gaps_max >= ds.n_gaps)
    assert np.isclose(np.linalg.norm(ds.initial_deviation), 1.0)
    assert np.all(ds.initial_deviation.values[:40] == 0.0)


def test_command_line_chain_and_simulate(tmp_path):
    run = [sys.executable, "-m", "chainchaos.workflow.cli"]
    subprocess.run(run + ["chain", "--seed", "879", "--alpha", "5", "--out", str(tmp_path / "c.nc")], check=True)
    done = subprocess.run(run + ["simulate", "--chain", str(tmp_path / "c.nc"), "--model", "hertz", "--energy",
                                 "1.8", "--t-final", "20", "--dt", "0.01", "--observables", "participation",
                                 "mlce", "--out", str(tmp_path / "s.nc")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "[hertz_H1.8] t = 20" in done.stderr and "100.0%" in done.stderr
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        assert {"participation", "mlce", "energy_error"} <= set(ds.data_vars) and ds.time.values[-1] == 20.0
    bad = subprocess.run(run + ["simulate", "--chain", str(tmp_path / "missing.nc"), "--model", "hertz",
                                "--energy", "1", "--t-final", "1", "--out", str(tmp_path / "x.nc")],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "missing.nc" in bad.stderr and "Traceback" not in bad.stderr
    assert not (tmp_path / "x.nc").exists()


def test_radii_file(tmp_path):
    (tmp_path / "radii.txt").write_text("\n".join(str(r) for r in np.linspace(1, 5, 10)) + "\n")
    subprocess.run([sys.executable, "-m", "chainchaos.workflow.cli", "chain", "--radii", str(tmp_path / "radii.txt"),
                    "--out", str(tmp_path / "c.nc")], check=True, capture_output=True)
    with xr.open_dataset(tmp_path / "c.nc") as ds:
        assert ds.sizes["site"] == 10 and ds.attrs["alpha"] == 5.0
        assert np.isclose(ds.radius.values.mean(), 1.0)


