"""Symplectic splitting schemes for H = T(p) + V(u), applied together with their tangent map.

A scheme is a table of coefficients: one step of size dt is

    kick(b_0) drift(a_0) kick(b_1) drift(a_1) ... drift(a_{s-1}) kick(b_s)

with drift(c): u += c dt M^-1 p and kick(d): p += d dt F(u). The tangent map method (Skokos &
Gerlach 2010) applies the same maps to a deviation vector (du, dp):

    drift(c): du += c dt M^-1 dp        kick(d): dp -= d dt Hess V(u) du

with Hess V tridiagonal from the bond stiffness k = df/dD (plus w''(u_n) on the diagonal for a
model with a site law, whose kick adds -w'(u_n) to each bead's force). A zero kick is skipped, and
a force evaluation is reused by the next kick when no drift came in between, so schemes whose step starts
and ends with a kick (BAB, "first same as last") cost one force evaluation less per step.
"""

from dataclasses import dataclass

import numpy as np
from numba import literally, njit

from chainchaos.errors import require
from chainchaos.kernels.exactmath import ln
from chainchaos.kernels.simd import LANES, vload, vnext, vprev, vstore
from chainchaos.system.models.base import (
    bond_force,
    bond_force_stiffness,
    bond_opening,
    bond_values,
    bond_vectors,
    check_sites,
    parameter_counts,
    site_kick,
    site_kick_deviation,
    site_vectors,
)


def inner(**options):
    """``njit(cache=True, **options)`` for a function that only compiled code calls. Numba builds a
    CPython and a C entry point for every function it compiles, each lowered and optimised like
    the function itself; the single engine's helpers (dozens of literal specialisations) never
    need one, and their callers' machine code is the same without. The batch engine's helpers
    keep theirs: without them its machine code changed. Without its CPython entry point a
    function cannot be called from Python (the interpreter would crash): only private names get
    this.

    Parameters
    ----------
    **options
        Further options of ``numba.njit`` (e.g. ``inline="always"``).

    Returns
    -------
    callable
        The decorator.
    """
    return njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True, **options)


@dataclass(frozen=True)
class Scheme:
    """A splitting scheme: the coefficients of one step (the module docstring), an entry of ``SCHEMES``.

    Parameters
    ----------
    name : str
        Its key in ``SCHEMES`` and in configs (``integrator``).
    order : int
        Its order of accuracy: the energy error of a run scales as dt^order.
    kicks : numpy.ndarray of shape (s + 1,)
        The kick coefficients b_0..b_s (summing to 1; a zero kick is skipped).
    drifts : numpy.ndarray of shape (s,)
        The drift coefficients a_0..a_{s-1} (summing to 1).
    reference : str
        Where it is published.
    """

    name: str
    order: int
    kicks: np.ndarray
    drifts: np.ndarray
    reference: str

    @property
    def force_evaluations(self) -> int:
        """Force evaluations per step in a long run (kicks not preceded directly by a kick)."""
        stages = [("k", b) for b in self.kicks[:1]]
        for a, b in zip(self.drifts, self.kicks[1:]):
            stages += [("d", a), ("k", b)]
        ops = [kind for kind, c in stages if c != 0.0]
        cyclic = ops + ops[:1]
        return sum(1 for i in range(len(ops)) if cyclic[i + 1] == "k" and cyclic[i] == "d")


def _symmetric(half: list[float], middle: float | None = None) -> np.ndarray:
    tail = half[::-1]
    return np.array(half + ([middle] if middle is not None else []) + tail)


