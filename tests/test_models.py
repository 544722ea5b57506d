"""The model registry (chainchaos.system.models): every bond law against exact properties.

Each registered model is checked the same way, so a new model is tested by its registry line:
its force is the derivative of its potential (up to the precompression force f(0), the same on
every bond, so that the chain is at rest at D = 0 and the walls take it), its stiffness the
derivative of its force, its stiffness at rest is the chain's K2 (the common linear limit), and
its parameters fit the engines' rows.
"""

import os

import numpy as np
import pytest
from numba import njit

from chainchaos.errors import ParameterError
from chainchaos.system.chain import kg_chain, random_chain
from chainchaos.system.models import MAX_BOND_PARAMETERS, MODELS, energy_kernel, get_model, model_label, total_energy
from chainchaos.system.models.base import bond_force, bond_force_stiffness, bond_potential

CHAIN = random_chain(879, 5.0, 40)
KG = kg_chain(879, 4.0, 40)


def lattice(model):
    """The lattice a model's parameters come from: the bead chain CHAIN, or a KG lattice (whose
    harmonic coupling K2 the bond-law tests below do not use: they take CHAIN's bond parameters)."""
    return CHAIN if model.lattice == "beads" else KG


def extra(model, chain):
    """The site parameters of a model with a site law, as the optional last argument."""
    sites = model.site_parameters(chain)
    return () if sites is None else (sites,)


@njit
def _law(model, P, D):
    """(V, f, k, f alone) of every bond b at compression D[b] (left = D, right = 0)."""
    out = np.empty((4, D.size))
    for b in range(D.size):
        bond = (P[0, b], P[1, b], P[2, b])
        out[0, b] = bond_potential(model, bond, D[b], 0.0)
        out[1, b], out[2, b] = bond_force_stiffness(model, bond, D[b], 0.0)
        out[3, b] = bond_force(model, bond, D[b], 0.0)
    return out


def law(model, D):
    """(V, f, k) of every bond at compressions D; the force alone is the force of the pair."""
    V, f, k, force = _law(model, model.bond_parameters(CHAIN), np.ascontiguousarray(D, dtype=float))
    np.testing.assert_array_equal(force, f)
    return V, f, k


@pytest.mark.parametrize("name", sorted(MODELS))
def test_force_is_the_derivative_of_the_potential_and_stiffness_that_of_the_force(name):
    model = MODELS[name]
    D = np.random.default_rng(0).uniform(-0.3, 0.3, CHAIN.N + 1) * CHAIN.delta
    h = 1e-5 * CHAIN.delta
    (_, f, k), (Vp, fp, _), (Vm, fm, _) = law(model, D), law(model, D + h), law(model, D - h)
    f_rest = law(model, np.zeros(CHAIN.N + 1))[1]
    np.testing.assert_allclose((Vp - Vm) / (2 * h), f - f_rest, rtol=1e-7, atol=1e-12)
    np.testing.assert_allclose((fp - fm) / (2 * h), k, rtol=1e-7, atol=1e-12)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_is_at_rest_at_zero_compression_with_the_linear_stiffness_K2(name):
    V, f, k = law(MODELS[name], np.zeros(CHAIN.N + 1))
    np.testing.assert_allclose(V, 0.0, atol=1e-15)
    np.testing.assert_allclose(f, f[0], rtol=1e-15)  # no net force on any bead
    np.testing.assert_allclose(k, CHAIN.K2, rtol=1e-15)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_fits_the_engines_and_is_labelled(name):
    model = MODELS[name]
    assert model.name == name and get_model(name) is model and model_label(name) == model.label
    chain = lattice(model)
    P = model.bond_parameters(chain)
    assert P.shape == (MAX_BOND_PARAMETERS, chain.N + 1)
    assert np.all(P[len(model.parameter_names):] == 0.0)
    assert total_energy(model, chain, np.zeros(chain.N), np.zeros(chain.N)) == 0.0


@pytest.mark.parametrize("name", sorted(MODELS))
def test_the_compiled_energy_is_the_energy(name):
    """energy_kernel (sums in order) and total_energy (NumPy's sums) differ only in rounding."""
    model = MODELS[name]
    rng = np.random.default_rng(3)
    u, p = 0.1 * rng.standard_normal(CHAIN.N), 0.1 * rng.standard_normal(CHAIN.N)
    chain = lattice(model)
    H = energy_kernel(model, u, p, chain.mass, model.bond_parameters(chain), np.empty(chain.N + 1),
                      *extra(model, chain))
    assert H > 0 and H == pytest.approx(total_energy(model, chain, u, p), rel=1e-14)


def test_models_have_distinct_labels_and_colours():
    assert len({m.label for m in MODELS.values()}) == len({m.colour for m in MODELS.values()}) == len(MODELS)


def test_an_unknown_model_is_refused_by_name():
    with pytest.raises(ParameterError, match="'morse'.*one of"):
        get_model("morse")


# ---- a model of one's own: its kernels keyed by its identity, never stale -------------------------

USER_MODEL = '''
from numba import njit
from chainchaos.system.models.base import Model
C = {C}

@njit(cache=True)
def force(P, left, right):
    D = left - right
    return C * D * (P[0] - D * (P[1] - D * P[2]))

@njit(cache=True)
def force_stiffness(P, left, right):
    D = left - right
    return C * D * (P[0] - D * (P[1] - D * P[2])), C * (P[0] - D * (2.0 * P[1] - 3.0 * P[2] * D))

@njit(cache=True)
def potential(P, left, right):
    y = right - left
    return C * y * y * (0.5 * P[0] + y * (P[1] / 3.0 + 0.25 * P[2] * y))

def parameters(chain):
    return chain.K2, chain.K3, chain.K4

MODEL = Model("mine", "Mine", "#000000", ("K2", "K3", "K4"), parameters, force, force_stiffness, potential)
'''

USER_RUN = '''
import sys
sys.path.insert(0, sys.argv[1])
from chainchaos import SceneParameters, random_chain, simulate
from chainchaos.system.models import MODELS
for module in sys.argv[2:]:
    MODELS["mine"] = __import__(module).MODEL
    ds = simulate(random_chain(seed=879, alpha=5.0, N=16), SceneParameters(model="mine", energy=1.0,
                  excited_site=8, t_final=5.0, dt=0.01, observables=("participation",)))
    print(repr(float(ds["participation"][-1])))
'''


@pytest.mark.slow
def test_a_model_of_one_s_own_gets_new_kernels_after_an_edit_and_shares_none_by_name(tmp_path):
    """Numba's cache keys a compiled engine by its argument types, and a model's type is named by
    the model's identity (name, kernels' modules, their sources): an edited kernel gives the numbers
    of a fresh cache, not the old ones, and two models named alike from two modules differ."""
    import subprocess
    import sys

    def run(*modules, cache="cache"):
        env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / cache)}
        done = subprocess.run([sys.executable, "-c", USER_RUN, str(tmp_path), *modules], env=env,
                              capture_output=True, text=True, timeout=600, check=True)
        return [float(x) for x in done.stdout.split()]

    (tmp_path / "mine.py").write_text(USER_MODEL.format(C=1.0))
    (before,) = run("mine")
    (tmp_path / "mine.py").write_text(USER_MODEL.format(C=1.5))  # the kernels change, the name stays
    (after,) = run("mine")
    (fresh,) = run("mine", cache="fresh")
    assert after == fresh and after != before
    (tmp_path / "other.py").write_text(USER_MODEL.format(C=1.0))  # "mine" again, from another module
    assert run("mine", "other") == [after, before]
