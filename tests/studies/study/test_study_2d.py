"""A study of the DNLS model on a square lattice from one spec (lattice.shape): its lattices and
block, the packet's m2 about its centre in two dimensions, the norm kept; the chain's study
unchanged by the new keys at their defaults; a shape, block or boundary that does not fit named
with what is allowed, before anything runs."""

import numpy as np
import pytest

from chainchaos.errors import StudyError
from chainchaos.studies.study import run_study
from chainchaos.studies.study.runs import group_settings
from chainchaos.studies.study.spec import load_study
from chainchaos.system.chain import dnls_lattice

SPEC = {"lattice": {"model": "dnls", "shape": [15, 13], "W": 10.0, "beta": 1.0, "realizations": 2},
        "excitation": {"kind": "block", "width": 3, "energies": [4.5]},
        "integration": {"integrator": "s9ABC6", "dt": 0.05, "t_final": 50.0, "samples_per_decade": 5},
        "observables": ["participation", "second_moment", "mlce", "norm_error"]}


def test_a_square_lattice_study_runs_from_one_spec():
    study = load_study(SPEC)
    assert study.N == 195 and study.geometry.shape == (15, 13)
    assert study.excitation().site == (8, 7)
    lattice = study.lattices("dnls")[1]
    np.testing.assert_array_equal(lattice.eps, dnls_lattice(1, 10.0, (15, 13), 1.0).eps)
    ds = run_study(SPEC)
    assert (ds["valid"] == 1).all() and list(np.ravel(ds.attrs["lattice_shape"])) == [15, 13]
    m2 = ds["second_moment"].isel(model=0, energy=0, lane=0)
    np.testing.assert_allclose(m2.isel(time=0), 2 * (9 - 1) / 12, rtol=1e-14)  # the uniform 3 x 3 block
    assert float(m2.isel(time=-1).min()) > 2 * (9 - 1) / 12  # it spreads
    assert float(ds["norm_error"].max()) < 1e-6


def test_the_chain_keys_stay_the_kept_groups_key():
    chain = {**SPEC, "lattice": {"model": "dnls", "N": 40, "W": 4.0}}
    explicit = {**chain, "lattice": {**chain["lattice"], "shape": None, "boundary": None}}
    assert group_settings(load_study(chain), 0) == group_settings(load_study(explicit), 0)
    assert "shape" not in group_settings(load_study(chain), 0)["lattice"]


@pytest.mark.parametrize("lattice, excitation, message", [
    ({"model": "hertz", "shape": [8, 8]}, {}, "lattice.shape = [8, 8]: allowed is [N] with the models ['hertz']"),
    ({"model": "dnls", "shape": [8, 8], "N": 64}, {}, "lattice.N = 64: allowed is an integer >= 2, or lattice.shape"),
    ({"model": "dnls", "shape": [8, 8, 8]}, {}, "lattice.shape"),
    ({"model": "dnls", "shape": [8, 8], "boundary": ["fixed", "open"]}, {}, "lattice.boundary"),
    ({"model": "dnls", "shape": [8, 8]}, {"kind": "block", "width": 5, "site": [2, 4]}, "excitation.site"),
    ({"model": "dnls", "shape": [8, 8]}, {"site": 4}, "excitation.site"),
])
def test_a_bad_shape_block_or_boundary_is_named_before_anything_runs(lattice, excitation, message):
    spec = {**SPEC, "lattice": lattice, "excitation": {"energies": [1.0], **excitation}}
    if lattice["model"] == "hertz":
        spec["integration"] = {"dt": 0.05, "t_final": 50.0}
    with pytest.raises(StudyError, match=message.replace("[", r"\[").replace("]", r"\]")):
        load_study(spec)


def test_an_observable_of_one_s_own_from_one_file_is_kept_per_orbit():
    """examples/anisotropy.py:ANISOTROPY named in a spec: loaded, checked on a short orbit,
    registered, and kept per orbit; a square 3 x 3 block starts round (A = 0 to rounding)."""
    from pathlib import Path

    examples = Path(__file__).resolve().parents[3] / "examples"
    spec = {**SPEC, "directory": str(examples),
            "observables": ["participation", "second_moment", "anisotropy.py:ANISOTROPY", "mlce"]}
    study = load_study(spec)
    assert "anisotropy" in study.observables
    ds = run_study(spec)
    a = ds["anisotropy"].isel(model=0, energy=0, lane=0)
    assert abs(float(a.isel(time=0, realization=0))) < 1e-12
    assert np.all(np.abs(a.values) <= 1.0)


