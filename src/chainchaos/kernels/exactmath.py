"""Arithmetic whose results do not depend on the CPU: the same doubles on every x86-64.

NumPy dispatches its transcendental ufuncs (``np.log``, ``np.log10``, ``np.exp``, ``np.cbrt``,
``np.power`` and ``**`` with exponents other than 2, ...) to code chosen for the CPU's vector
extensions (AVX-512 or AVX2), whose last bits differ; OpenBLAS does the same for ``@``, ``np.dot``
and ``np.linalg``. Sums (``np.sum``, pairwise in a fixed order), the IEEE operations + - * / and
``np.sqrt`` are correctly rounded or fixed in order, hence the same everywhere. This module holds
the replacements the package's data paths use:

1. Correctly rounded roots of rationals, in exact integer arithmetic (:func:`rational`,
   :func:`root`): the double nearest to (num / den)^(1/n) for positive integers, the same on
   every machine by construction. The chain parameters (chainchaos.system.chain) are computed this way.

2. Products of arrays, :func:`matmul` (``a @ b``), :func:`norm` and :func:`line_slope` (a
   least-squares slope), as Numba loops that sum in index order, instead of BLAS and LAPACK.

3. Elementwise logarithms and powers of arrays as Numba loops over scalars, never a vector
   implementation (Numba uses Intel's SVML only when it is installed; chainchaos.kernels.cache turns
   that off). :func:`log` is :func:`ln`, fdlibm's logarithm in IEEE operations only: the same bits
   on every IEEE-754 machine. :func:`log10` and :func:`exp10` call the C library's scalar
   ``log10`` and ``pow`` (glibc's libm, which Numba links, as CPython's ``math`` does: the results
   equal ``math.log10(x)`` and ``10.0 ** x``). glibc picks its routines by CPU only between a
   variant for CPUs with FMA and one without, which round a few arguments differently; every
   x86-64 CPU with AVX2 has FMA (x86-64-v3), so AVX2 and AVX-512 machines agree. They serve only
   for the sample steps (chainchaos.run.driver.sample_steps), integers after rounding.
"""

import math

import numpy as np
from numba import njit

from chainchaos.errors import require

#: Bits of the integer root: at least two more than a double's 53 (see :func:`root`).
ROOT_BITS = 64


