"""The same numbers on every x86-64: correctly rounded chain parameters, a deterministic
eigensolver and products (chainchaos.kernels.exactmath, chainchaos.system.linear), and bit-for-bit checks.

The tests named ``*_bit_for_bit`` are reproducibility tests: the numbers they hold are this code's
own output (written on an AMD Zen 5 with AVX-512), not independent reference values. They must come
out the same on every x86-64 CPU with FMA: test_same_bits_in_an_emulated_avx2_build reruns them
with NumPy, Numba and OpenBLAS set up as on an AVX2-only CPU. A deliberate change of the numerics
(another order of operations in a kernel, another chain or scene) changes them; regenerate them
then with the functions below, and say so in the commit.
"""

import hashlib
import itertools
import math
import os
import subprocess
import sys
from decimal import Decimal, localcontext
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import eigh_tridiagonal

from chainchaos import Chain, chain_from_radii, random_chain
from chainchaos.engine.integrators import advance, get_scheme
from chainchaos.kernels import exactmath
from chainchaos.kernels.cache import kernel_key
from chainchaos.observe.registry import model_observables
from chainchaos.records.io import chain_dataset
from chainchaos.records.provenance import EMULATED_AVX2
from chainchaos.run.driver import sample_steps
from chainchaos.run.scenes import SceneParameters, simulate
from chainchaos.system.chain import sonic_vacuum_chain
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.linear import tridiagonal_eigh
from chainchaos.system.models import get_model

ROOT = Path(__file__).resolve().parents[2]

# ---- correctly rounded chain parameters --------------------------------------------------------


def decimal_bond(r_left: float, r_right: float) -> list[float]:
    """(A, delta, K2, K3, K4) from the formulas of chainchaos.system.chain evaluated with 60 decimal
    digits on the exact values of the double radii, each rounded once to a double."""
    with localcontext() as ctx:
        ctx.prec = 60
        a, b = Decimal(r_left), Decimal(r_right)  # exact: a double is a finite decimal
        A = (2 * a * b / (a + b)).sqrt() / 6
        delta = (Decimal(1) / 6 / A) ** (Decimal(2) / 3)
        K2 = Decimal("1.5") * A * delta.sqrt()
        K3 = -Decimal("0.375") * A / delta.sqrt()
        K4 = A * delta ** Decimal("-1.5") / 16
        return [float(x) for x in (A, delta, K2, K3, K4)]


CHAINS = {
    "seed 5346, alpha 5": lambda: random_chain(5346, 5.0, 40),
    "seed 879, alpha 5": lambda: random_chain(879, 5.0, 40),
    "seed 0, alpha 2": lambda: random_chain(0, 2.0, 40),
    "seed 17, alpha 20, wall 0.3": lambda: random_chain(17, 20.0, 12, wall_radius=0.3),
    "radii in mm, wall 1.7": lambda: chain_from_radii([2.0, 3.5, 7.25, 1.0, 4.125], wall_radius=1.7),
    "homogeneous": lambda: Chain(np.ones(40), 1.0),
}


@pytest.mark.parametrize("name", CHAINS)
def test_chain_parameters_are_correctly_rounded(name):
    chain = CHAINS[name]()
    ext = [chain.wall_radius, *chain.radius.tolist(), chain.wall_radius]
    for b, (left, right) in enumerate(zip(ext[:-1], ext[1:])):
        expected = decimal_bond(left, right)
        got = [float(getattr(chain, key)[b]) for key in ("A", "delta", "K2", "K3", "K4")]
        assert got == expected, (name, b, left, right)
    for n, r in enumerate(chain.radius.tolist()):
        assert chain.mass[n] == float(Fraction(r) ** 3), (name, n, r)
    taylor = chain.with_k4_sign(-1)
    assert np.array_equal(taylor.K4, -chain.K4) and taylor.k4_sign == -1.0
    assert np.array_equal(taylor.with_k4_sign(1).K4, chain.K4)


@pytest.mark.parametrize("name", CHAINS)
def test_bond_values_are_the_columns_entries(name):
    """A few bonds' parameters, asked for before or after their column is computed, are the
    column's entries (K4 with the chain's sign; a precompressed chain's own delta)."""
    for chain in (CHAINS[name](), CHAINS[name]().with_k4_sign(-1), sonic_vacuum_chain(CHAINS[name]())):
        bonds = (0, 2, chain.N)
        early = {key: chain.bond_values(key, bonds) for key in ("A", "delta", "K2", "K3", "K4")}
        for key, values in early.items():
            column = getattr(chain, key)
            assert values.tolist() == column[list(bonds)].tolist() == chain.bond_values(key, bonds).tolist(), key