@pytest.mark.parametrize("reference, message", [
    ("anisotropy.py:NOPE", "the name of a chainchaos Observable"),
    ("missing.py:ANISOTROPY", "an existing Python file"),
    ("bad_observable.py:BAD", "a compute\\(run\\) that runs"),
])
def test_an_observable_of_one_s_own_that_does_not_fit_is_named_before_the_run(reference, message, tmp_path):
    from pathlib import Path

    examples = Path(__file__).resolve().parents[3] / "examples"
    (tmp_path / "bad_observable.py").write_text(
        "from chainchaos.observe.registry import Observable\n"
        "BAD = Observable(name='bad', dims=('time',), label='b', long_name='fails', compute=lambda run: 1 / 0)\n")
    directory = tmp_path if reference.startswith("bad") else examples
    spec = {**SPEC, "directory": str(directory), "observables": ["participation", reference]}
    with pytest.raises(StudyError, match=message):
        load_study(spec)


def test_density_maps_are_the_sampled_densities_at_the_chosen_times():
    """integration.map_times: each orbit's density at the sample nearest in log t, every one
    normalised, and the packet's m2 measured on the map is the one kept at that sample (float32)."""
    from chainchaos.observe.formulas import second_moment, site_positions

    spec = {**SPEC, "integration": {**SPEC["integration"], "map_times": [1.0, 9.0, 50.0]}}
    study = load_study(spec)
    assert "maps" in study.spec["figures"]
    ds = run_study(spec)
    maps = ds["density_map"]
    assert int(ds["shown_realization"].isel(model=0, energy=0)) == 0 and "shown_density_map" in ds
    assert maps.dtype == np.float32 and maps.sizes["site"] == 195
    times = maps["map_time"].values  # samples, each within half a sample spacing (5 a decade) of its time
    assert set(times) <= set(ds["time"].values) and times[0] == 1.0 and times[-1] == 50.0
    assert np.all(np.abs(np.log10(times) - np.log10([1.0, 9.0, 50.0])) <= 0.1 + 0.01)
    np.testing.assert_allclose(maps.sum("site").values, 1.0, rtol=1e-5)
    positions = site_positions(study.geometry)
    for k, t in enumerate(maps["map_time"].values):
        z = maps.isel(model=0, energy=0, lane=0, map_time=k).values.astype(np.float64)
        kept = ds["second_moment"].isel(model=0, energy=0, lane=0).sel(time=t).values
        np.testing.assert_allclose(second_moment(z, positions), kept, rtol=1e-5)


@pytest.mark.parametrize("integration, figures, message", [
    ({"map_times": [100.0]}, None, "integration.map_times = \\[100.0\\]: allowed is times <= t_final = 50"),
    ({}, ["maps"], "figures = 'maps': allowed is a figure of maps with integration.map_times given"),
])
def test_maps_after_the_run_or_without_times_are_named(integration, figures, message):
    spec = {**SPEC, "integration": {**SPEC["integration"], **integration}, **({"figures": figures} if figures else {})}
    with pytest.raises(StudyError, match=message):
        load_study(spec)


def test_map_times_on_one_sample_and_a_norm_asked_of_a_bond_model_are_named():
    spec = {**SPEC, "integration": {**SPEC["integration"], "map_times": [2.6, 2.7]}}
    with pytest.raises(StudyError, match="integration.map_times = \\[2.6, 2.7\\]: allowed is times whose nearest "
                                         "samples differ"):
        load_study(spec)
    kg = {**SPEC, "lattice": {"model": "kg", "shape": [9, 9], "W": 10.0}, "integration": {"dt": 0.1, "t_final": 10.0}}
    with pytest.raises(StudyError, match="observables = 'norm_error': allowed is an observable of the split models"):
        load_study(kg)


def test_the_deviation_vector_starts_on_the_excited_sites_when_asked():
    """integration.deviation_start: excited puts the run's own random vector on the excited
    sites only, at its norm (the window's start), so that on a lattice integrated whole Lambda
    measures the packet at once: positive from t = 10 on, where the vector spread over every site
    of a 21 x 21 KG lattice gives a Lambda still negative there (its part at rest shrinks first)."""
    from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
    from chainchaos.system.chain import kg_lattice
    from chainchaos.system.initial import Excitation

    lattices = [kg_lattice(seed, 10.0, (21, 21)) for seed in range(2)]
    orbits = [Orbit(model="kg", energy=0.4, chain=c, site=0, lane=0, excitation=Excitation(site=(11, 11),
                    variable="momentum")) for c in lattices]
    runs = {}
    for start in ("all", "excited"):
        settings = OrbitSettings(t_final=100.0, dt=0.4, integrator="ABA864", samples_per_decade=5)
        times, runs[start] = integrate(orbits, settings, series={"mlce": None, "log_growth": None},
                                       deviation_start=start)
    late = times >= 10.0
    assert all(np.all(r["mlce"][late] > 0) for r in runs["excited"])
    assert all(np.any(r["mlce"][late] < 0) for r in runs["all"])
    with pytest.raises(Exception, match="deviation_start = 'some'"):
        integrate(orbits, settings, deviation_start="some")
