"""Every model through every entry point, and a model of one's own.

Every registered model runs through ``simulate``, ``Problem`` + ``sample``, ``run_study`` and
``chainchaos simulate`` on its lattice, and a lattice of the wrong kind is refused saying how to
make the right one. A model defined in a user's file passes the checks of
``engine.model_checks`` (which the package's models pass too), runs from Python, a study file
and the command line, and is refused, with the failed check named, when its kernels break a rule
the engines rely on: each broken model below breaks exactly one (the rule, not the code's own
earlier output, decides what must fail).
"""

import os
import re
import subprocess
import sys

import numpy as np
import pytest

from chainchaos import (MODELS, Model, Problem, SceneParameters, add_model, check_model, kg_chain, load_model,
                        random_chain, run_study, simulate)
from chainchaos.engine.model_checks import CHECKS, ModelCheckError
from chainchaos.errors import ParameterError
from chainchaos.run.driver import sample
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import BOND_MODELS, PACKAGE_MODELS

# the registered models at import, before any test adds one of its own
REGISTERED = sorted(m for m in PACKAGE_MODELS if m in BOND_MODELS)  # split models: tests/engine/test_split.py
N = 16


def lattice_of(model, seed=3):
    return kg_chain(seed, 4.0, N) if MODELS[model].lattice == "kg" else random_chain(seed, 5.0, N)


def energy_of(model):
    return 0.4 if MODELS[model].lattice == "kg" else 1.0


@pytest.mark.parametrize("model", REGISTERED)
def test_every_registered_model_passes_the_checks_a_model_of_ones_own_must_pass(model):
    check_model(MODELS[model])


@pytest.mark.parametrize("model", REGISTERED)
def test_every_model_runs_through_simulate_and_sample_on_its_lattice(model):
    chain = lattice_of(model)
    params = SceneParameters(model=model, energy=energy_of(model), excited_site=8, t_final=2.0, dt=0.01,
                             observables=("participation", "mlce"))
    ds = simulate(chain, params)
    assert ds.attrs["model"] == model and ds.attrs["max_energy_error"] < 1e-6
    assert ds.sizes["site"] == N and np.isfinite(ds["participation"]).all()
    # the same orbit through the problem object and the driver
    problem = Problem(model, [chain], integrator=params.integrator, dt=params.dt)
    q, p, _ = initial_state(MODELS[model], chain, params.energy, 8)
    dq, dp = initial_deviation(N, 0)
    samples = sample(problem, q[:, None], p[:, None], dq[:, None], dp[:, None], params.sample_steps())
    assert samples.energy_error[0, -1] == ds.attrs["final_energy_error"]  # the same orbit, to the bit


@pytest.mark.parametrize("model", REGISTERED)
def test_a_lattice_of_the_wrong_kind_is_refused_saying_how_to_make_the_right_one(model):
    wrong = random_chain(3, 5.0, N) if MODELS[model].lattice == "kg" else kg_chain(3, 4.0, N)
    make = "kg_chain(seed, W, N)" if MODELS[model].lattice == "kg" else "random_chain(seed, alpha, N)"
    params = SceneParameters(model=model, energy=energy_of(model), excited_site=8, t_final=1.0, dt=0.01,
                             observables=("participation",))
    with pytest.raises(ParameterError, match=rf"chains = \[.{type(wrong).__name__}.\].*{model!r}.*{re.escape(make)}"):
        simulate(wrong, params)