def test_homogeneous_chain_parameters_are_exact():
    chain = Chain(np.ones(6), 1.0)
    assert np.all(chain.mass == 1.0) and np.all(chain.delta == 1.0) and np.all(chain.K2 == 0.25)
    assert np.all(chain.K3 == -0.0625) and np.all(chain.A == 1 / 6) and np.all(chain.K4 == 1 / 96)


def test_roots_round_to_nearest_with_ties_to_even():
    m = 2**53 + 1  # 54 bits: exactly halfway between the doubles 2^53 and 2^53 + 2
    assert exactmath.root(m * m, 1, 2) == 2.0**53  # tie: to even
    assert exactmath.root(m**3, 1, 3) == 2.0**53
    assert exactmath.root(m * m + 1, 1, 2) == 2.0**53 + 2  # just above the midpoint: up
    assert exactmath.root(m**3 - 1, 1, 3) == 2.0**53  # just below: down
    assert exactmath.root(27, 8, 3) == 1.5 and exactmath.root(2, 1, 2) == math.sqrt(2.0)
    with localcontext() as ctx:
        ctx.prec = 60
        for num, den in itertools.product((1, 2, 3, 10, 2**70 + 1), (1, 3, 7, 10**20)):
            assert exactmath.root(num, den, 3) == float((Decimal(num) / den) ** (Decimal(1) / 3))
            assert exactmath.root(num, den, 2) == float((Decimal(num) / den).sqrt())


# ---- deterministic linear algebra and elementwise functions -----------------------------------


def tridiagonal(chain):
    K2, m = chain.K2, chain.mass
    return (K2[:-1] + K2[1:]) / m, -K2[1:-1] / np.sqrt(m[:-1] * m[1:])


@pytest.mark.parametrize("seed", [879, 5346])
def test_eigensolver_agrees_with_scipy(seed):
    diag, off = tridiagonal(random_chain(seed, 5.0, 40))
    w, V = tridiagonal_eigh(diag, off)
    w_ref, V_ref = eigh_tridiagonal(diag, off)
    assert np.abs(w - w_ref).max() < 1e-13
    V_ref = V_ref * np.sign(np.sum(V * V_ref, axis=0))
    assert np.abs(V - V_ref).max() < 1e-12
    assert np.abs(V.T @ V - np.eye(40)).max() < 1e-13


def test_eigensolver_small_and_degenerate_matrices():
    assert tridiagonal_eigh(np.array([2.0]), np.empty(0))[0].tolist() == [2.0]
    w, V = tridiagonal_eigh(np.array([1.0, 1.0, 5.0]), np.array([0.0, 0.0]))  # diagonal, a double eigenvalue
    assert w.tolist() == [1.0, 1.0, 5.0] and np.array_equal(np.abs(V), np.eye(3))
    w, _ = tridiagonal_eigh(np.full(5, 2.0), np.full(4, -1.0))
    assert np.allclose(w, 2 - 2 * np.cos(np.arange(1, 6) * np.pi / 6), atol=1e-15, rtol=0)


def test_matmul_and_norm_keep_the_shapes_of_blas():
    rng = np.random.default_rng(4)
    U, v = rng.normal(size=(7, 5)), rng.normal(size=7)
    for a in (rng.normal(size=7), rng.normal(size=(3, 7)), rng.normal(size=(2, 3, 7))):
        for b in (U, v):
            got, ref = exactmath.matmul(a, b), a @ b
            assert np.shape(got) == np.shape(ref) and np.allclose(got, ref, rtol=1e-14, atol=1e-14)
    assert exactmath.norm(v) == pytest.approx(np.linalg.norm(v), rel=1e-15)
    a = rng.normal(size=(4, 7))
    assert exactmath.matmul(a, U)[2, 3] == sum(a[2, n] * U[n, 3] for n in range(7))  # summed in order


