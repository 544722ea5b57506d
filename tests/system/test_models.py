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
from chainchaos.system.models import BOND_MODELS, MODELS, energy_kernel, get_model, model_label, total_energy
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


@pytest.mark.parametrize("name", sorted(BOND_MODELS))
def test_force_is_the_derivative_of_the_potential_and_stiffness_that_of_the_force(name):
    model = MODELS[name]
    D = np.random.default_rng(0).uniform(-0.3, 0.3, CHAIN.N + 1) * CHAIN.delta
    h = 1e-5 * CHAIN.delta
    (_, f, k), (Vp, fp, _), (Vm, fm, _) = law(model, D), law(model, D + h), law(model, D - h)
    f_rest = law(model, np.zeros(CHAIN.N + 1))[1]
    np.testing.assert_allclose((Vp - Vm) / (2 * h), f - f_rest, rtol=1e-7, atol=1e-12)
    np.testing.assert_allclose((fp - fm) / (2 * h), k, rtol=1e-7, atol=1e-12)


@pytest.mark.parametrize("name", sorted(BOND_MODELS))
def test_every_model_is_at_rest_at_zero_compression_with_the_linear_stiffness_K2(name):
    V, f, k = law(MODELS[name], np.zeros(CHAIN.N + 1))
    np.testing.assert_allclose(V, 0.0, atol=1e-15)
    np.testing.assert_allclose(f, f[0], rtol=1e-15)  # no net force on any bead
    np.testing.assert_allclose(k, CHAIN.K2, rtol=1e-15)


@pytest.mark.parametrize("name", sorted(BOND_MODELS))
def test_every_model_fits_the_engines_and_is_labelled(name):
    model = MODELS[name]
    assert model.name == name and get_model(name) is model and model_label(name) == model.label
    chain = lattice(model)
    P = model.bond_parameters(chain)
    assert P.shape == (len(model.parameter_names), chain.N + 1) and P.flags.c_contiguous
    assert total_energy(model, chain, np.zeros(chain.N), np.zeros(chain.N)) == 0.0


@pytest.mark.parametrize("name", sorted(BOND_MODELS))
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