@pytest.mark.slow
def test_every_model_runs_through_run_study_and_the_command_line(tmp_path):
    study = run_study({"name": "every_model", "lattice": {"model": REGISTERED, "N": N, "alpha": 5.0, "W": 4.0,
                                                          "realizations": 2},
                       "excitation": {"energies": [0.4]}, "integration": {"t_final": 2.0, "dt": 0.01},
                       "observables": ["participation"]})
    assert sorted(study.model.values) == REGISTERED
    assert np.isfinite(study["mean_log10_participation"].isel(time=-1)).all()
    chain = tmp_path / "chain.nc"
    cli = [sys.executable, "-m", "chainchaos"]
    subprocess.run([*cli, "chain", "--seed", "3", "--N", str(N), "--out", str(chain)], check=True, timeout=300)
    for model in REGISTERED:
        lattice = ["--W", "4", "--seed", "3", "--N", str(N)] if MODELS[model].lattice == "kg" else ["--chain", str(chain)]
        out = tmp_path / f"{model}.nc"
        done = subprocess.run([*cli, "simulate", "--model", model, *lattice, "--energy", str(energy_of(model)),
                               "--site", "8", "--t-final", "1", "--dt", "0.01", "--observables", "participation",
                               "--out", str(out)], capture_output=True, text=True, timeout=600)
        assert done.returncode == 0 and out.stat().st_size > 0, done.stderr
    done = subprocess.run([*cli, "simulate", "--model", "kg", "--chain", str(chain), "--energy", "0.4", "--t-final",
                           "1", "--out", str(tmp_path / "x.nc")], capture_output=True, text=True, timeout=300)
    assert done.returncode == 2 and "option --chain" in done.stderr and "--W" in done.stderr


# ---- a model of one's own -------------------------------------------------------------------------

MORSE = '''
"""A Morse bond V(D) = K2 (1 - exp(a D))^2 / (2 a^2), D the compression: stiffness K2 at rest."""
import numpy as np
from numba import njit
from chainchaos import Model

A = {A}
INV_A, HALF_INV_A2 = 1.0 / A, 0.5 / (A * A)


@njit(cache=True)
def force(P, left, right):
    e = np.expm1((left - right) * A)
    return P[0] * INV_A * e * (e + 1.0)


@njit(cache=True)
def force_stiffness(P, left, right):
    e = np.expm1((left - right) * A)
    return P[0] * INV_A * e * (e + 1.0), P[0] * (e + 1.0) * (e * 2.0 + {TWO_OR_BROKEN})


@njit(cache=True)
def potential(P, left, right):
    e = np.expm1((left - right) * A)
    return P[0] * HALF_INV_A2 * e * e{REST}


def parameters(chain):
    return (chain.K2,)


MORSE = Model(name="{NAME}", label="Morse", colour="#2e7d32", parameter_names=("K2",), parameters=parameters,
              force=force, force_stiffness=force_stiffness, potential=potential)
'''


def morse_file(path, name="morse", A=2.0, stiffness="1.0", rest=""):
    path.write_text(MORSE.format(A=A, TWO_OR_BROKEN=stiffness, REST=rest, NAME=name))
    return path


# Each breaks one rule: the check that must refuse it.
BROKEN = {
    "stiffness = df/dD": {"stiffness": "1.5"},
    "rest": {"rest": " + P[0] * 1e-3"},
}


def test_a_stiffness_wrong_in_its_seventh_digit_is_refused(tmp_path):
    """The derivatives are checked against scipy.differentiate.derivative's adaptive estimate and
    its own error, not a fixed step and tolerance (which let 1e-6 relative through)."""
    path = morse_file(tmp_path / "slightly.py", name="slightly", stiffness="1.0000001")
    with pytest.raises(ModelCheckError, match="check 'stiffness = df/dD'"):
        load_model(f"{path}:MORSE")


@pytest.mark.parametrize("check", sorted(BROKEN))
def test_a_model_that_breaks_a_rule_is_refused_with_the_check_named(tmp_path, check):
    name = f"broken_{sorted(BROKEN).index(check)}"
    path = morse_file(tmp_path / f"{name}.py", name=name, **BROKEN[check])
    with pytest.raises(ModelCheckError, match=f"check {check!r}") as info:
        load_model(f"{path}:MORSE")
    assert info.value.check == check and name not in MODELS


def _law(force, stiffness, potential, name):
    return Model(name=name, label=name, colour="#000000", parameter_names=("K2",), parameters=lambda c: (c.K2,),
                 force=force, force_stiffness=stiffness, potential=potential)