def test_logarithm_is_accurate_to_one_ulp():
    """exactmath.ln (fdlibm's algorithm in IEEE operations) against 40-digit logarithms."""
    rng = np.random.default_rng(6)
    x = np.concatenate([rng.uniform(1e-6, 1e3, 400), np.exp(rng.uniform(-700, 700, 200)),
                        1.0 + rng.uniform(-1e-6, 1e-6, 200), rng.uniform(0.7, 1.45, 400),
                        [5e-324, 2.0**-1022, 0.5, 1.0, 2.0, 10.0, 1e308],
                        [np.nextafter(1.0, 2.0), np.nextafter(1.0, 0.0)]])
    with localcontext() as ctx:
        ctx.prec = 40
        for value, got in zip(x.tolist(), exactmath.log(x).tolist()):
            exact = Decimal(value).ln()
            assert abs(Decimal(got) - exact) < Decimal(math.ulp(float(exact)) if exact else 5e-324), value
    assert exactmath.log(1.0) == 0.0 and exactmath.log(2.0) == math.log(2.0)
    assert np.array_equal(exactmath.log(np.array([0.0, -1.0, np.inf, np.nan])), [-np.inf, np.nan, np.inf, np.nan],
                          equal_nan=True)


def test_log10_and_exp10_are_the_c_library_scalars():
    x = np.random.default_rng(5).uniform(1e-6, 1e3, 2000)
    assert exactmath.log10(x).tolist() == [math.log10(v) for v in x]
    assert exactmath.exp10(x[:300] / 100).tolist() == [10.0 ** (v / 100) for v in x[:300]]
    assert exactmath.log(x.reshape(40, 50)).shape == (40, 50) and isinstance(exactmath.log(2.0), float)


def test_small_arrays_take_the_same_c_functions_from_python():
    """Up to SCALAR_LOOP_MAX elements log10 and exp10 run in Python, beyond it in the Numba loop:
    the same bits either way, at the edges (zeros, negatives, infinities, NaNs, overflow) too."""
    x = np.array([0.0, -0.0, -1.0, np.inf, -np.inf, np.nan, -np.nan, 1e-320, 5.0, 1e300, 0.1])
    y = np.array([-400.0, 400.0, 308.3, -323.5, np.nan, -np.nan, np.inf, -np.inf, 0.0, 1.5, -0.7])
    for values, python, loop in ((x, exactmath.log10, exactmath._log10_loop),
                                 (y, exactmath.exp10, exactmath._exp10_loop)):
        assert values.size <= exactmath.SCALAR_LOOP_MAX
        assert np.array_equal(python(values).view(np.uint64), exactmath._elementwise(loop, values).view(np.uint64))
    big = np.random.default_rng(6).uniform(-3.0, 3.0, exactmath.SCALAR_LOOP_MAX + 1)
    assert exactmath.exp10(big).tolist() == [10.0 ** v for v in big]
    assert exactmath.exp10(big[:3]).tolist() == exactmath.exp10(big)[:3].tolist()


def test_sample_steps_are_those_of_the_numpy_version():
    """The same step indices as the former NumPy version (np.log10 and 10.0 ** array) for the
    step sizes, spans and densities of config/*.yaml (digest of its output)."""
    digest = hashlib.sha256()
    for t_final, dt, per_decade, t_first in itertools.product([1e3, 1e4, 1e5, 1e6], [5e-4, 5e-3, 1e-2],
                                                             [10, 40], [0.1, 1.0]):
        digest.update(sample_steps(t_final, dt, per_decade, t_first).astype("<i8").tobytes())
    assert digest.hexdigest() == "3c7905f62735e1c889ee8b88dfb28e9957224215c65b3d7c862e7bf3dd137520"


def test_provenance_records_the_machine(chain):
    attrs = simulate(chain, SceneParameters(model="fput", energy=0.1, t_final=1.0, dt=0.1, observables=("participation",))).attrs
    for key in ("cpu_model", "cpu_vector_extensions", "numpy_simd_targets", "numba_target_cpu",
                "python_version", "numpy_version", "numba_version", "llvmlite_version", "scipy_version",
                "xarray_version", "git_commit", "chainchaos_version", "parameters"):
        assert isinstance(attrs[key], str) and attrs[key], key
    if os.environ.get("NUMBA_CPU_NAME"):
        assert attrs["numba_target_cpu"] == os.environ["NUMBA_CPU_NAME"]


# ---- bit for bit --------------------------------------------------------------------------------


def digest_arrays(arrays: dict) -> str:
    """SHA-256 of named arrays: name, dtype, shape and little-endian bytes, by name."""
    digest = hashlib.sha256()
    for name in sorted(arrays):
        a = np.asarray(arrays[name])
        a = np.ascontiguousarray(a.astype(a.dtype.newbyteorder("<")))
        digest.update(f"{name}|{a.dtype.str}|{a.shape}|".encode() + a.tobytes())
    return digest.hexdigest()