def icbrt(x: int) -> int:
    """floor(x^(1/3)) of an integer x >= 0, exactly: a float estimate, one integer Newton step
    g <- floor((2 g + floor(x / g^2)) / 3) (which never falls below the floor of the root), and
    unit corrections until g^3 <= x < (g + 1)^3."""
    if x < 8:
        return int(x > 0)
    g = max(1, int(math.cbrt(float(x))))
    g = (2 * g + x // (g * g)) // 3
    while g * g * g > x:
        g -= 1
    while (g + 1) ** 3 <= x:
        g += 1
    return g


def iroot(x: int, n: int) -> int:
    """floor(x^(1/n)) of an integer x >= 0 for n = 1, 2, 3, exactly."""
    if n == 1:
        return x
    return math.isqrt(x) if n == 2 else icbrt(x)


def rational(num: int, den: int) -> float:
    """The double nearest to num / den (ties to even), for integers num >= 0, den > 0.

    CPython's int / int is correctly rounded whatever the sizes of the operands."""
    return num / den


def root(num: int, den: int, n: int) -> float:
    """The double nearest to (num / den)^(1/n) (ties to even), for integers num, den > 0 and
    n = 1, 2, 3, in exact integer arithmetic.

    With a shift k chosen so that v = (num / den)^(1/n) 2^k has at least ROOT_BITS - 1 bits,
    s = floor(v) = iroot(floor(num 2^(n k) / den), n) and ``exact`` says whether v = s. The double
    nearest to v is the double nearest to the integer t = 2 s + (0 if exact else 1), scaled by
    2^-(k+1): the rounding boundaries of a 53-bit significand at this scale are multiples of
    2^(bits(s) - 53) >= 4 in units of t, so they are even; t and 2 v either coincide (exact) or
    both lie strictly inside (2 s, 2 s + 2), an interval whose only possible boundary is its
    left end 2 s, where t = 2 s + 1 rounds up just as 2 v > 2 s does. Python's int-to-float
    conversion and ldexp are exact or correctly rounded (normal range).
    """
    require(num > 0 and den > 0, "num/den", (num, den), "positive integers")
    require(n in (1, 2, 3), "n", n, "1, 2 or 3")
    k = ROOT_BITS - (num.bit_length() - den.bit_length()) // n
    shift = n * k
    if shift >= 0:
        scaled, remainder = divmod(num << shift, den)
    else:
        scaled, remainder = divmod(num, den << -shift)
    s = iroot(scaled, n)
    exact = remainder == 0 and s**n == scaled
    return math.ldexp(float(2 * s + (not exact)), -(k + 1))


# ---- elementwise functions on arrays -----------------------------------------------------------

# fdlibm's e_log.c (Sun Microsystems, 1993): ln 2 split so that k * LN2_HI is exact for |k| < 2^11,
# and the minimax coefficients of R(z) ~ ln((1+s)/(1-s)) / s - 2 on |s| < 0.1716 (z = s^2).
LN2_HI = 6.93147180369123816490e-01
LN2_LO = 1.90821492927058770002e-10
LG1, LG2, LG3 = 6.666666666666735130e-01, 3.999999999940941908e-01, 2.857142874366239149e-01
LG4, LG5 = 2.222219843214978396e-01, 1.818357216161805012e-01
LG6, LG7 = 1.531383769920937332e-01, 1.479819860511658591e-01
# fdlibm's branch points, on the top 20 fraction bits of x's significand in [1, 2), as fractions:
_HALVE = 0x6a09c / 2**20  # from here (1 + f ~ sqrt 2) on, x = 2^(k+1) (1 + f) with 1 + f < 1
_BAND = (0x6147a / 2**20, 0x6b852 / 2**20)  # fractions where the f^2/2 form is used
_TINY = (1 / 2**20, 0xffffe / 2**20)  # |f| < ~2^-20: the series in f


@njit(cache=True)
def ln(x):
    """Natural logarithm of a double: fdlibm's algorithm (error below 1 ulp) in IEEE operations
    only (+ - * /, frexp), hence the same bits on every IEEE-754 machine, unlike the C library's
    ``log``, whose variant for CPUs without FMA rounds some arguments differently.

    x = 2^k (1 + f) with sqrt(2)/2 < 1 + f < sqrt(2), s = f / (2 + f), and
    ln(1 + f) = f - s (f - R(s^2)) (or f - (f^2/2 - s (f^2/2 + R)) where that is more accurate);
    ln x = k ln 2 + ln(1 + f). NaN for x < 0 or NaN, -inf at 0, inf at inf.
    """
    if not x > 0.0:
        return -math.inf if x == 0.0 else math.nan
    if x == math.inf:
        return x
    m, e = math.frexp(x)  # x = m 2^e, 0.5 <= m < 1
    frac = 2.0 * m - 1.0  # fraction of the significand 2 m in [1, 2), exact
    k = e - 1
    if frac >= _HALVE:
        k += 1
        f = m - 1.0  # exact (Sterbenz)
    else:
        f = frac
    dk = float(k)
    if frac < _TINY[0] or frac >= _TINY[1]:
        if f == 0.0:
            return dk * LN2_HI + dk * LN2_LO
        R = f * f * (0.5 - 0.33333333333333333 * f)
        if k == 0:
            return f - R
        return dk * LN2_HI - ((R - dk * LN2_LO) - f)
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    t1 = w * (LG2 + w * (LG4 + w * LG6))
    t2 = z * (LG1 + w * (LG3 + w * (LG5 + w * LG7)))
    R = t2 + t1
    if _BAND[0] <= frac < _BAND[1]:
        hfsq = 0.5 * f * f
        if k == 0:
            return f - (hfsq - s * (hfsq + R))
        return dk * LN2_HI - ((hfsq - (s * (hfsq + R) + dk * LN2_LO)) - f)
    if k == 0:
        return f - s * (f - R)
    return dk * LN2_HI - ((s * (f - R) - dk * LN2_LO) - f)


@njit(cache=True)
def _log_loop(x, out):
    for i in range(x.size):
        out[i] = ln(x[i])


@njit(cache=True)
def _log10_loop(x, out):
    for i in range(x.size):
        out[i] = math.log10(x[i])


@njit(cache=True)
def _exp10_loop(x, out):
    for i in range(x.size):
        out[i] = 10.0 ** x[i]


#: Up to this many elements, :func:`log10` and :func:`exp10` call the C library from Python
#: (the same function, the same bits): a process that only needs a grid of a few energies then
#: neither compiles nor loads a kernel (loading the first one costs Numba half a second).
SCALAR_LOOP_MAX = 64


def _elementwise(loop, x, scalar=None) -> np.ndarray | float:
    """Apply a scalar loop to every element of x (any shape, also a scalar); float64 result of
    x's shape (a Python float for a scalar). ``scalar``, the same function in Python, serves
    arrays of up to :data:`SCALAR_LOOP_MAX` elements."""
    a = np.asarray(x, dtype=np.float64)
    flat = np.ascontiguousarray(a).reshape(-1)
    if scalar is not None and flat.size <= SCALAR_LOOP_MAX:
        out = np.array([scalar(v) for v in flat.tolist()], dtype=np.float64)
    else:
        out = np.empty_like(flat)
        loop(flat, out)
    return float(out[0]) if a.ndim == 0 else out.reshape(a.shape)


def log(x):
    """Natural logarithm ln x of every element (:func:`ln`; NaN for x < 0, -inf at 0)."""
    return _elementwise(_log_loop, x)


def _log10_scalar(v: float) -> float:
    # math.log10 raises where the C function returns -inf or NaN
    if v > 0.0 or math.isnan(v):
        return math.log10(v)
    return -math.inf if v == 0.0 else math.nan


def log10(x):
    """Decimal logarithm log10 x of every element (C library ``log10``)."""
    return _elementwise(_log10_loop, x, _log10_scalar)


def _exp10_scalar(v: float) -> float:
    try:
        return 10.0 ** v
    except OverflowError:  # where the C function returns inf
        return math.inf


def exp10(x):
    """10^x of every element (C library ``pow(10, x)``, as Python's ``10.0 ** x``)."""
    return _elementwise(_exp10_loop, x, _exp10_scalar)


# ---- sine and cosine, in + - * only -----------------------------------------------------------

# fdlibm's k_sin.c and k_cos.c (Sun Microsystems, 1993): minimax coefficients of sin x and cos x on
# |x| <= pi/4, and pi/2 in three parts (e_rem_pio2.c): PIO2_1 its first 33 bits, PIO2_2 the next 33,
# PIO2_2T the rest, so that fn * PIO2_1 and fn * PIO2_2 are exact for integers |fn| < 2^20.
S1, S2, S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
S4, S5, S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
C1, C2, C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
C4, C5, C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11
INVPIO2 = 6.36619772367581382433e-01
PIO2_1, PIO2_2, PIO2_2T = 1.57079632673412561417e+00, 6.07710050630396597660e-11, 2.02226624879595063154e-21
#: Arguments up to this size are reduced exactly enough for an error of about 1 ulp (fdlibm's
#: "medium" range, |fn| < 2^19); beyond it the reduction loses accuracy, but not determinism.
SINCOS_ACCURATE = 2.0**19 * 1.5707963267948966
#: 1.5 * 2^52: (y + _ROUND) - _ROUND is y rounded to the nearest integer (ties to even), |y| < 2^51.
_ROUND = 6755399441055744.0


@njit(cache=True, inline="always")
def _nearest_integer(y):
    return (y + _ROUND) - _ROUND


@njit(cache=True, inline="always")
def sincos(x):
    """(sin x, cos x) of a double, or lane by lane of a SIMD vector (``kernels.simd``), in + - *
    only: the same bits on every IEEE-754 machine and at every vector width, unlike the C
    library's ``sin``/``cos`` and NumPy's vector versions, whose code depends on the CPU. What the
    DNLS on-site rotation (``engine.split``) turns by.

    fdlibm's algorithm without its branches: x = fn pi/2 + r with fn the nearest integer to
    x 2/pi, r = y0 + y1 a head and tail (x - fn PIO2_1 exact; the rest by an exact two-sum);
    sin r and cos r by fdlibm's kernels (k_sin.c; k_cos.c in FreeBSD's form
    w + (((1 - w) - z/2) + (z R - r y1)), w = 1 - z/2, which needs no branch); then the quadrant
    m = fn mod 4 turns (sin r, cos r) by m pi/2 through the factors cos(m pi/2), sin(m pi/2) in
    {-1, 0, 1}, exact products. Error about 1 ulp (``tests/kernels/test_sincos.py``) for
    |x| <= :data:`SINCOS_ACCURATE`; NaN for a NaN or infinite x.

    Parameters
    ----------
    x : float or SIMD vector
        The angle, in radians.

    Returns
    -------
    tuple
        (sin x, cos x), floats or vectors like x.
    """
    fn = _nearest_integer(x * INVPIO2)
    a = x - fn * PIO2_1  # exact: fn * PIO2_1 has at most 53 bits and lies within a factor 2 of x
    b = fn * (0.0 - PIO2_2)  # exact
    y0 = a + b  # two-sum: y0 + e = a + b exactly
    bb = y0 - a
    e = (a - (y0 - bb)) + (b - bb)
    y1 = e + fn * (0.0 - PIO2_2T)
    z = y0 * y0
    v = z * y0
    rs = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))
    sine = y0 - ((z * (0.5 * y1 - v * rs) - y1) - v * S1)
    rc = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))))
    hz = 0.5 * z
    w = 1.0 - hz
    cosine = w + (((1.0 - w) - hz) + (z * rc - y0 * y1))
    m = fn - 4.0 * _nearest_integer(fn * 0.25 - 0.375)  # fn mod 4, in {0, 1, 2, 3}
    odd = m - 2.0 * _nearest_integer(m * 0.5 - 0.25)  # m mod 2
    c = (1.0 - odd) * (1.0 - m)  # cos(m pi/2): 1, 0, -1, 0
    s = odd * (2.0 - m)  # sin(m pi/2): 0, 1, 0, -1
    return s * cosine + c * sine, c * cosine - s * sine


