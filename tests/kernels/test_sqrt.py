"""chainchaos.kernels.sqrt.fma_sqrt against np.sqrt, bit for bit (docs/conventions.md#square-root).

(a) random: 2^30 (> 1e9) samples over the Hertz force's range (half uniformly random bit patterns
    between 2^-64 and 1e-2, i.e. uniform exponent and mantissa bits, half uniform on [0, 1e-3]) and
    2^30 uniformly random bit patterns in 0x0..0x7FF0000000000000 (every exponent, subnormals, +inf);
    the random words come from np.random.default_rng(seed) outside @njit, in chunks, and are turned
    into doubles and compared inside an @njit loop. ``CHAINCHAOS_SQRT_SAMPLES`` sets fewer.
(b) edge cases: +-0, subnormals, DBL_MAX, +-inf, NaN, negatives, every power of two with its
    +-1..+-8 ulp neighbours, exact squares across the exponent range with +-1..+-8 ulp neighbours,
    the nearest doubles to (m + 1/2)^2 for m near 2^52 and 2^53 (and random m) with +-1..+-4 ulp
    neighbours, scaled by powers of 4 over the whole range, and number-theoretic hard cases
    (X = r^2 + d 2^-106 with r a midpoint between two doubles and |d| < 2^12) scaled likewise.
(c) the edge cases and a random chunk through the SIMD vector type at LANES, through a float64
    loop, and value by value through a scalar call.
(d) the same (b, c and a reduced (a)) in a subprocess in emulated AVX2 (4 lanes), and the bounds
    of the proof in exact arithmetic (tests/sqrt_bounds.py).
"""

import os
import subprocess
import sys
import time
from fractions import Fraction
from pathlib import Path

import numba
import numpy as np
import pytest
from numba import types
from numba.extending import intrinsic

from chainchaos.kernels import sqrt as fma_module
from chainchaos.kernels.simd import LANES, vload, vstore
from chainchaos.kernels.sqrt import fma_sqrt as fmasqrt
from chainchaos.records.provenance import EMULATED_AVX2

HERE = Path(__file__).resolve().parent

RANDOM_SAMPLES = int(os.environ.get("CHAINCHAOS_SQRT_SAMPLES", 2**30))  # per family (2 families)
CHUNK = 2**16  # random words per chunk (stays in L2)


# ---- bit views inside @njit ----------------------------------------------------------------------

@intrinsic
def float_bits(typingctx, x):
    if isinstance(x, types.Float) and x.bitwidth == 64:
        return types.int64(x), lambda context, builder, sig, args: builder.bitcast(
            args[0], context.get_value_type(types.int64))


@intrinsic
def bits_float(typingctx, b):
    if isinstance(b, types.Integer) and b.bitwidth == 64:
        return types.float64(b), lambda context, builder, sig, args: builder.bitcast(
            args[0], context.get_value_type(types.float64))


def f2b(x):
    return np.asarray(x, dtype=np.float64).view(np.int64)


def b2f(b):
    return np.asarray(b, dtype=np.int64).view(np.float64)


# ---- (a) random ----------------------------------------------------------------------------------

FULL_HI = 0x7FF0000000000000  # +inf
HERTZ_LO = int(f2b(2.0**-64))
HERTZ_HI = int(f2b(1e-2))


@numba.njit(cache=True)
def _to_doubles(raw, family, out):
    """Doubles from random 64-bit words (rejection keeps each distribution exactly uniform):
    family 0: bit patterns uniform in [0, FULL_HI]; 1: bit patterns uniform in [HERTZ_LO, HERTZ_HI];
    2: uniform on [0, 1e-3) (53 random bits, as Generator.random, times 1e-3). Returns the count."""
    n = 0
    for i in range(raw.size):
        w = raw[i]
        if family == 0:
            v = np.int64(w >> np.uint64(1))  # 63 bits
            if v <= FULL_HI:
                out[n] = bits_float(v)
                n += 1
        elif family == 1:
            v = np.int64(w >> np.uint64(6))  # 58 bits >= HERTZ_HI - HERTZ_LO
            if v <= HERTZ_HI - HERTZ_LO:
                out[n] = bits_float(v + HERTZ_LO)
                n += 1
        else:
            out[n] = np.float64(w >> np.uint64(11)) * (1.0 / 9007199254740992.0) * 1e-3
            n += 1
    return n