def chaotic_orbit(model_name: str, energy: float, t_final: float = 200.0, dt: float = 0.01):
    """(q, p, ln|v(t)|) at t_final of the scene's orbit on random_chain(5346, 5, 40), bead 21
    excited, SRKN6b with the tangent map from the deviation vector of seed 0."""
    chain = random_chain(5346, 5.0, 40)
    model, N = get_model(model_name), chain.N
    q, p, _ = initial_state(model, chain, energy, 21)
    dq, dp = initial_deviation(N, 0)
    scheme, diagnostics = get_scheme("SRKN6b"), np.zeros(2)
    bad = advance(model, q, p, dq, dp, 1.0 / chain.mass, model.bond_parameters(chain), scheme.kicks,
                  scheme.drifts, dt, round(t_final / dt), True, 1000, False, np.zeros(N + 1, dtype=np.int64),
                  diagnostics, np.empty(N + 1), np.empty(N + 1))
    assert bad == -1
    return q, p, float(diagnostics[0])


def hex_block(values) -> str:
    """The float.hex strings of ``values``, space-separated (how the expected orbits are stored)."""
    return " ".join(float(x).hex() for x in values)


CHAIN_5346_DIGEST = "50326c3319669c885819c00ec9927668eee2dbb8cd659668513bc163f5878129"
CHAIN_FILE_DIGEST = "6c4cd055a21f3e04e17cb71ddc0a7026eee8b15b3e8ce5744cacead80a270887"
SCENE_DIGESTS = {
    "hertz": "a1c14ac44c7fe60a18532109014f5b855b9589ac30022f062d74bb6458e383cb",
    "fput": "f9d5a357b0b1c23811951ba1834402cd5d08738e93832f83117649d71ae5cbb3",
}
#: model: (energy, ln|v(t)| at t = 200, q, p as float.hex strings)
ORBITS = {
    "fput": (
        8.7381,
        "0x1.e4620ba5bd440p-1",
        "0x1.e0c90adb5e78bp-3 0x1.ce7adbc0fdbd3p-2 0x1.07ae12e4603dbp-1 0x1.edd8ddc597762p-2 "
        "0x1.c6ccf112fed07p-2 0x1.a1105d7dc3159p-2 0x1.6e1077bff3c16p-2 0x1.29edc42c1ca37p-2 "
        "0x1.19e844cf6c981p-4 -0x1.62bb9e72ba9a8p-3 -0x1.78c21e244c4bfp-2 -0x1.d6553bee4269ap-2 "
        "-0x1.6e5119857ca2cp-1 -0x1.8960b758916c1p-1 -0x1.99369ce808e8dp-1 -0x1.15ea8cacd207cp-2 "
        "-0x1.33099676686e4p-1 -0x1.90f7a09507216p-2 0x1.069cf394cb412p-1 -0x1.94d69dc383744p-1 "
        "0x1.378d73916a299p+1 0x1.17f066ca69142p+1 0x1.7686c8132b8ccp+0 0x1.f6e95a2cc5697p-1 "
        "0x1.405f005115755p-1 0x1.5701ddb6417a3p-1 0x1.88eae366a784dp-1 0x1.6d92b1c43590ep-1 "
        "0x1.3ca51099392a5p-1 0x1.eef80844dd687p-2 0x1.0ae627d8f76bap-2 -0x1.0a015224891d8p-10 "
        "-0x1.58768666d3f88p-3 -0x1.577601d2e2e8ap-2 -0x1.a4950885d8aaep-2 -0x1.aef612f06f103p-2 "
        "-0x1.04e9ce0a445b6p-2 -0x1.124b65959c2b0p-4 0x1.7c270341b4ae9p-4 0x1.cb88496199251p-5",
        "-0x1.f545c2e84b11bp-10 -0x1.60b492c38abd4p-6 -0x1.12e9d099511f1p-6 0x1.dcb6203c1f5afp-9 "
        "0x1.a5e4892dc2164p-7 0x1.f9e836b92a127p-16 0x1.a0c2bfa9123b8p-7 0x1.a0844ad62fc8fp-4 "
        "0x1.117c2288fba02p-7 0x1.7b1c4e666df49p-6 0x1.5ab13470935efp-3 -0x1.121c8322f3a9bp-3 "
        "-0x1.a652b5244f9b7p-2 -0x1.cd46279d8677fp-6 -0x1.f2bae74aaebd8p-3 -0x1.1177944cc6823p-2 "
        "-0x1.2dba3c120362fp-3 -0x1.1b8a27d2c2e7ap-1 0x1.2e8d47f7a3448p-3 0x1.34f578d50bb6ep+0 "
        "-0x1.d24a2f146c2afp+0 0x1.d5f85f6594aa3p-1 -0x1.a1c22ba873b11p-10 -0x1.c06ac3d7ae50ap-5 "
        "0x1.d6aa4096426e9p-2 0x1.c0e56a8c2050ep-5 0x1.2772e294bc54bp-1 0x1.f1247acfc84d4p-5 "
        "0x1.524a1b9a22cf3p-4 0x1.02f3420283beep-2 0x1.e7821f95b40e4p-5 -0x1.189ae9a492f9cp-3 "
        "-0x1.d52318e3db1b0p-10 0x1.a245a5efc7c4cp-8 0x1.6b5f10ffc9977p-6 0x1.4bed798b7b9ebp-4 "
        "0x1.ef38ee381df19p-9 0x1.0a0261bb6806ap-9 -0x1.7308b291498fep-5 -0x1.fcbf6b0930936p-9",
    ),
    "hertz": (
        3.0,
        "0x1.bff20b60cd246p+2",
        "0x1.64540da1aa128p-10 -0x1.bb2b2fa29f836p-8 -0x1.8876ea5cd3e4ep-4 -0x1.77a4c06b75741p-4 "
        "-0x1.e4460cba44963p-4 -0x1.e6d2c97dd56b8p-3 -0x1.77c594b564e60p-2 -0x1.0adaee35c6ad4p-1 "
        "-0x1.fb3180483c071p-2 -0x1.d27460d5f6900p-2 -0x1.025a80ff41fa1p-1 -0x1.e26873770983ap-1 "
        "-0x1.96bdbe36a2be4p+0 -0x1.e09e6d3bcf10fp-1 -0x1.58982cce8ec0dp-4 0x1.47d0d50cc88edp-1 "
        "0x1.1b625632f0750p+1 0x1.5b17938133a98p+1 0x1.3a073cf71ed8fp+0 0x1.595b4c5273771p+1 "
        "0x1.2231820417d79p+0 0x1.703f891078e7dp-1 0x1.ee940f121311fp-2 0x1.5ef3a826f3c92p-1 "
        "0x1.aef4112580a26p-1 0x1.1b47cf664a738p+0 0x1.4f0ca8000692cp+0 0x1.fb6456d47197bp-1 "
        "0x1.58d385547c694p-1 0x1.fb40ec6f48355p-2 0x1.d9fc545b7a424p-2 0x1.44ab795d55cb2p-1 "
        "0x1.6acea8463ed32p-1 0x1.93d735cfc92abp-1 0x1.d429247348ab4p-1 0x1.f4e45a5324d5cp-1 "
        "0x1.a6f3610bb397dp-1 0x1.66dbb9e0e7ee5p-1 0x1.5bc6387d88b41p-1 0x1.3c99cb079dc32p-2",
        "-0x1.3a38148b02383p-7 -0x1.b66baaa8cb880p-4 -0x1.54f4e0ea95cfdp-4 0x1.d07afb5ec9113p-8 "
        "0x1.3326dee4c6461p-4 0x1.96f7da807438fp-4 0x1.e2f90862be56fp-6 -0x1.4ba1a013518f4p-2 "
        "-0x1.a3fb05c5e1667p-6 -0x1.faa8b92afe9ccp-5 -0x1.9138b665b5a6ap-3 -0x1.68ef5039472c2p-3 "
        "0x1.ebcd2d186e6adp-2 -0x1.d333015096704p-6 0x1.99f9671bc9720p-1 0x1.6199993b4f120p-2 "
        "0x1.cf8acd2f9925dp-2 -0x1.2db01c27b90a1p-2 0x1.8d1aa1a441a55p-2 0x1.27b021f56bd54p-3 "
        "-0x1.182955bb1af95p-1 0x1.f1d7a326c6c89p-3 0x1.a084133809158p-2 -0x1.2c105738e3fbbp-6 "
        "-0x1.44a40f892a329p+0 -0x1.b5a9f8fe151f1p-4 -0x1.62a99a4a0fbc4p-2 -0x1.638d1842e7576p-8 "
        "0x1.1f4a9e18f70a8p-5 0x1.9b3f52f6ac11cp-3 0x1.e70dc263d054ep-4 -0x1.13f3426f293f4p-2 "
        "-0x1.5d89b8c9ec990p-7 -0x1.9a5f7fbbe1fcdp-4 -0x1.c0aff70c5aa39p-4 0x1.d018d4f263346p-6 "
        "0x1.29d4d156e36f5p-7 0x1.ec53a2652fdb2p-6 0x1.ef294c170666dp-2 0x1.4e366f51efdfap-3",
    ),
}