def _kick_drift_pairs(b: list[float], a: list[float]) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (kick b_i, drift a_i) as written by Blanes & Moan and McLachlan & Atela."""
    return np.array(b + [0.0]), np.array(a)


def _composition_of_verlet(weights: list[float]) -> tuple[np.ndarray, np.ndarray]:
    """Compose kick-drift-kick Verlet sub-steps of sizes w_i dt, merging adjacent half kicks."""
    w = np.asarray(weights)
    kicks = np.concatenate(([w[0] / 2], (w[:-1] + w[1:]) / 2, [w[-1] / 2]))
    return kicks, w.copy()


def _build_table() -> dict[str, Scheme]:
    table = {}

    def add(name, order, kicks, drifts, reference):
        kicks, drifts = np.asarray(kicks, float), np.asarray(drifts, float)
        assert kicks.size == drifts.size + 1
        assert abs(kicks.sum() - 1) < 1e-14 and abs(drifts.sum() - 1) < 1e-14, name
        table[name] = Scheme(name, order, kicks, drifts, reference)

    add("verlet", 2, [0.5, 0.5], [1.0], "velocity Verlet (Stormer-Verlet, kick-drift-kick)")

    # McLachlan & Atela 1992, optimal fourth order RKN (4 stages, non-symmetric).
    add("mclachlan_atela4", 4, *_kick_drift_pairs(
        [0.1344961992774310892, -0.2248198030794208058, 0.7563200005156682911, 0.3340036032863214255],
        [0.5153528374311229364, -0.085782019412973646, 0.4415830236164665242, 0.1288461583653841854]),
        "McLachlan & Atela, Nonlinearity 5, 541 (1992)")

    # Blanes & Moan 2002, SRKN_6^b: order 4, BAB, 6 force evaluations per step.
    b1, b2, b3 = 0.082984406417405200, 0.39630980149836800, -0.039056304922348600
    a1, a2 = 0.24529895718427100, 0.60487266571108000
    add("SRKN6b", 4, _symmetric([b1, b2, b3], 1 - 2 * (b1 + b2 + b3)),
        _symmetric([a1, a2, 0.5 - a1 - a2]),
        "Blanes & Moan, J. Comput. Appl. Math. 142, 313 (2002), SRKN_6^b")

    # Blanes, Casas, Farres, Laskar, Makazaga & Murua 2013, ABA864: order 4 (8,6,4), 7 evaluations.
    a = [0.0711334264982231177779387300061549964174, 0.241153427956640098736487795326289649618,
         0.521411761772814789212136078067994229991, -0.333698616227678005726562603400438876027]
    b = [0.183083687472197221961703757166430291072, 0.310782859898574869507522291054262796375,
         -0.0265646185119588006972121379164987592663]
    add("ABA864", 4, np.concatenate(([0.0], _symmetric(b, 1 - 2 * sum(b)), [0.0])),
        _symmetric(a[:3] + [0.5 - sum(a[:3])]),
        "Blanes et al., Appl. Numer. Math. 68, 58 (2013), ABA(8,6,4)")

    # Blanes & Moan 2002, SRKN_11^b: order 6, BAB, 11 force evaluations per step.
    b = [0.041464998518262400, 0.19812867191806700, -0.040006192104153300,
         0.075253984301580700, -0.011511387420687900]
    a = [0.12322977594627100, 0.29055379779955800, -0.12704921262541700,
         -0.24633176106207500, 0.35720887279592800]
    add("SRKN11b", 6, _symmetric(b + [0.5 - sum(b)]), _symmetric(a, 1 - 2 * sum(a)),
        "Blanes & Moan, J. Comput. Appl. Math. 142, 313 (2002), SRKN_11^b")

    # Yoshida 1990, sixth order solution A: seven Verlet sub-steps.
    w1, w2, w3 = -1.17767998417887, 0.235573213359357, 0.784513610477560
    add("yoshida6", 6, *_composition_of_verlet([w3, w2, w1, 1 - 2 * (w1 + w2 + w3), w1, w2, w3]),
        "Yoshida, Phys. Lett. A 150, 262 (1990), solution A")
    return table


SCHEMES: dict[str, Scheme] = _build_table()


def get_scheme(name: str) -> Scheme:
    """The splitting scheme called ``name``.

    Parameters
    ----------
    name : str
        A key of ``SCHEMES``.

    Returns
    -------
    Scheme
        Its entry.

    Raises
    ------
    ParameterError
        For a name not in ``SCHEMES`` (the message lists those that are).
    """
    require(name in SCHEMES, "integrator", name, f"one of {sorted(SCHEMES)}")
    return SCHEMES[name]


@njit(cache=True)  # with its entry points: the batch engine's code is compiled as it was measured
def _renormalise(dq, dp):
    s = 0.0
    for n in range(dq.shape[0]):
        s += dq[n] * dq[n] + dp[n] * dp[n]
    norm = np.sqrt(s)
    for n in range(dq.shape[0]):
        dq[n] /= norm
        dp[n] /= norm
    return ln(norm)


@njit(cache=True)
def _check(q, p, dq, dp, tangent, diagnostics):
    """A check of one trajectory's arrays (every ``check_every`` steps and at the end of a call):
    the deviation vector renormalised with ``tangent``, ln of its norm added to diagnostics[0];
    returns whether the state (and the vector's first component) is finite."""
    s = 0.0
    for n in range(q.shape[0]):
        s += q[n] + p[n]
    if tangent:
        diagnostics[0] += _renormalise(dq, dp)
        s += dq[0]
    return np.isfinite(s)


#: The rows of the single engine's work buffer, all indexed alike and padded to whole vectors:
#: displacements U and deviations DQ with the walls (U[0] = U[N+1] = 0, beads at 1..N), momenta
#: P, DP and inverse masses IM of the beads at 1..N, bond force F and stiffness K of bond
#: b = 0..N, which joins U[b] and U[b+1]; then one row per bond parameter of the model (B, as
#: many as ``Model.bond_parameter_count``) and one per site parameter of the beads at 1..N (S,
#: none without a site law).
ROWS = ("U", "DQ", "P", "DP", "IM", "F", "K", "B", "S")


@inner()
def _row_offsets(model, L):
    """Where each of ``ROWS`` starts in the work buffer (B and S: the first of the model's rows),
    and the length R of a row: rows of L + LANES doubles, so that every row starts on a vector
    boundary and a sweep may read one vector past L."""
    R = L + LANES
    n_bond, _ = parameter_counts(model)
    return 0, R, 2 * R, 3 * R, 4 * R, 5 * R, 6 * R, 7 * R, (7 + n_bond) * R, R


@njit(cache=True)  # with its entry points: the batch engine's code is compiled as it was measured
def _drift_vector(drift, tangent, Z, U, DQ, P, DP, IM, n, a):
    """(u, dq) of the vector of beads at n of rows U and DQ, drifted by a if ``drift``:
    u += a M^-1 p, dq += a M^-1 dp, with p, dp and M^-1 at n of rows P, DP and IM (stored back)."""
    u = vload(Z, U + n)
    dq = vload(Z, DQ + n)
    if drift:
        im = vload(Z, IM + n)
        u = u + a * im * vload(Z, P + n)
        vstore(Z, U + n, u)
        if tangent:
            dq = dq + a * im * vload(Z, DP + n)
            vstore(Z, DQ + n, dq)
    return u, dq


@inner()
def _kick_vector(model, tangent, Z, P, DP, site, n, c, f_before, f, g_before, k, u, dq, dq_after):
    """kick(c) of the beads of vector n: p_i += c (F_{i-1} - F_i) and, with the tangent map,
    dp_i += c (G_{i-1} - G_i), G_b = K_b (dq_b - dq_{b+1}); f, k are the forces and stiffnesses of
    the vector's bonds, f_before, g_before those of the vector before, u, dq the displacements and
    deviations of this vector's beads, dq_after the next's. With a site law (parameters ``site``)
    p_i += c ((F_{i-1} - F_i) - w'(u_i)), dp_i += c ((G_{i-1} - G_i) - w''(u_i) dq_i)
    (``models.base.site_kick``; nothing of it is compiled for a model without one). Returns (f, G)
    for the next vector."""
    vstore(Z, P + n, vload(Z, P + n) + c * site_kick(model, site, u, vprev(f_before, f) - f))
    g = f
    if tangent:
        g = k * (dq - vnext(dq, dq_after))
        vstore(Z, DP + n, vload(Z, DP + n) + c * site_kick_deviation(model, site, u, dq, vprev(g_before, g) - g))
    return f, g


@inner(error_model="numpy")
def _stage(model, tangent, drift, kick, keep_forces, L, Z, a, c):
    """One pass over the vectors of the work buffer: (if ``drift``) drift(a) of every bead, then
    (if ``kick``) the force and stiffness of every bond at the new positions (stored in F and K
    with ``keep_forces``) and kick(c) of every bead. Iteration n drifts vector n+1, computes the
    bonds of vector n (bond b joins U[b] and U[b+1], both drifted) and kicks vector n (bead i
    takes F[i-1] - F[i]), so the vectors' work overlaps instead of making three passes that store
    what the next one loads.
    Per element the operations of drift(a), the force law and kick(c), in that order:
    dq_i += a dp_i / m_i, G_b = K_b (dq_b - dq_{b+1}), dp_i += c (G_{i-1} - G_i) for the tangent
    map."""
    literally(tangent)
    literally(drift)
    literally(kick)
    literally(keep_forces)
    U, DQ, P, DP, IM, F, K, B, S, R = _row_offsets(model, L)
    u, dq = _drift_vector(drift, tangent, Z, U, DQ, P, DP, IM, np.int64(0), a)  # not Literal[int](0): one compile
    f_before = g_before = vload(Z, U + L)  # U[L:L+LANES], always zero
    for b in range(0, L, LANES):
        if b + LANES < L:
            u_after, dq_after = _drift_vector(drift, tangent, Z, U, DQ, P, DP, IM, b + LANES, a)
        else:  # the vector past L: zero, never drifted
            u_after, dq_after = vload(Z, U + L), vload(Z, DQ + L)
        if kick:
            bond = bond_vectors(model, Z, B + b, R)
            if tangent:
                f, k = bond_force_stiffness(model, bond, u, vnext(u, u_after))
            else:
                f = k = bond_force(model, bond, u, vnext(u, u_after))
            if keep_forces:
                vstore(Z, F + b, f)
                if tangent:
                    vstore(Z, K + b, k)
            f_before, g_before = _kick_vector(model, tangent, Z, P, DP, site_vectors(model, Z, S + b, R), b, c,
                                              f_before, f, g_before, k, u, dq, dq_after)
        u, dq = u_after, dq_after


@inner(error_model="numpy")
def _kick(model, tangent, L, Z, c):
    """kick(c) of every bead with the stored forces F and stiffnesses K:
    p_i += c (F_{i-1} - F_i);  dp_i += c (G_{i-1} - G_i), G_b = K_b (dq_b - dq_{b+1}); a site law's
    w'(u_i) and w''(u_i) are computed again at the unchanged displacements (the same bits)."""
    literally(tangent)
    U, DQ, P, DP, _, F, K, _, S, R = _row_offsets(model, L)
    f_before = g_before = vload(Z, U + L)  # zero
    dq = vload(Z, DQ)
    for n in range(0, L, LANES):
        dq_after = vload(Z, DQ + n + LANES)
        f_before, g_before = _kick_vector(model, tangent, Z, P, DP, site_vectors(model, Z, S + n, R), n, c,
                                          f_before, vload(Z, F + n), g_before, vload(Z, K + n), vload(Z, U + n), dq, dq_after)
        dq = dq_after


@inner(error_model="numpy")
def _step_loop(model, tangent, N, L, Z, bonds, kicks, drifts, dt, n_steps, check_every, track_gaps, gap_steps,
               diagnostics):
    """The steps of ``advance`` on its work buffer Z (``ROWS``, ``_row_offsets``).

    Every loop runs over whole, aligned vectors of LANES elements, 0..L-1 with L >= N + 2; a
    neighbour's values (U[b+1], F[i-1], ...) come from the vector before or after by a shuffle
    (``simd.vnext``, ``simd.vprev``), not from an unaligned load of data just stored. Padding
    beads (0 and N+1.. L-1) have zero inverse mass and never move (P[0] and P[N+1] collect the
    walls' impulse, unused); padding bonds have zero parameters and carry no force. A drift and
    the kick after it are one pass (``_stage``); the forces of a step's last kick are stored, for
    a kick that follows it without a drift (``_kick``) and for the caller. Per element the
    operations are those of the scalar expressions, in the same order.
    """
    literally(tangent)
    U, DQ, P, DP, _, _, _, _, _, _ = _row_offsets(model, L)
    n_stages = drifts.shape[0]
    last_kick = -1  # the last stage whose drift a kick follows
    for i in range(n_stages):
        if kicks[i + 1] != 0.0:
            last_kick = i
    force_valid = False
    bad = -1
    for step in range(n_steps):
        c = kicks[0] * dt
        if c != 0.0:
            if force_valid:
                _kick(model, tangent, L, Z, c)
            else:
                _stage(model, tangent, False, True, True, L, Z, 0.0, c)
        for i in range(n_stages):
            a, c = drifts[i] * dt, kicks[i + 1] * dt
            if c == 0.0:
                _stage(model, tangent, True, False, False, L, Z, a, c)
            elif i == last_kick:
                _stage(model, tangent, True, True, True, L, Z, a, c)
            else:
                _stage(model, tangent, True, True, False, L, Z, a, c)
            force_valid = c != 0.0
        if track_gaps:  # open bonds
            n_open = 0
            for b in range(N + 1):
                is_open = bond_opening(model, bond_values(model, bonds, b), Z[U + b], Z[U + b + 1]) < 0.0
                gap_steps[b] += is_open
                n_open += is_open
            if n_open > diagnostics[1]:
                diagnostics[1] = n_open
        if (step + 1) % check_every == 0 or step + 1 == n_steps:
            s = 0.0
            for n in range(1, N + 1):
                s += Z[U + n] + Z[P + n]
            if tangent:
                diagnostics[0] += _renormalise(Z[DQ + 1:DQ + N + 1], Z[DP + 1:DP + N + 1])
                s += Z[DQ + 1]
            if not np.isfinite(s):
                bad = step + 1
                break
    return bad


@njit(cache=True)  # with its entry points: the batch engine's code is compiled as it was measured
def _aligned_zeros(n):
    """n zeros starting on a 64-byte boundary (a cache line, an AVX-512 vector)."""
    buf = np.zeros(n + 8)
    misalignment = int(buf.ctypes.data % np.uint64(64)) // 8
    return buf[(8 - misalignment) % 8:][:n]


@inner()
def _put(Z, start, x):
    """Z[start:start + x.size] = x, one element at a time. A slice assignment between arrays
    compiles Numba's formatted shape-mismatch error (seconds of compilation per kernel that has
    one) for a check these copies, sized by construction, never need."""
    for i in range(x.shape[0]):
        Z[start + i] = x[i]


@inner()
def _take(Z, start, x, n):
    """x[:n] = Z[start:start + n], one element at a time (see :func:`_put`)."""
    for i in range(n):
        x[i] = Z[start + i]


@njit(cache=True, error_model="numpy")
def advance(model, q, p, dq, dp, inv_mass, bonds, kicks, drifts, dt, n_steps, tangent, check_every, track_gaps,
            gap_steps, diagnostics, f, k, sites=None):
    """Advance the state (q, p) of ``model`` (a ``chainchaos.system.models`` Model) and, if ``tangent``,
    the deviation vector (dq, dp) by n_steps.

    inv_mass (N,); bonds (parameters, N+1), the model's bond parameters
    (``Model.bond_parameters``); sites (parameters, N), the site parameters of a model
    with a site law (``Model.site_parameters``; required for one, ignored otherwise). Every
    ``check_every`` steps and at the end the state is checked for finiteness and the deviation
    vector is renormalised, its log growth added to diagnostics[0]. With ``track_gaps`` (a model
    whose bonds open) the number of steps each bond ends open is added to gap_steps and the
    largest number of simultaneously open bonds is kept in diagnostics[1]. f and k (N+1) are left holding the last bond forces and stiffnesses.
    Returns -1, or the number of steps done when a non-finite state stopped the run.

    The state and parameters are copied into one aligned work buffer (``ROWS``), padded to whole
    SIMD vectors (``chainchaos.kernels.simd``), and the steps run on explicit vectors across the bonds:
    no loop has a scalar remainder or needs a runtime check that two arrays do not overlap. The
    model's bond law and site law are compiled in (each model gets its own machine code); the cache directory is
    keyed by the kernels' source (chainchaos.kernels.cache), so an edit there recompiles this.
    """
    check_sites(model, sites)
    N = q.shape[0]
    L = (N + 1 + LANES) // LANES * LANES
    n_bond, n_site = parameter_counts(model)
    U, DQ, P, DP, IM, F, K, B, S, R = _row_offsets(model, L)
    Z = _aligned_zeros((7 + n_bond + n_site) * R)
    _put(Z, U + 1, q)
    _put(Z, DQ + 1, dq)
    _put(Z, P + 1, p)
    _put(Z, DP + 1, dp)
    _put(Z, IM + 1, inv_mass)
    for r in range(n_bond):
        _put(Z, B + r * R, bonds[r])
    if sites is not None:
        for r in range(n_site):
            _put(Z, S + r * R + 1, sites[r])
    # the tangent flag literal: each case compiles to its own code without these branches
    if tangent:
        bad = _step_loop(model, True, N, L, Z, bonds, kicks, drifts, dt, n_steps, check_every, track_gaps,
                         gap_steps, diagnostics)
    else:
        bad = _step_loop(model, False, N, L, Z, bonds, kicks, drifts, dt, n_steps, check_every, track_gaps,
                         gap_steps, diagnostics)
    _take(Z, U + 1, q, N)
    _take(Z, DQ + 1, dq, N)
    _take(Z, P + 1, p, N)
    _take(Z, DP + 1, dp, N)
    _take(Z, F, f, N + 1)
    _take(Z, K, k, N + 1)
    return bad