def test_a_kernel_without_a_vector_version_is_refused_by_the_lanes_check_naming_the_operation():
    from numba import njit

    @njit
    def force(P, left, right):
        return -(P[0] * (right - left))  # K2 D, by a unary minus: the engines' vectors have none

    @njit
    def stiffness(P, left, right):
        return -(P[0] * (right - left)), P[0] * 1.0

    @njit
    def potential(P, left, right):
        return (left - right) * (left - right) * P[0] * 0.5

    with pytest.raises(ModelCheckError, match=r"check 'lanes'.*neg\(Vector"):
        check_model(_law(force, stiffness, potential, "negated"))
    assert list(CHECKS)[-1] == "lanes"


def test_a_wrong_force_is_refused_and_a_taken_name_too():
    from numba import njit

    @njit
    def force(P, left, right):
        return P[0] * (left - right) * 2.0  # twice dV/dD

    @njit
    def stiffness(P, left, right):
        return P[0] * (left - right) * 2.0, P[0] * 2.0

    @njit
    def potential(P, left, right):
        return (left - right) * (left - right) * P[0] * 0.5

    with pytest.raises(ModelCheckError, match=r"check 'force = dV/dD'"):
        add_model(_law(force, stiffness, potential, "twice"))
    with pytest.raises(ParameterError, match="model name = 'hertz'"):
        add_model(_law(force, stiffness, lambda P, left, right: (left - right) * (left - right) * P[0], "hertz"))
    assert MODELS["hertz"] is load_model("hertz")


def test_a_model_from_a_users_file_runs_from_python_and_a_study_file(tmp_path):
    morse_file(tmp_path / "morse_a.py", name="morse_a")
    (tmp_path / "morse_study.yaml").write_text(
        "lattice: {model: morse_a.py:MORSE, N: 16, alpha: 5.0, realizations: 2}\n"
        "excitation: {energies: [0.5]}\nintegration: {t_final: 5.0, dt: 0.01}\nobservables: [participation]\n")
    study = run_study(str(tmp_path / "morse_study.yaml"))  # the file found beside the study file
    assert list(study.model.values) == ["morse_a"] and MODELS["morse_a"].label == "Morse"
    scene = simulate(random_chain(879, 5.0, N), SceneParameters(model=MODELS["morse_a"], energy=0.5, excited_site=8,
                                                                t_final=5.0, dt=0.01, observables=("participation",)))
    assert scene.attrs["model"] == "morse_a" and scene.attrs["max_energy_error"] < 1e-6


USER_RUN = '''
import sys
from chainchaos import SceneParameters, random_chain, simulate
for reference in sys.argv[1:]:
    ds = simulate(random_chain(seed=879, alpha=5.0, N=16), SceneParameters(model=reference, energy=1.0,
                  excited_site=8, t_final=5.0, dt=0.01, observables=("participation",)))
    print(repr(float(ds["participation"][-1])))
'''


@pytest.mark.slow
def test_an_edited_model_gets_new_kernels_and_two_models_of_one_name_share_none(tmp_path):
    """Numba's cache keys a compiled engine by its argument types, and a model's type is named by
    the model's identity (name, kernels' modules, their sources): an edited kernel gives the numbers
    of a fresh cache, not the old ones, and two models named alike from two modules differ."""

    def run(*references, cache="cache"):
        env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / cache)}
        done = subprocess.run([sys.executable, "-c", USER_RUN, *references], env=env, cwd=tmp_path,
                              capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stderr[-3000:]
        return [float(x) for x in done.stdout.split()]

    morse_file(tmp_path / "mine.py", A=2.0)
    (before,) = run("mine.py:MORSE")
    morse_file(tmp_path / "mine.py", A=3.0)  # the kernels change, the name stays
    (after,) = run("mine.py:MORSE")
    (fresh,) = run("mine.py:MORSE", cache="fresh")
    assert after == fresh and after != before
    # "morse" again, from another module, in the same process: refused, never another's kernels
    morse_file(tmp_path / "other.py", A=2.0)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    done = subprocess.run([sys.executable, "-c", USER_RUN, "mine.py:MORSE", "other.py:MORSE"], env=env,
                          cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert done.returncode != 0 and "model name = 'morse'" in done.stderr and "mine" in done.stderr
    assert run("other.py:MORSE") == [before]  # alone, other.py's Morse (a = 2) gives a = 2's numbers
