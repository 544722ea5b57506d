"""The error bounds of ``chainchaos.kernels.sqrt.fma_sqrt`` in exact rational arithmetic.

Everything the proof of docs/conventions.md#square-root relies on, computed with
``fractions.Fraction``, never in floating point:

1. the exact range [t_min, t_max] of t = X Y^2 over all normal X, Y = bits^-1(K - (bits(X) >> 1))
   (t depends only on the low 53 bits of bits(X), and is a cubic in them on each of a few pieces:
   its extrema are found in closed form);
2. an enclosure of alpha(t) = sqrt(t) p(tc - t) - 1 on [t_min, t_max] for the degree-5 polynomial
   p with the double coefficients the kernels use (exact Taylor expansions on subintervals);
3. the rounding errors of the sequence carried to the bias eta of the last Newton step, and the
   inequalities the proof needs: 0 < a, b and 0 < eta <= 2^-54 sqrt(X).
"""

import math
from fractions import Fraction as F

U = F(1, 2**53)  # unit roundoff of binary64, round to nearest


# ---------------------------------------------------------------------------------------------
# 1. the range of t = X Y^2
# ---------------------------------------------------------------------------------------------

def t_range(K: int):
    """Exact [min, max] of t = X * Y(X)^2 over all normal X (and all X for which Y stays normal).

    Multiplying X by 4 adds 2^53 to bits(X), subtracts 2^52 from bits(Y), i.e. halves Y: t is
    unchanged. So t depends only on r = bits(X) mod 2^53 and it suffices to take
    bits(X) = 1022 * 2^52 + r, X in [1/2, 2). Then bits(X) >> 1 = 511 * 2^52 + n with n = r >> 1,
    and bits(Y) = C - n, C = K - 511 * 2^52. On a range of n where the exponent field E of C - n is
    constant, Y = 2^(E-1075) (M - n) with M = C - (E - 1) 2^52 (affine in n), and X is affine in
    r = 2n + beta (beta = r mod 2) on each of r < 2^52 (X = (2^52 + r) 2^-53) and r >= 2^52
    (X = r 2^-52). On each such piece t is the cubic c (nu + 2n + beta)(M - n)^2 of n, whose
    extrema over a real interval lie at its ends or at n* = (M - nu - beta) / 3: evaluating there
    (exactly) bounds t over the integers of the piece."""
    C = K - 511 * 2**52
    lo, hi = None, None
    for r_lo, r_hi, mu, nu in ((0, 2**52 - 1, F(1, 2**53), 2**52), (2**52, 2**53 - 1, F(1, 2**52), 0)):
        for beta in (0, 1):
            n_lo = -((-(r_lo - beta)) // 2)  # ceil
            n_hi = (r_hi - beta) // 2
            # split [n_lo, n_hi] where the exponent field of C - n changes
            pieces = []
            n = n_lo
            while n <= n_hi:
                E = (C - n) >> 52
                assert 1 <= E <= 2046, "Y must stay normal"
                n_end = min(n_hi, C - E * 2**52)  # last n with C - n >= E * 2^52
                pieces.append((n, n_end, E))
                n = n_end + 1
            for n1, n2, E in pieces:
                lam = F(2) ** (E - 1075)
                M = C - (E - 1) * 2**52

                def t_of(nn):
                    return mu * (nu + 2 * nn + beta) * lam**2 * (M - nn) ** 2

                cands = [F(n1), F(n2)]
                ncrit = F(M - nu - beta, 3)
                if n1 < ncrit < n2:
                    cands.append(ncrit)
                for c in cands:
                    v = t_of(c)
                    lo = v if lo is None or v < lo else lo
                    hi = v if hi is None or v > hi else hi
    return lo, hi


def poly_mul(p, q):
    r = [F(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            r[i + j] += a * b
    return r


def compose_shift(c, tc):
    """Coefficients (in t) of p(tc - t) for p with coefficients c (in D)."""
    out = [F(0)]
    for ck in reversed(c):  # Horner: out = out * (tc - t) + ck
        out = poly_mul(out, [F(tc), F(-1)])
        out[0] += ck
    return out


def taylor_at(q, x0):
    """Coefficients of q(x0 + s) in s (exact)."""
    q = list(q)
    n = len(q)
    for i in range(n):
        for j in range(n - 2, i - 1, -1):
            q[j] += x0 * q[j + 1]
    return q


def enclose_Q(c, tc, t_lo, t_hi, pieces=2048):
    """Rigorous [min, max] of Q(t) = t p(tc - t)^2 - 1 over [t_lo, t_hi]: on each subinterval of
    half-width h about a dyadic centre t_i, Q(t_i + s) = sum_k q_k s^k exactly, so
    |Q(t_i + s) - Q(t_i)| <= sum_{k>=1} |q_k| h^k."""
    pt = compose_shift(c, tc)
    Q = poly_mul([F(0), F(1)], poly_mul(pt, pt))
    Q[0] -= 1
    width = t_hi - t_lo
    lo, hi = None, None
    for i in range(pieces):
        a = t_lo + width * i / pieces
        b = t_lo + width * (i + 1) / pieces
        mid = (a + b) / 2
        h = (b - a) / 2
        q = taylor_at(Q, mid)
        slack = sum(abs(qk) * h**k for k, qk in enumerate(q) if k >= 1)
        lo = q[0] - slack if lo is None or q[0] - slack < lo else lo
        hi = q[0] + slack if hi is None or q[0] + slack > hi else hi
    return lo, hi


def sqrt_bounds(y: F, below: bool) -> F:
    """A rational lower (below=True) or upper bound of sqrt(y), y > 0, within 2^-128 of it."""
    scale = 2**128
    s = math.isqrt(y.numerator * scale * scale // y.denominator)  # floor(sqrt(y) scale), or 1 less
    return F(s, scale) if below else F(s + 2, scale)


def verify(K, tc, coeffs, pieces=2048):
    """Check every inequality the proof (docs/conventions.md#square-root) relies on; return the bounds."""
    tc = F(tc)
    c = [F(x) for x in coeffs]
    n = len(c) - 1
    t_lo, t_hi = t_range(K)
    D_lo, D_hi = tc - t_hi, tc - t_lo
    # p > 0 and the size of p, p' on a slightly widened D range
    # |D_hat - (tc - t)|: G = X Y (1 + rho1), D_hat = RN(tc - G Y) (one rounding: relative u, or
    # absolute 2^-1075 if the result is subnormal)
    dD = U * t_hi + U * (max(abs(D_lo), abs(D_hi)) + U * t_hi) + F(1, 2**1075)
    Dabs = max(abs(D_lo), abs(D_hi)) + dD
    sum_abs = sum(abs(ck) * Dabs**k for k, ck in enumerate(c))  # sum |c_k| |D|^k
    dp_max = sum(k * abs(ck) * Dabs ** (k - 1) for k, ck in enumerate(c) if k >= 1)
    p_min = c[0] - sum(abs(ck) * Dabs**k for k, ck in enumerate(c) if k >= 1)
    assert p_min > 0
    gamma = 2 * n * U / (1 - 2 * n * U)  # Horner with n fused steps: gamma_n; gamma_2n to be safe
    eps_p = (gamma * sum_abs + dp_max * dD) / p_min  # |p_hat / p(tc - t) - 1|
    Q_lo, Q_hi = enclose_Q(c, tc, t_lo, t_hi, pieces)
    # 1 + alpha = sqrt(1 + Q)
    alpha_lo = sqrt_bounds(1 + Q_lo, below=True) - 1
    alpha_hi = sqrt_bounds(1 + Q_hi, below=False) - 1
    # a, b: relative errors of g1 = RN(G p_hat) and hh = RN(Yh p_hat) w.r.t. sqrt(X), 1/(2 sqrt(X))
    L = (1 + alpha_lo) * (1 - eps_p) * (1 - U) ** 2 - 1
    Hb = (1 + alpha_hi) * (1 + eps_p) * (1 + U) ** 2 - 1
    # eta / sqrt(X) = a^2/2 + (a + a^2/2)(b + rho5 (1 + b)),  |rho5| <= u
    eta_lo = L**2 / 2 + (L + L**2 / 2) * (L - U * (1 + Hb))
    eta_hi = Hb**2 / 2 + (Hb + Hb**2 / 2) * (Hb + U * (1 + Hb))
    ok = L > 0 and eta_lo > 0 and eta_hi <= F(1, 2**54)
    out = dict(t_lo=t_lo, t_hi=t_hi, D_lo=D_lo, D_hi=D_hi, alpha_lo=alpha_lo, alpha_hi=alpha_hi,
               eps_p=eps_p, a_lo=L, a_hi=Hb, eta_lo=eta_lo, eta_hi=eta_hi, ok=ok)
    return out