@numba.njit(cache=True)
def _mismatches(x, n):
    """Number of i < n where fmasqrt(x[i]) and np.sqrt(x[i]) differ in a bit."""
    bad = 0
    for i in range(n):
        bad += float_bits(fmasqrt(x[i])) != float_bits(np.sqrt(x[i]))
    return bad


@numba.njit(cache=True)
def _first_mismatch(x, n):
    for i in range(n):
        if float_bits(fmasqrt(x[i])) != float_bits(np.sqrt(x[i])):
            return i
    return -1


def random_sweep(seed, families, samples):
    """Compare `samples` random doubles (split evenly over `families`); return (tested, bad, first x)."""
    rng = np.random.default_rng(seed)
    x = np.empty(CHUNK)
    tested = bad = 0
    first = None
    per_family = samples // len(families)
    for family in families:
        done = 0
        while done < per_family:
            raw = rng.bit_generator.random_raw(min(CHUNK, per_family - done))
            n = _to_doubles(raw, family, x)
            b = _mismatches(x, n)
            if b and first is None:
                first = x[_first_mismatch(x, n)]
            bad += b
            tested += n
            done += raw.size
    return tested, bad, first


def _report(name, tested, bad, first, seconds):
    print(f"\n{name}: {tested:,} samples, {bad} mismatches, {seconds:.1f} s"
          + ("" if first is None else f", first x = {first!r} ({float(first).hex()}): "
             f"fmasqrt {_scalar(first)!r} vs np.sqrt {np.sqrt(first)!r}"))


def test_random_hertz_range():
    t0 = time.perf_counter()
    tested, bad, first = random_sweep(20240601, (1, 2), RANDOM_SAMPLES)
    _report("Hertz range (bits in [2^-64, 1e-2] and uniform [0, 1e-3])", tested, bad, first,
            time.perf_counter() - t0)
    assert tested >= 0.94 * RANDOM_SAMPLES and bad == 0


def test_random_whole_range():
    t0 = time.perf_counter()
    tested, bad, first = random_sweep(20240602, (0,), RANDOM_SAMPLES)
    _report("whole positive range (bits in [0, 0x7FF0000000000000])", tested, bad, first,
            time.perf_counter() - t0)
    assert tested >= 0.99 * RANDOM_SAMPLES and bad == 0


# ---- (b) edge and hard cases ---------------------------------------------------------------------

def neighbours(x, k):
    """x and its +-1..+-k ulp neighbours (bit patterns; only those that stay non-negative and <= inf)."""
    b = f2b(x).ravel()
    out = np.concatenate([b + d for d in range(-k, k + 1)])
    return b2f(out[(out >= 0) & (out <= FULL_HI)])


def powers_of_two():
    return np.ldexp(1.0, np.arange(-1074, 1024))


def exact_squares(rng):
    """s^2 for s = m 2^e, m < 2^26 (so s^2 is exact, also when subnormal), e across the range."""
    m = np.concatenate([np.arange(1, 257), [2**26 - 1, 2**26 - 3, 2**25 + 1, 2**26 - 5, 2**24 + 1],
                        rng.integers(2**20, 2**26, 200)]).astype(np.float64)
    sq = m * m  # exact (< 2^53)
    out = []
    for e2 in range(-1074, 1024, 2):  # scale by 4^j: exact while the result is representable
        with np.errstate(over="ignore"):
            y = np.ldexp(sq, e2)
        ok = np.isfinite(y) & (y > 0)
        back = np.ldexp(y[ok], -e2)
        out.append(y[ok][back == sq[ok]])  # keep the exact ones
    return np.concatenate(out)


def scaled_by_powers_of_4(x, step=1):
    """x (doubles around [1, 2^110)) times 4^j for every j (or every `step`-th) that keeps them normal."""
    x = np.asarray(x)
    out = []
    for j in range(-600, 520, step):
        with np.errstate(over="ignore"):
            y = np.ldexp(x, 2 * j)
        out.append(y[np.isfinite(y) & (y >= 2.0**-1022)])
    return np.concatenate(out)


def half_integer_squares(rng):
    """The nearest doubles to (m + 1/2)^2 for m near 2^52, near 2^53 and random in [2^52, 2^53)."""
    ms = list(range(2**52 - 256, 2**52 + 257)) + list(range(2**53 - 256, 2**53)) + \
        [int(v) for v in rng.integers(2**52, 2**53, 1000, dtype=np.int64)]
    return np.array([float(Fraction((2 * m + 1) ** 2, 4)) for m in ms])  # float(Fraction) rounds correctly


