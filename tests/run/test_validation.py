"""Every invalid input raises an error naming the parameter, its value and what is allowed;
the guards stop a run with the scene, the time and the value."""

import numpy as np
import pytest
import xarray as xr

from chainchaos import Chain, random_chain
from chainchaos.errors import ChainFileError, ParameterError, SimulationError
from chainchaos.records.io import chain_dataset, read_chain, write_netcdf
from chainchaos.run.scenes import SceneParameters, simulate


def scene(**overrides):
    args = dict(model="hertz", energy=0.25, t_final=10.0, dt=0.01, observables=("participation",))
    args.update(overrides)
    return SceneParameters(**args)


@pytest.mark.parametrize("build, name, value", [
    (lambda: random_chain(0, 5.0, N=1), "N", 1),
    (lambda: Chain(np.ones(1), 1.0), "N", 1),
    (lambda: random_chain(0, 0.5), "alpha", 0.5),
    (lambda: scene(dt=0.0), "dt", 0.0),
    (lambda: scene(dt=-1e-3), "dt", -1e-3),
    (lambda: scene(t_final=0.0), "t_final", 0.0),
    (lambda: scene(energy=-1.0), "energy", -1.0),
    (lambda: scene(energy=float("nan")), "energy", "nan"),
    (lambda: scene(model="morse"), "model", "morse"),
    (lambda: scene(integrator="rk4"), "integrator", "rk4"),
    (lambda: scene(observables=("participation", "temperature")), "observables", "temperature"),
    (lambda: scene(model="fput", observables=("n_gaps",)), "observables", "n_gaps"),
])
def test_invalid_parameters_are_named(build, name, value):
    with pytest.raises(ParameterError) as err:
        build()
    assert err.value.name == name
    message = str(err.value)
    assert name in message and str(value) in message and "allowed" in message


@pytest.mark.parametrize("site", [0, 41])
def test_excited_site_outside_the_chain(chain, site):
    with pytest.raises(ParameterError, match=f"excited_site = {site}.*1..40"):
        simulate(chain, scene(excited_site=site))


def test_missing_chain_file(tmp_path):
    with pytest.raises(ChainFileError, match="does not exist"):
        read_chain(tmp_path / "absent.nc")


def test_chain_file_lacking_a_variable(tmp_path, chain):
    path = tmp_path / "chain.nc"
    write_netcdf(chain_dataset(chain).drop_vars("delta"), path)
    with pytest.raises(ChainFileError, match="delta"):
        read_chain(path)


def test_chain_file_round_trip(tmp_path, chain):
    path = write_netcdf(chain_dataset(chain), tmp_path / "chain.nc")
    again = read_chain(path)
    assert np.array_equal(again.radius, chain.radius) and again.seed == chain.seed
    with xr.open_dataset(path) as ds:
        assert ds.attrs["alpha"] == 5.0 and ds.attrs["seed"] == 879 and "generator" in ds.attrs


def test_unreachable_energy_with_taylor_sign(chain):
    with pytest.raises(ParameterError, match="energy = 50.*at most"):
        simulate(chain, scene(model="fput", energy=50.0, k4_sign=-1))


def test_escape_to_infinity_is_stopped_by_the_guard(chain):
    """FPUT with the Taylor sign of K4 just below the barrier escapes: the run stops with the scene
    and time named, not NaNs."""
    from chainchaos.system.initial import initial_displacement

    # the barrier height along the excitation: the largest energy that still has a root
    energies = np.linspace(0.5, 20, 40)
    reachable = []
    for e in energies:
        try:
            initial_displacement("fput", chain.with_k4_sign(-1), e, 21)
            reachable.append(e)
        except ParameterError:
            break
    with pytest.raises(SimulationError) as err:
        simulate(chain, scene(model="fput", energy=reachable[-1], k4_sign=-1, t_final=1000.0))
    assert err.value.scene == "fput_H%g" % reachable[-1] and err.value.time > 0
    assert "fput_H" in str(err.value) and "t = " in str(err.value)


def test_energy_error_guard(chain):
    with pytest.raises(SimulationError, match="relative energy error") as err:
        simulate(chain, scene(energy=1.8, dt=0.2, t_final=100.0, max_energy_error=1e-12))
    assert err.value.time > 0 and err.value.value > 1e-12


def test_failed_write_leaves_no_file(tmp_path):
    ds = xr.Dataset({"x": ("t", np.arange(3.0))}, attrs={"bad": {"not": "serialisable"}})
    with pytest.raises(Exception):
        write_netcdf(ds, tmp_path / "out.nc")
    assert list(tmp_path.iterdir()) == []