def test_chain_parameters_bit_for_bit():
    chain = random_chain(5346, 5.0, 40)
    arrays = {key: getattr(chain, key) for key in ("radius", "mass", "A", "delta", "K2", "K3", "K4")}
    assert digest_arrays(arrays) == CHAIN_5346_DIGEST
    ds = chain_dataset(chain)
    assert digest_arrays({k: ds[k].values for k in ds.variables}) == CHAIN_FILE_DIGEST


@pytest.mark.parametrize("model", sorted(ORBITS))
def test_chaotic_orbit_bit_for_bit(model):
    energy, growth, q_hex, p_hex = ORBITS[model]
    q, p, log_growth = chaotic_orbit(model, energy)
    assert log_growth.hex() == growth
    assert hex_block(q) == " ".join(q_hex.split())
    assert hex_block(p) == " ".join(p_hex.split())


def scene(model: str):
    """A short scene with every observable of the model on random_chain(5346, 5, 40)."""
    energy = {"hertz": 3.0, "fput": 8.7381}[model]
    observables = model_observables(model)
    params = SceneParameters(model=model, energy=energy, t_final=200.0, dt=0.01, observables=observables, samples_per_decade=10)
    return simulate(random_chain(5346, 5.0, 40), params)


@pytest.mark.parametrize("model", ["hertz", "fput"])
def test_scene_data_bit_for_bit(model):
    ds = scene(model)
    assert digest_arrays({k: ds[k].values for k in ds.variables}) == SCENE_DIGESTS[model]


