"""The square root of the Hertz kernels: IEEE ``sqrt``, from the CPU's square-root unit or from
integer operations and fused multiply-adds, with the same bits.

``root(x)`` is what the Hertz force and stiffness call, on a float64 or on a SIMD ``vector`` of
``chainchaos.kernels.simd``. ``CHAINCHAOS_SQRT`` selects, when the package is imported, how it
is computed:

- ``hardware`` (default): ``np.sqrt``, i.e. the CPU's square-root instruction (vsqrtpd);
- ``fma``: :func:`fma_sqrt`, a branch-free sequence of 27 lane-wise operations (integer
  operations, multiplies and fused multiply-adds) whose result is the correctly rounded square
  root, bit for bit what ``np.sqrt`` returns, on every double: docs/conventions.md#square-root
  proves it, tests/kernels/test_sqrt.py checks it on over 2e9 random inputs and on the hard cases.

Both give the same numbers everywhere; only the time differs, and which one is faster depends on
the CPU (its square-root unit against its FMA ports, which the rest of the kernel also uses):
``benchmarks/batch_throughput.py`` measures both on a machine. The choice changes the compiled
kernels, so it is part of the Numba cache key (``chainchaos.kernels.cache``).

The sequence, per element (``int``: on the i64 view of the same register; after Markstein 1990
and Cornea, Harrison & Tang 2002)::

    c  = x < 2^-900 ;  X = c ? x 2^200 : x          tiny inputs, subnormals included, scaled exactly
    Y  = bits^-1(K - (bits(X) >> 1)), Yh = Y / 2     ~ 1/sqrt(X) from the exponent and mantissa bits
    G  = X Y ;  D = fma(-G, Y, tc)                   t = X Y^2 in [3/4, 27/32], D = tc - t
    p  = c0 + D (c1 + ... + D c5)                    ~ 1/sqrt(t), biased high on purpose (5 fma)
    g1 = G p ;  hh = Yh p                            sqrt(X) (1 + a), (1 + b) / (2 sqrt(X)), a, b > 0
    s  = fma(fma(-g1, g1, X), hh, g1)                Newton step: s in {pred R, R}, R = RN(sqrt X)
    R  = fma(s, succ(s), -X) < 0 ? succ(s) : s       one-sided Tuckerman test, exact sign
    R  = R (c ? 2^-100 : 1) ;  x < 0 -> NaN ; x = +inf -> +inf
"""


import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from chainchaos.errors import require
from chainchaos.kernels.cache import SQRT_VARIABLE, sqrt_choice
from chainchaos.kernels.simd import LANES, VectorType, vector

#: The ways ``root`` can be computed (``CHAINCHAOS_SQRT``).
METHODS = ("hardware", "fma")

#: bits(Y) = MAGIC - (bits(X) >> 1): t = X Y^2 in [3/4, 27/32 + 1.3e-16] for every normal X.
MAGIC = 0x5FE4000000000000
#: D = T_CENTRE - t lies in [-0.046875, 0.046875].
T_CENTRE = float.fromhex("0x1.9800000000001p-1")
#: p(D) = sum COEFFS[k] D^k = (T_CENTRE - D)^(-1/2) (1 + alpha), 3.6e-11 < alpha < 6.3e-10.
COEFFS = tuple(float.fromhex(h) for h in (
    "0x1.1ec70127ea1d4p+0", "0x1.67e0a21d181d5p-1", "0x1.52b4f2e40c1a5p-1",
    "0x1.6233c57e7ca19p-1", "0x1.869a1446861bcp-1", "0x1.b982c1c5bd6ddp-1"))
TINY = 2.0**-900  # inputs below are scaled by 2^200 (exact), the result by 2^-100 (exact)
SCALE_UP = 2.0**200
SCALE_DOWN = 2.0**-100

_DOUBLE = ir.DoubleType()
_I64 = ir.IntType(64)


def method() -> str:
    """The square root the kernels use: ``CHAINCHAOS_SQRT`` if set, else ``hardware``."""
    chosen = sqrt_choice()
    require(chosen in METHODS, SQRT_VARIABLE, chosen, f"one of {list(METHODS)}")
    return chosen


def emit_fma_sqrt(builder, x, lanes=None):
    """Emit the sequence of the module docstring for ``x``, an LLVM ``double`` (lanes None) or
    ``<lanes x double>``, and return the correctly rounded square root."""
    fty = _DOUBLE if lanes is None else ir.VectorType(_DOUBLE, lanes)
    ity = _I64 if lanes is None else ir.VectorType(_I64, lanes)
    suffix = "f64" if lanes is None else f"v{lanes}f64"
    fma_fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(fty, [fty, fty, fty]),
                                            f"llvm.fma.{suffix}")

    def f(v):
        return ir.Constant(fty, v if lanes is None else [v] * lanes)

    def i(v):
        return ir.Constant(ity, v if lanes is None else [v] * lanes)

    def fma(a, b, c):
        return builder.call(fma_fn, [a, b, c])

    b = builder
    tiny = b.fcmp_ordered("<", x, f(TINY))
    X = b.select(tiny, b.fmul(x, f(SCALE_UP)), x)
    sh = b.lshr(b.bitcast(X, ity), i(1))
    Y = b.bitcast(b.sub(i(MAGIC), sh), fty)
    Yh = b.bitcast(b.sub(i(MAGIC - (1 << 52)), sh), fty)
    G = b.fmul(X, Y)
    D = fma(b.fneg(G), Y, f(T_CENTRE))
    p = fma(D, f(COEFFS[5]), f(COEFFS[4]))
    for ck in reversed(COEFFS[:4]):
        p = fma(p, D, f(ck))
    g1 = b.fmul(G, p)
    hh = b.fmul(Yh, p)
    s = fma(fma(b.fneg(g1), g1, X), hh, g1)
    sn = b.bitcast(b.add(b.bitcast(s, ity), i(1)), fty)
    r = b.select(b.fcmp_ordered("<", fma(s, sn, b.fneg(X)), f(0.0)), sn, s)
    r = b.fmul(r, b.select(tiny, f(SCALE_DOWN), f(1.0)))
    r = b.select(b.fcmp_ordered("<", x, f(0.0)), f(float("nan")), r)
    return b.select(b.fcmp_ordered("==", x, f(float("inf"))), f(float("inf")), r)


@intrinsic
def fma_sqrt(typingctx, x):
    """The correctly rounded square root of a float64 or, lane by lane, of a SIMD vector."""
    if isinstance(x, VectorType):
        return vector(x), lambda context, builder, sig, args: emit_fma_sqrt(builder, args[0], LANES)
    if isinstance(x, types.Float) and x.bitwidth == 64:
        return types.float64(x), lambda context, builder, sig, args: emit_fma_sqrt(builder, args[0])
    return None


@njit(cache=True)
def hardware_sqrt(x):
    """The CPU's square root (``np.sqrt``; for vectors, ``llvm.sqrt``)."""
    return np.sqrt(x)


#: The square root of the Hertz kernels (module docstring), fixed when the package is imported.
root = fma_sqrt if method() == "fma" else hardware_sqrt
