"""The first commands a new user types, as they type them: each exits 0 and writes a file that
reads back as what it claims to be."""

import json
import shutil
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from chainchaos import chain_from_radii, normal_modes, random_chain
from chainchaos.observe.registry import ALIGNMENT, GAPS, NORM, OBSERVABLES, SPECTRUM, needing
from chainchaos.records.io import read_chain
from chainchaos.run.scenes import SceneParameters, model_observables
from chainchaos.system.models import BEAD_MODELS

CHAIN_PARAMETERS = ("radius", "mass", "A", "delta", "K2", "K3", "K4", "frequency", "mode_shape",
                    "mode_participation")


def chainchaos(*args, cwd):
    """Run the installed console script (as a user would), or the module where it is not on PATH."""
    command = [shutil.which("chainchaos")] if shutil.which("chainchaos") else [sys.executable, "-m", "chainchaos.workflow.cli"]
    done = subprocess.run([*command, *map(str, args)], cwd=cwd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, f"chainchaos {' '.join(map(str, args))}:\n{done.stdout}{done.stderr}"
    return done


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("first_contact")


@pytest.fixture(scope="module")
def seed_chain_file(workdir):
    done = chainchaos("chain", "--seed", 879, "--out", "chain.nc", cwd=workdir)
    assert done.stdout.strip() == "chain.nc"
    return workdir / "chain.nc"


def test_chain_from_seed(seed_chain_file):
    chain = read_chain(seed_chain_file)
    expected = random_chain(879, 5.0)
    assert chain.seed == 879 and chain.alpha == 5.0 and chain.N == 40
    assert np.array_equal(chain.radius, expected.radius)
    with xr.open_dataset(seed_chain_file) as ds:
        assert np.array_equal(ds["K2"].values, expected.K2)
        assert np.array_equal(ds["frequency"].values, normal_modes(expected)[0])


def test_chain_from_radii_in_any_unit(workdir):
    """Radii in millimetres: rescaled by (min + max) / 2, alpha = max / min."""
    radii = np.array([2.0, 3.0, 4.5, 6.0, 2.5, 5.0])
    np.savetxt(workdir / "radii_mm.txt", radii, header="bead radii in mm")
    chainchaos("chain", "--radii", "radii_mm.txt", "--out", "mm.nc", cwd=workdir)
    chain = read_chain(workdir / "mm.nc")
    assert chain.seed is None and chain.N == 6 and chain.alpha == 3.0
    assert np.allclose(chain.radius, radii / 4.0, rtol=0, atol=1e-15)


def test_seed_chain_round_trip_through_a_radii_file(workdir, seed_chain_file):
    """A seed chain's radii written one per line and read back with --reference-radius 1 and its
    alpha give the same chain, bit for bit; without them they give another one."""
    with xr.open_dataset(seed_chain_file) as ds:
        np.savetxt(workdir / "radii.txt", ds["radius"].values)
        original = {v: ds[v].values for v in CHAIN_PARAMETERS}
    chainchaos("chain", "--radii", "radii.txt", "--reference-radius", 1, "--alpha", 5, "--out", "again.nc",
               cwd=workdir)
    chainchaos("chain", "--radii", "radii.txt", "--out", "rescaled.nc", cwd=workdir)
    with xr.open_dataset(workdir / "again.nc") as again, xr.open_dataset(workdir / "rescaled.nc") as rescaled:
        for name in CHAIN_PARAMETERS:
            assert np.array_equal(again[name].values, original[name]), name
        assert again.attrs["alpha"] == 5.0
        assert not np.allclose(rescaled["frequency"].values, original["frequency"], rtol=1e-3, atol=0)


def test_chain_from_radii_takes_the_reference_and_alpha():
    chain = random_chain(3, 5.0)
    again = chain_from_radii(chain.radius, reference_radius=1.0, alpha=5.0)
    assert again.alpha == 5.0
    for name in ("radius", "mass", "A", "delta", "K2", "K3", "K4"):
        assert np.array_equal(getattr(again, name), getattr(chain, name)), name
    default = chain_from_radii(chain.radius)
    assert default.alpha == chain.radius.max() / chain.radius.min()
    assert np.array_equal(default.radius, chain.radius / ((chain.radius.max() + chain.radius.min()) / 2))


@pytest.mark.parametrize("model", sorted(BEAD_MODELS))
def test_default_observables_follow_the_model(model):
    params = SceneParameters(model=model, energy=1.0, t_final=10.0, dt=0.01)
    assert params.observables == model_observables(model)
    indicators = needing(SPECTRUM) | needing(ALIGNMENT)  # costly: computed when asked for by name
    spreading = {"second_moment", "compactness", "edge_energy", "largest_share",
                 "density"}  # the studies' measures (density: their maps): asked for by name
    assert (set(OBSERVABLES) - set(params.observables)) == \
        indicators | spreading | needing(NORM) | (set() if model == "hertz" else needing(GAPS))


@pytest.mark.parametrize("model", sorted(BEAD_MODELS))
def test_simulate_each_model_with_defaults(workdir, seed_chain_file, model):
    out = f"{model}.nc"
    done = chainchaos("simulate", "--chain", seed_chain_file.name, "--model", model, "--energy", 1,
                      "--t-final", 1, "--out", out, cwd=workdir)
    assert done.stdout.strip() == out and f"[{model}_H1]" in done.stderr  # progress on stderr
    with xr.open_dataset(workdir / out) as ds:
        assert ds.attrs["model"] == model and ds.attrs["dt"] == 5e-4 and ds.attrs["integrator"] == "SRKN6b"
        assert ds.attrs["observables"].split() == list(model_observables(model))
        assert ds.time.values[-1] == 1.0 and ds.sizes["site"] == 40
        assert ds.attrs["max_energy_error"] < 1e-8
        h = ds["energy_density"].values
        assert np.allclose(h.sum(axis=1), 1.0) and np.argmax(h[0]) == 20  # bead 21 excited
        assert ("n_gaps" in ds) == (model == "hertz")


def test_ensemble(workdir):
    chainchaos("ensemble", "--alpha", 2, 5, "--realizations", 20, "--out", "ensemble.nc", cwd=workdir)
    with xr.open_dataset(workdir / "ensemble.nc") as ds:
        assert ds["alpha"].values.tolist() == [2.0, 5.0] and ds.attrs["n_realizations"] == 20
        mean = ds["mean_participation"].values
        assert mean.shape == (2, 40) and np.all(np.diff(mean, axis=1) <= 0)  # ranked by decreasing P
        assert mean[1].mean() < mean[0].mean()  # stronger disorder localizes more


def test_bench(workdir):
    done = chainchaos("bench", "--model", "fput", "--steps", 200, "--repeats", 2, "--json", cwd=workdir)
    report = json.loads(done.stdout)
    assert report["model"] == "fput" and report["n_steps"] == 200 and report["repeats"] == 2
    assert report["ns_per_step_tangent"] > 0 and report["ns_per_step_no_tangent"] > 0


def test_simulate_shows_and_uses_the_defaults_of_scene_parameters():
    """The command's defaults are read from SceneParameters' fields, so its help and the generated
    command-line page state the real ones."""
    from dataclasses import MISSING, fields

    from chainchaos.workflow.cli import build_parser

    parser = build_parser()
    simulate = next(a for a in parser._actions if a.dest == "command").choices["simulate"]
    field_of = {"site": "excited_site"}
    defaults = {f.name: f.default for f in fields(SceneParameters) if f.default is not MISSING}
    checked = 0
    for action in simulate._actions:
        name = field_of.get(action.dest, action.dest)
        if name in defaults and action.default is not None and name not in ("observables", "name"):
            assert action.default == defaults[name], action.dest
            assert "%(default)s" in action.help, action.dest  # the help prints the value itself
            checked += 1
    assert checked >= 7