def _sqrt_mod_pow2(a, n):
    """An odd q with q^2 = a (mod 2^n), for a = 1 (mod 8) (Hensel lifting)."""
    q = 1
    for k in range(3, n):
        if (q * q - a) % (1 << (k + 1)):
            q += 1 << (k - 1)
    return q % (1 << n)


def midpoint_hard_cases(max_d=2**12):
    """X in [1, 4) with X - r^2 = d 2^-106, r = Q 2^-53 (Q odd: r is the midpoint of two doubles in
    [1, 2)), for every d = 7 (mod 8), |d| < max_d: sqrt(X) is within ~|d| 2^-107 of a midpoint, the
    closest a square root of a double can come. X = M 2^(p-52), M in [2^52, 2^53), p = 0, 1:
    M 2^(54+p) = Q^2 + d, so Q^2 = -d (mod 2^(54+p))."""
    xs = []
    for p in (0, 1):
        n = 54 + p
        mod = 1 << n
        lo, hi = 1 << (106 + p), 1 << (107 + p)  # range of Q^2 + d
        for d in range(-max_d + 1, max_d, 1):
            if d % 8 != 7:  # -d = 1 (mod 8): -d is then a square modulo every 2^n
                continue
            a = (-d) % mod
            q = _sqrt_mod_pow2(a, n)
            for r0 in {q, mod - q, (q + mod // 2) % mod, (mod - q + mod // 2) % mod}:
                for Q in (r0, r0 + mod):
                    if Q % 2 and lo <= Q * Q + d < hi and (Q * Q + d) % mod == 0:
                        xs.append(float(Fraction((Q * Q + d) // mod) * Fraction(2) ** (p - 52)))
    return np.array(sorted(set(xs)))


SPECIALS = np.array([0.0, -0.0, 5e-324, b2f(0x000FFFFFFFFFFFFF), 2.2250738585072014e-308, 1.7976931348623157e308,
                     np.inf, -np.inf, np.nan, -np.nan, b2f(0x7FF0000000000001), b2f(0x7FF8000000000001),
                     b2f(0x7FFFFFFFFFFFFFFF), b2f(-1), b2f(-0x0008000000000000), -1.0, -5e-324,
                     -1.7976931348623157e308, 1.0, 2.0, 3.0, 4.0, 0.5, 0.25, 1e-300, 1e300, 2.0**-900,
                     np.nextafter(2.0**-900, 0),
                     2.0**-970, 2.0**-1022 * 3, 1.0 + 2.0**-52, 4.0 - 2.0**-51, 2.0 - 2.0**-52])


@pytest.fixture(scope="module")
def edge_cases():
    rng = np.random.default_rng(7)
    pow2 = neighbours(powers_of_two(), 8)
    squares = neighbours(exact_squares(rng), 8)
    half = scaled_by_powers_of_4(neighbours(half_integer_squares(rng), 4), step=3)
    hard = scaled_by_powers_of_4(midpoint_hard_cases(), step=7)
    print(f"\nedge cases: {SPECIALS.size} specials, {pow2.size:,} powers of two and neighbours, "
          f"{squares.size:,} exact squares and neighbours, {half.size:,} (m + 1/2)^2 and neighbours "
          f"scaled, {hard.size:,} midpoint hard cases scaled")
    return {"specials": SPECIALS, "powers of two": pow2, "exact squares": squares, "(m+1/2)^2": half,
            "midpoint hard cases": hard}


def assert_same(x, got, what):
    with np.errstate(invalid="ignore"):
        want = np.sqrt(x)
    same = (f2b(got) == f2b(want)) | (np.isnan(got) & np.isnan(want))
    bad = np.flatnonzero(~same)
    assert bad.size == 0, (f"{what}: {bad.size} of {x.size} differ; first x = {x[bad[0]]!r} "
                           f"({float(x[bad[0]]).hex()}): got {got[bad[0]]!r}, np.sqrt {want[bad[0]]!r}")


@numba.njit(cache=True)
def _loop(x):
    y = np.empty_like(x)
    for i in range(x.size):
        y[i] = fmasqrt(x[i])
    return y


@numba.njit(cache=True)
def _scalar(x):
    return fmasqrt(x)


@numba.njit(cache=True)
def _vector(x, y):
    for i in range(0, x.size, LANES):
        vstore(y, i, fmasqrt(vload(x, i)))


def vector_sqrt(x):
    n = -(-x.size // LANES) * LANES
    xp = np.zeros(n)
    xp[:x.size] = x
    y = np.empty(n)
    _vector(xp, y)
    return y[:x.size]


def test_mid_point_generator():
    """The hard cases are what they claim: X 2^106 - Q^2 = d with Q odd (r = Q 2^-53 a midpoint)."""
    import math

    xs = midpoint_hard_cases(64)
    assert xs.size > 20
    for x in xs:
        N = Fraction(float(x)) * 2**106
        assert N.denominator == 1
        N = N.numerator
        Q = math.isqrt(N)
        assert any(q % 2 and abs(N - q * q) < 64 and (N - q * q) % 8 == 7 for q in (Q - 1, Q, Q + 1)), x


def test_specials_value_by_value():
    for x in SPECIALS:
        got = _scalar(x)
        with np.errstate(invalid="ignore"):
            want = np.sqrt(x)
        assert (np.isnan(got) and np.isnan(want)) or f2b(got) == f2b(want), (x, got, want)
    assert np.signbit(_scalar(-0.0)) and not np.signbit(_scalar(0.0))


@pytest.mark.parametrize("path", ["float64 loop", "vector", "scalar calls"])
def test_edge_cases(edge_cases, path):
    total = 0
    for what, x in edge_cases.items():
        if path == "scalar calls":
            x = x if x.size <= 20000 else x[np.random.default_rng(3).choice(x.size, 20000, replace=False)]
            got = np.array([_scalar(v) for v in x])
        else:
            got = _loop(x) if path == "float64 loop" else vector_sqrt(x)
        assert_same(x, got, f"{what} ({path})")
        total += x.size
    print(f"\n{path}: {total:,} edge cases, 0 mismatches (LANES = {LANES})")


def test_random_chunk_through_vector():
    rng = np.random.default_rng(11)
    x = np.empty(CHUNK)
    for family in (0, 1, 2):
        for _ in range(64):
            n = _to_doubles(rng.bit_generator.random_raw(CHUNK), family, x)
            assert_same(x[:n], vector_sqrt(x[:n]), f"random family {family} (vector, LANES={LANES})")


# ---- (d) emulated AVX2 and the design bounds -----------------------------------------------------

@pytest.mark.skipif(os.environ.get("CHAINCHAOS_SQRT_CHILD") == "1", reason="already the emulated child")
def test_emulated_avx2(tmp_path):
    """The edge cases, the vector path at 4 lanes and 2^24 random samples in an AVX2 build."""
    env = dict(os.environ, **EMULATED_AVX2, CHAINCHAOS_SQRT_CHILD="1", CHAINCHAOS_SQRT_SAMPLES=str(2**24))
    env.pop("CHAINCHAOS_SIMD_LANES", None)
    env.pop("NUMBA_CACHE_DIR", None)  # the package keys its cache by the build
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", "-p", "no:xdist",
                        __file__, "-k", "not bounds"], env=env, capture_output=True, text=True, cwd=HERE)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    lanes = subprocess.run([sys.executable, "-c", "from chainchaos.kernels.simd import LANES; print(LANES)"],
                           env=env, capture_output=True, text=True, check=True)
    assert lanes.stdout.strip() == "4"


def test_the_bounds_of_the_proof_hold():
    """The inequalities of the proof hold for the constants of chainchaos.kernels.sqrt (exact
    arithmetic): t = X Y^2 in [3/4, 27/32 + 1.3e-16], the relative errors a, b > 0 and the bias
    of the Newton step 0 < eta <= 2^-54 sqrt(X)."""
    import sqrt_bounds

    out = sqrt_bounds.verify(fma_module.MAGIC, fma_module.T_CENTRE, fma_module.COEFFS, pieces=1024)
    assert out["ok"]
    assert out["t_lo"] == Fraction(3, 4) and float(out["t_hi"]) <= 0.84375 + 1e-15
    assert 0 < out["a_lo"] and out["eta_hi"] <= Fraction(1, 2**54)


def test_the_choice_is_checked_and_keys_the_cache(monkeypatch):
    from chainchaos.errors import ParameterError
    from chainchaos.kernels.cache import SQRT_VARIABLE, kernel_key

    keys = {}
    for value in ("", "hardware", "fma"):
        monkeypatch.setenv(SQRT_VARIABLE, value)
        assert fma_module.method() == (value or "hardware")
        keys[value] = kernel_key()
    assert keys[""] == keys["hardware"] != keys["fma"]  # other code, another cache
    monkeypatch.setenv(SQRT_VARIABLE, "rsqrt")
    with pytest.raises(ParameterError, match="CHAINCHAOS_SQRT.*rsqrt.*hardware.*fma"):
        fma_module.method()
