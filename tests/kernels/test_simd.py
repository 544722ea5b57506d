"""Explicit SIMD vectors (chainchaos.kernels.simd): every lane gets exactly its scalar operation."""

import numpy as np
import pytest
from numba import njit

from chainchaos.engine import model_checks
from chainchaos.kernels.simd import LANES, vbelow, vload, vnext, vprev, vstore
from chainchaos.system.chain import random_chain
from chainchaos.system.models import BOND_MODELS as MODELS

# normal numbers, signed zeros, subnormals, infinities and NaN in every operand position
SPECIAL = np.array([1.5, -2.25, 0.0, -0.0, 5e-324, -1e-310, np.inf, -np.inf, np.nan, 3.0e300, -7.0, 0.125])


def operands(n_vectors, seed):
    rng = np.random.default_rng(seed)
    x = np.concatenate([SPECIAL, rng.normal(scale=3.0, size=n_vectors * LANES - SPECIAL.size)])
    return rng.permutation(x), rng.permutation(x)


@njit
def _vector_ops(x, y, out):
    for i in range(0, x.size, LANES):
        a, b = vload(x, i), vload(y, i)
        vstore(out[0], i, a + b)
        vstore(out[1], i, a - b)
        vstore(out[2], i, a * b)
        vstore(out[3], i, 2.5 * a - b * 0.5 + 1)
        vstore(out[4], i, max(a, b))
        vstore(out[5], i, max(a, 0.0))
        vstore(out[6], i, np.sqrt(a))
        vstore(out[7], i, np.expm1(a))


@njit
def _scalar_ops(x, y, out):
    for i in range(x.size):
        a, b = x[i], y[i]
        out[0, i], out[1, i], out[2, i] = a + b, a - b, a * b
        out[3, i] = 2.5 * a - b * 0.5 + 1
        out[4, i], out[5, i] = max(a, b), max(a, 0.0)
        out[6, i] = np.sqrt(a)
        out[7, i] = np.expm1(a)


def test_each_lane_is_its_scalar_operation_bit_for_bit():
    x, y = operands(8, 0)
    vec, ref = np.full((8, x.size), 99.0), np.full((8, x.size), 99.0)
    with np.errstate(invalid="ignore"):
        _vector_ops(x, y, vec)
        _scalar_ops(x, y, ref)
    # same bits, NaN and the sign of zero included
    np.testing.assert_array_equal(vec.view(np.int64), ref.view(np.int64))


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_bond_law_compiles_for_vectors_and_agrees_with_the_scalar_one(name):
    model = MODELS[name]
    chain = random_chain(1, 5.0, 4 * LANES - 1)
    P = model.bond_parameters(chain)
    rng = np.random.default_rng(1)
    left, right = rng.normal(scale=0.7, size=(2, 4 * LANES))  # about half the Hertz bonds open
    vec, ref = np.zeros((5, left.size)), np.zeros((5, left.size))
    # the kernels of model_checks' lanes check: rows f, k, the force alone, the opening (1..4)
    model_checks._vector_laws(model, P, left, right, vec)
    model_checks._scalar_laws(model, P, left, right, ref)
    vec, ref = vec[1:], ref[1:]
    np.testing.assert_array_equal(vec.view(np.int64), ref.view(np.int64))
    np.testing.assert_array_equal(vec[2], vec[0])  # the force alone is the force of the pair
    if model.has_gaps:
        assert (vec[0] == 0).any() and (vec[0] > 0).any() and (vec[3] < 0).any()
    else:
        assert (vec[3] > 0).all() and (vec[0] != 0).all()


@njit
def _load_store(x, i, out, j):
    vstore(out, j, vload(x, i))


def test_load_and_store_move_lanes_elements_from_any_offset():
    x = np.arange(3.0 * LANES)
    out = np.zeros(3 * LANES)
    _load_store(x, 5, out, 3)
    np.testing.assert_array_equal(out[3:3 + LANES], x[5:5 + LANES])
    assert not out[:3].any() and not out[3 + LANES:].any()


def test_vectors_reject_arrays_they_are_not_made_for():
    with pytest.raises(Exception, match="vload"):
        _load_store(np.arange(3 * LANES, dtype=np.int64), 0, np.zeros(3 * LANES), 0)


@njit
def _windows(x, out):
    a, b = vload(x, 0), vload(x, LANES)
    vstore(out[0], 0, vnext(a, b))
    vstore(out[1], 0, vprev(a, b))
    vstore(out[2], 0, vbelow(a, 0.0))
    vstore(out[3], 0, vbelow(a, b))


def test_windows_shift_by_one_element_across_two_vectors_and_below_counts():
    x = np.array([3.0, -1.0, -0.0, np.nan, -np.inf, 2.0, -5e-324, 7.0] * (2 * LANES))[:2 * LANES]
    x[LANES:] = np.arange(LANES) - 1.5
    out = np.zeros((4, LANES))
    _windows(x, out)
    np.testing.assert_array_equal(out[0], x[1:1 + LANES])
    np.testing.assert_array_equal(out[1], x[LANES - 1:2 * LANES - 1])
    with np.errstate(invalid="ignore"):
        np.testing.assert_array_equal(out[2], (x[:LANES] < 0.0).astype(float))  # NaN: not below
        np.testing.assert_array_equal(out[3], (x[:LANES] < x[LANES:]).astype(float))