@pytest.mark.slow  # every kernel compiled again, for another CPU, in a second process
def test_same_bits_in_an_emulated_avx2_build():
    """Rerun every other test of this file, the bit-for-bit ones included, with NumPy, Numba and
    OpenBLAS choosing the code of an AVX2 CPU (chainchaos.records.provenance.EMULATED_AVX2), with a
    Numba cache of its own."""
    if os.environ.get("NUMBA_CPU_NAME"):
        pytest.skip("already running in an emulated build")
    env = {**os.environ, **EMULATED_AVX2,
           "NUMBA_CACHE_DIR": str(ROOT / ".numba_cache" / "emulated-avx2" / kernel_key())}
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:xdist",
                           str(Path(__file__)), "-k", "not emulated_avx2_build"],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, (done.stdout + done.stderr)[-4000:]
    assert " passed" in done.stdout and "failed" not in done.stdout


def dnls_orbit():
    """(q, p, ln|v|) at t = 100 of a DNLS orbit (dnls_chain(7, 4, 32, beta 2), norm 1 on site 16,
    s9ABC6 at dt 0.05 with the tangent map) on the batch engine: its on-site rotations run
    exactmath.sincos, so they, too, must give the same bits on every CPU."""
    from chainchaos.engine.problem import Problem
    from chainchaos.system.chain import dnls_chain

    N = 32
    q, p = np.zeros((N, 1)), np.zeros((N, 1))
    q[15] = math.sqrt(2.0)
    dq, dp = initial_deviation(N, 0)
    engine = Problem("dnls", [dnls_chain(7, 4.0, N, beta=2.0)], dt=0.05).engine(q, p, dq[:, None], dp[:, None], "batch")
    engine.advance(2000)
    return engine.q[:, 0], engine.p[:, 0], float(engine.log_growth[0])


def test_dnls_orbit_bit_for_bit():
    q, p, log_growth = dnls_orbit()
    assert (log_growth.hex(), digest_arrays({"q": q, "p": p})) == DNLS_ORBIT


DNLS_ORBIT = ("0x1.17d170bb39131p+1", "bfe557fa862b22c8b97f53e5265da04a43b2f68318008c000e0aaf83e1085f60")