@njit(cache=True)
def _sincos_loop(x, sine, cosine):
    for i in range(x.size):
        sine[i], cosine[i] = sincos(x[i])


def sin_cos(x) -> tuple[np.ndarray, np.ndarray]:
    """sin x and cos x of every element (:func:`sincos`): arrays of x's shape.

    Parameters
    ----------
    x : array_like
        Angles, in radians.

    Returns
    -------
    sine, cosine : numpy.ndarray
        Of x's shape, float64.
    """
    a = np.asarray(x, dtype=np.float64)
    flat = np.ascontiguousarray(a).reshape(-1)
    sine, cosine = np.empty_like(flat), np.empty_like(flat)
    _sincos_loop(flat, sine, cosine)
    return sine.reshape(a.shape), cosine.reshape(a.shape)


# ---- products and norms, summed in index order -----------------------------------------------


@njit(cache=True)
def _matmul_loop(a, b, out):
    """out[s, k] = sum_n a[s, n] b[n, k], the terms added in order n = 0, 1, ..."""
    for s in range(a.shape[0]):
        for k in range(b.shape[1]):
            total = 0.0
            for n in range(a.shape[1]):
                total += a[s, n] * b[n, k]
            out[s, k] = total


def matmul(a, b) -> np.ndarray:
    """``a @ b`` for a of shape (..., n) and b of shape (n, K) or (n,), every sum taken in index
    order: result of shape (..., K) or (...)."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    require(a.ndim >= 1 and b.ndim in (1, 2) and a.shape[-1] == b.shape[0], "shapes", (a.shape, b.shape),
            "a (..., n) and b (n, K) or (n,)")
    B = np.ascontiguousarray(b.reshape(b.shape[0], -1))
    flat = np.ascontiguousarray(a.reshape(-1, a.shape[-1]))
    out = np.empty((flat.shape[0], B.shape[1]))
    _matmul_loop(flat, B, out)
    return out.reshape(a.shape[:-1] + b.shape[1:])


def line_slope(x, y) -> float:
    """Least-squares slope of y against x (vectors of the same length >= 2):
    sum_i (x_i - xm)(y_i - ym) / sum_i (x_i - xm)^2 with the means xm, ym, every sum in index
    order (for ``np.polyfit(x, y, 1)[0]``, which goes through LAPACK)."""
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    require(x.ndim == 1 and x.shape == y.shape and x.size >= 2, "x, y", (x.shape, y.shape),
            "vectors of one length >= 2")
    dx = x - float(matmul(x, np.ones(x.size))) / x.size
    dy = y - float(matmul(y, np.ones(y.size))) / y.size
    return float(matmul(dx, dy)) / float(matmul(dx, dx))


def norm(x) -> float:
    """Euclidean norm sqrt(sum_n x_n^2) of a vector, the squares summed in index order."""
    x = np.asarray(x, dtype=np.float64)
    require(x.ndim == 1, "x", x.shape, "a vector")
    return math.sqrt(float(matmul(x, x)))


@njit(cache=True)
def gram_schmidt(W, first, orthogonal, growth):
    """Rows first..k-1 of W (k, 2N: a deviation vector per row, du_1..du_N then dp_1..dp_N) in
    place: rows first..orthogonal-1 made orthogonal to every row before them (modified
    Gram-Schmidt), then each of rows first..k-1 divided by its norm, ln of the norm added to
    growth[row - first]; rows before ``first`` are taken as they are (unit and orthogonal).
    Norms and dot products are summed bead by bead, du_n then dp_n, as in the engines' ``integrators._renormalise``,
    so a row equal to a vector the engine renormalises gets the same bits."""
    N = W.shape[1] // 2
    for j in range(first, W.shape[0]):
        if j < orthogonal:
            for i in range(j):
                dot = 0.0
                for n in range(N):
                    dot += W[i, n] * W[j, n] + W[i, N + n] * W[j, N + n]
                for m in range(2 * N):
                    W[j, m] -= dot * W[i, m]
        s = 0.0
        for n in range(N):
            s += W[j, n] * W[j, n] + W[j, N + n] * W[j, N + n]
        norm = np.sqrt(s)
        for m in range(2 * N):
            W[j, m] /= norm
        growth[j - first] += ln(norm)
