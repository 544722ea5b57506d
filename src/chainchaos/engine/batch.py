"""A batch engine: B trajectories integrated at once, vectorised across trajectories.

``integrators.advance`` integrates one trajectory, vectorised across its bonds: a vector of
LANES bonds holds one trajectory's neighbouring bonds, and a chain of N = 40 fills six of them.
Here the trajectories go in blocks of ``LANES`` (the SIMD width fitted to the CPU,
``chainchaos.kernels.simd``), one lane per trajectory: a drift, the forces and stiffnesses at the new
positions and a kick are one sweep over the bonds that keeps the neighbouring beads' vectors and
the bonds' forces in registers, each bond's work spread over three iterations so that the square
roots of the Hertz force overlap with the rest of the work; forces are stored only where the next
step's first kick reuses them. A block's state and parameters live in one 64-byte aligned buffer,
row by row (row r: the LANES lanes of each of the ``QUANTITIES`` in turn): all a sweep touches
fits in L1 cache, every vector load is aligned, and no two quantities that one iteration reads and
writes sit 4 KiB apart (separately allocated arrays made the timing vary from one process to the
next).

The trajectories of a batch share the model, the scheme, dt and the number of steps; each has its
own state, deviation vector and chain parameters (per-trajectory arrays shaped (N+1, B) for bond
parameters and (N, B) for inverse masses: one chain repeated, or B different realizations). A
batch of any size B is padded to whole blocks by repeating its last trajectory, or its last
lanes run on the single-trajectory engine (:class:`Batch`'s ``serial_lanes``): a block costs
more than :data:`SERIAL_REMAINDER` single-engine trajectories, whatever its padding.

Semantics are those of ``integrators.advance`` lane by lane, to the bit (tests/engine/test_batch.py,
tests/engine/test_lane_width.py, at every width): the same kick/drift table (``integrators.SCHEMES``),
the same floating-point operations in the same order, a force evaluation reused by the next kick
when no drift came in between, the tangent map drift(c): dq += c dt M^-1 dp, kick(d): dp -= d dt
Hess V(u) dq with Hess V tridiagonal from the bond stiffness (and a site law's w'(u) and w''(u)
on each bead, for a model with one), and every ``check_every`` steps and
at the end of a call the deviation vector of each trajectory renormalised, its log growth added
to ``log_growth[j]``. A trajectory whose state becomes non-finite is reported in ``bad[j]`` (the
step of the first failed check) while the other lanes go on: lanes never mix.

Speed: ``benchmarks/batch_throughput.py`` (figures in the README, per machine).
"""

import numpy as np
from numba import literally, njit

from chainchaos.engine.integrators import (
    _aligned_zeros,
    _drift_vector,
    _renormalise,
    advance,
)
from chainchaos.errors import require
from chainchaos.kernels.exactmath import gram_schmidt
from chainchaos.kernels.simd import LANES, vbelow, vload, vstore
from chainchaos.system.models.base import (
    bond_force,
    bond_force_stiffness,
    bond_opening,
    bond_vectors,
    check_sites,
    parameter_counts,
    site_kick,
    site_kick_deviation,
    site_vectors,
)

#: Up to this many lanes beyond whole blocks cost no more on the single-trajectory engine than in
#: a padded block: a block takes the time of LANES / r single-engine trajectories, r the batch
#: speed-up that ``benchmarks/batch_throughput.py`` prints (about 1.6 to 2 at both widths).
SERIAL_REMAINDER = LANES // 2

#: The per-row contents of a block's buffer, LANES doubles each. Row r of U and DQ is bead r-1
#: (the walls are rows 0 and N+1); row n of P, DP and IM is bead n; row b of the bond force F and
#: stiffness K is bond b, which joins beads b-1 and b. Then, in the same row, the model's
#: parameters (``models.base``), as many as it has: bond b's (B), then bead b's site law's (S,
#: none without one). All a sweep touches of a bond is in one row, read in order.
QUANTITIES = ("U", "DQ", "P", "DP", "IM", "F", "K", "B", "S")
_U, _DQ, _P, _DP, _IM, _F, _K, _B = (i * LANES for i in range(len(QUANTITIES) - 1))


@njit(cache=True)
def _row(model):
    """Doubles per row of a block's buffer: seven quantities and the model's parameters."""
    n_bond, n_site = parameter_counts(model)
    return (7 + n_bond + n_site) * LANES


@njit(cache=True)
def _site_offset(model):
    """Where a row's site parameters start (``QUANTITIES``): after its bond parameters."""
    n_bond, _ = parameter_counts(model)
    return _B + n_bond * LANES


@njit(cache=True)
def _bond_parameters(model, Z, bond):
    """The parameters of the bond whose row starts at ``bond``, as vectors (a tuple, one per
    bond parameter of the model)."""
    return bond_vectors(model, Z, bond + _B, LANES)


@njit(cache=True)
def _site_parameters(model, Z, row):
    """The site parameters of the bead whose momenta are in row ``row``, as vectors (the empty
    tuple without a site law)."""
    return site_vectors(model, Z, row + _site_offset(model), LANES)


@njit(cache=True, error_model="numpy")
def _sweep(model, tangent, drift, kick, keep_forces, N, Z, a, c):
    """One pass over the bonds b = 0..N of a block: (if ``drift``) drift(a) of every bead, (if
    ``kick``) the force and stiffness of every bond at the new positions and kick(c) of every
    bead; with ``keep_forces`` the forces and stiffnesses are stored for a kick that follows
    without a drift. Iteration b drifts bead b+1, computes bond b (between beads b-1 and b, both
    drifted) and kicks bead b-2 (whose bonds were computed in the two iterations before), so that
    the long chain of one bond, drift - force (a square root for Hertz) - kick, is spread over
    three iterations: the CPU overlaps the bonds instead of holding one bond's chain in its
    schedulers. A bond's force f and tangent force g = k (dq_{b-1} - dq_b) stay in registers until
    both kicks that use them are done: each is computed once. Per lane the operations are those
    of ``integrators.advance``, in the same order. Row N (no bead) has zero momenta and inverse
    masses, so its drift leaves the right wall at zero."""
    literally(tangent)
    literally(drift)
    literally(kick)
    literally(keep_forces)
    row_size = _row(model)
    u_left = vload(Z, _U)  # the wall
    dq_left = vload(Z, _DQ)  # deviation of bead b-1
    u_right, dq_right = _drift_bead(drift, tangent, Z, row_size, 0, a)
    f1 = f2 = g1 = g2 = u_left  # f, g of bonds b-1 and b-2
    for b in range(N + 1):
        bond = b * row_size
        if b < N:
            u_next, dq_next = _drift_bead(drift, tangent, Z, row_size, bond + row_size, a)
        else:
            u_next, dq_next = u_right, dq_right
        if kick:
            parameters = _bond_parameters(model, Z, bond)
            if tangent:
                f, k = bond_force_stiffness(model, parameters, u_left, u_right)
            else:
                f = bond_force(model, parameters, u_left, u_right)
                k = f
            if keep_forces:
                vstore(Z, bond + _F, f)
                if tangent:
                    vstore(Z, bond + _K, k)
            g = k * (dq_left - dq_right) if tangent else f
            if b >= 2:
                _kick_bead(model, tangent, Z, bond - 2 * row_size, c, f2, f1, g2, g1)
            f2, g2, f1, g1 = f1, g1, f, g
        u_left, dq_left = u_right, dq_right
        u_right, dq_right = u_next, dq_next
    if kick:
        _kick_bead(model, tangent, Z, (N - 1) * row_size, c, f2, f1, g2, g1)


@njit(cache=True)
def _drift_bead(drift, tangent, Z, row_size, bond, a):
    """(u, dq) of the bead whose momenta are in row ``bond`` (its displacement in the next row, rows
    ``row_size`` doubles apart), drifted by a if ``drift``: u += a M^-1 p, dq += a M^-1 dp (``integrators._drift_vector``)."""
    bead = bond + row_size
    return _drift_vector(drift, tangent, Z, bead + _U, bead + _DQ, bond + _P, bond + _DP, bond + _IM, 0, a)


@njit(cache=True)
def _kick_bead(model, tangent, Z, row, c, f_left, f_right, g_left, g_right):
    """kick(c) of the bead of ``row`` between bonds whose forces are f_left and f_right (tangent
    forces g_left, g_right): p += c (f_left - f_right), dp += c (g_left - g_right); with a site law
    p += c ((f_left - f_right) - w'(u)), dp += c ((g_left - g_right) - w''(u) dq) at the bead's
    (drifted) u and dq, read back from the buffer (``models.base.site_kick``: nothing of it is
    compiled for a model without one)."""
    row_size = _row(model)
    site = _site_parameters(model, Z, row)
    u = vload(Z, row + row_size + _U)
    vstore(Z, row + _P, vload(Z, row + _P) + c * site_kick(model, site, u, f_left - f_right))
    if tangent:
        dq = vload(Z, row + row_size + _DQ)
        vstore(Z, row + _DP, vload(Z, row + _DP) + c * site_kick_deviation(model, site, u, dq, g_left - g_right))


@njit(cache=True, error_model="numpy")
def _kick_only(model, tangent, N, Z, c):
    """kick(c) of every bead with the stored forces and stiffnesses (the tangent force of bond b,
    g_b = k_b (dq_{b-1} - dq_b), carried from one bead to the next); a site law's w'(u) and w''(u)
    are computed again at the unchanged displacements (the same bits)."""
    literally(tangent)
    row_size = _row(model)
    f_left = vload(Z, _F)
    g_left = vload(Z, _K) * (vload(Z, _DQ) - vload(Z, row_size + _DQ)) if tangent else f_left
    for n in range(N):
        row = n * row_size
        site = _site_parameters(model, Z, row)
        u = vload(Z, row + row_size + _U)
        f = vload(Z, row + row_size + _F)
        vstore(Z, row + _P, vload(Z, row + _P) + c * site_kick(model, site, u, f_left - f))
        f_left = f
        if tangent:
            dq = vload(Z, row + row_size + _DQ)
            g = vload(Z, row + row_size + _K) * (dq - vload(Z, row + 2 * row_size + _DQ))
            vstore(Z, row + _DP, vload(Z, row + _DP) + c * site_kick_deviation(model, site, u, dq, g_left - g))
            g_left = g


#: An extra deviation vector's buffer, per lane: row r holds its dq of bead r-1 (rows 0 and N+1,
#: the walls, stay zero) and its dp of bead r, as in a block's rows (``QUANTITIES``).
_VQ, _VP = 0, LANES
VROW = 2 * LANES


@njit(cache=True)
def _vector_base(N, j):
    """Where extra deviation vector j starts in the buffer of a block's extra vectors."""
    return j * (N + 2) * VROW


#: Extra deviation vectors advanced together by one pass over the bonds: they share its loads of
#: the inverse masses and stiffnesses, which leaves the stores of dq and dp as the pass's limit.
VECTOR_GROUP = 3


@njit(cache=True)
def _vector_bond(model, V, vector, b, N, drift, kick, a_im, stiffness, site, u_left, c, wall, dq_left, g_left,
                 dp_left):
    """Iteration b of a pass over the bonds for one extra deviation vector starting at ``vector``:
    drift(a) of bead b (dq += a M^-1 dp with its dp before the kick; ``a_im`` = a M^-1 of the
    bead), the tangent force g_b = k_b (dq_{b-1} - dq_b) of bond b and kick(c) of bead b-1, whose
    dp (``dp_left``, loaded by the iteration before) is stored kicked, with -w''(u) dq of its site
    law (parameters ``site``, displacement ``u_left``) for a model with one; bead N is the right
    ``wall`` (zero). Returns (dq_b, g_b, dp_b) for iteration b+1."""
    if b < N:
        dp = vload(V, vector + b * VROW + _VP)
        dq = vload(V, vector + (b + 1) * VROW + _VQ)
        if drift:
            dq = dq + a_im * dp
            vstore(V, vector + (b + 1) * VROW + _VQ, dq)
    else:
        dp = dq = wall
    g = g_left
    if kick:
        g = stiffness * (dq_left - dq)
        if b >= 1:
            vstore(V, vector + (b - 1) * VROW + _VP,
                   dp_left + c * site_kick_deviation(model, site, u_left, dq_left, g_left - g))
    return dq, g, dp


@njit(cache=True, error_model="numpy")
def _drift_kick_vectors(model, N, Z, V, extra, drift, kick, a, c):
    """drift(a) (if ``drift``) then kick(c) (if ``kick``) of the ``extra`` deviation vectors in V
    with the inverse masses and the stiffnesses stored in the block Z (the orbit's sweep stored
    them at the drifted positions): per lane and element the operations of ``_sweep`` on the
    block's own deviation vector, dq += a M^-1 dp, g_b = k_b (dq_{b-1} - dq_b),
    dp += c (g_b - g_{b+1}), so a vector equal to it stays equal to it, to the bit. The vectors go
    by groups of ``VECTOR_GROUP``, one pass over the bonds per group (the last ones one by one);
    iteration b drifts bead b, computes bond b (beads b-1 and b, both drifted) and kicks bead
    b-1 (whose drift used its momentum before the kick; a site law's w''(u) of that bead at the
    orbit's drifted u, as the block's own vector has it)."""
    literally(drift)
    literally(kick)
    row_size = _row(model)
    wall = vload(V, _VQ)  # row 0 of vector 0: a wall, zero
    grouped = extra - extra % VECTOR_GROUP
    for j in range(0, grouped, VECTOR_GROUP):
        v0, v1, v2 = _vector_base(N, j), _vector_base(N, j + 1), _vector_base(N, j + 2)
        q0 = g0 = p0 = q1 = g1 = p1 = q2 = g2 = p2 = wall
        for b in range(N + 1):
            a_im = a * vload(Z, b * row_size + _IM)  # row N: zero
            k = vload(Z, b * row_size + _K) if kick else wall
            site = _site_parameters(model, Z, max(b - 1, 0) * row_size)  # bead b-1's (used from b = 1)
            u = vload(Z, b * row_size + _U)
            q0, g0, p0 = _vector_bond(model, V, v0, b, N, drift, kick, a_im, k, site, u, c, wall, q0, g0, p0)
            q1, g1, p1 = _vector_bond(model, V, v1, b, N, drift, kick, a_im, k, site, u, c, wall, q1, g1, p1)
            q2, g2, p2 = _vector_bond(model, V, v2, b, N, drift, kick, a_im, k, site, u, c, wall, q2, g2, p2)
    for j in range(grouped, extra):
        v0 = _vector_base(N, j)
        q0 = g0 = p0 = wall
        for b in range(N + 1):
            a_im = a * vload(Z, b * row_size + _IM)  # row N: zero
            k = vload(Z, b * row_size + _K) if kick else wall
            site = _site_parameters(model, Z, max(b - 1, 0) * row_size)
            u = vload(Z, b * row_size + _U)
            q0, g0, p0 = _vector_bond(model, V, v0, b, N, drift, kick, a_im, k, site, u, c, wall, q0, g0, p0)


@njit(cache=True, error_model="numpy")
def _normalise_vectors(N, Z, row_size, V, lane, extra, orthogonal, growth, W, lane_growth):
    """The extra deviation vectors of one lane at a check, gathered with the block's own vector
    (already normalised) into the rows of W (extra + 1, 2N), the first ``orthogonal`` of them
    orthonormalised against it and each other and the others normalised
    (``kernels.exactmath.gram_schmidt``), ln of their norms added to growth[:, lane]."""
    for n in range(N):
        W[0, n] = Z[(n + 1) * row_size + _DQ + lane]
        W[0, N + n] = Z[n * row_size + _DP + lane]
        for j in range(extra):
            W[j + 1, n] = V[_vector_base(N, j) + (n + 1) * VROW + _VQ + lane]
            W[j + 1, N + n] = V[_vector_base(N, j) + n * VROW + _VP + lane]
    lane_growth[:] = 0.0
    gram_schmidt(W, 1, orthogonal + 1, lane_growth)
    for j in range(extra):
        growth[j, lane] += lane_growth[j]
        for n in range(N):
            V[_vector_base(N, j) + (n + 1) * VROW + _VQ + lane] = W[j + 1, n]
            V[_vector_base(N, j) + n * VROW + _VP + lane] = W[j + 1, N + n]


@njit(cache=True, error_model="numpy")
def _count_gaps(model, N, Z, gap_steps, max_gaps):
    """Open bonds of every lane (the model's opening < 0): one step added to
    gap_steps[b] (a row of LANES counts per bond, as doubles) and max_gaps (LANES) raised to the
    number open now where that is larger."""
    row_size = _row(model)
    n_open = vload(max_gaps, 0) * 0.0
    for b in range(N + 1):
        bond = b * row_size
        parameters = _bond_parameters(model, Z, bond)
        is_open = vbelow(bond_opening(model, parameters, vload(Z, bond + _U), vload(Z, bond + row_size + _U)), 0.0)
        vstore(gap_steps, b * LANES, vload(gap_steps, b * LANES) + is_open)
        n_open = n_open + is_open
    vstore(max_gaps, 0, max(n_open, vload(max_gaps, 0)))


@njit(cache=True, error_model="numpy")
def _advance_block(model, tangent, N, Z, kicks, drifts, dt, n_steps, check_every, track_gaps, gap_steps,
                   log_growth, max_gaps, bad, V, extra, orthogonal, vector_growth):
    """``advance_batch`` for one block in its buffer Z; gap_steps is (N+1) x LANES, flattened, and
    with max_gaps held as doubles. With the tangent map, the ``extra`` deviation vectors in V
    (``_vector_base``) follow the block's own one through every drift and kick (the stiffnesses
    are then stored at every sweep); at every check the first ``orthogonal`` of them are
    orthonormalised against it and each other, the rest normalised, and ln of their norms added
    to vector_growth (extra, LANES)."""
    literally(tangent)
    row_size = _row(model)
    n_stages = drifts.shape[0]
    force_valid = False
    W = np.empty((extra + 1, 2 * N))  # a lane's vectors at a check, and their ln norms
    lane_growth = np.empty(max(extra, 1))
    for step in range(n_steps):
        c = kicks[0] * dt
        if c != 0.0:
            if force_valid:
                _kick_only(model, tangent, N, Z, c)
            elif extra:
                _sweep(model, tangent, False, True, True, N, Z, 0.0, c)
            else:
                _sweep(model, tangent, False, True, False, N, Z, 0.0, c)
            if extra:
                _drift_kick_vectors(model, N, Z, V, extra, False, True, 0.0, c)
        for i in range(n_stages):
            a, c = drifts[i] * dt, kicks[i + 1] * dt
            if c == 0.0:
                _sweep(model, tangent, True, False, False, N, Z, a, c)
            elif i == n_stages - 1 or extra:  # the forces are kept for the next step's first kick
                _sweep(model, tangent, True, True, True, N, Z, a, c)  # or the extra vectors' kick
            else:
                _sweep(model, tangent, True, True, False, N, Z, a, c)
            if extra:
                if c == 0.0:
                    _drift_kick_vectors(model, N, Z, V, extra, True, False, a, c)
                else:
                    _drift_kick_vectors(model, N, Z, V, extra, True, True, a, c)
            force_valid = c != 0.0
        if track_gaps:
            _count_gaps(model, N, Z, gap_steps, max_gaps)
        if (step + 1) % check_every == 0 or step + 1 == n_steps:
            for j in range(LANES):
                s = 0.0
                for n in range(N):
                    s += Z[(n + 1) * row_size + _U + j] + Z[n * row_size + _P + j]
                if tangent:  # lane j's deviation vector: every row_size-th element of the buffer
                    log_growth[j] += _renormalise(Z[row_size + _DQ + j:(N + 1) * row_size + _DQ + j:row_size],
                                                  Z[_DP + j:N * row_size + _DP + j:row_size])
                    s += Z[row_size + _DQ + j]
                    if extra:
                        _normalise_vectors(N, Z, row_size, V, j, extra, orthogonal, vector_growth, W, lane_growth)
                if bad[j] < 0 and not np.isfinite(s):
                    bad[j] = step + 1


@njit(cache=True, error_model="numpy")
def advance_batch(model, q, p, dq, dp, inv_mass, bonds, kicks, drifts, dt, n_steps, tangent, check_every, track_gaps,
                  gap_steps, log_growth, max_gaps, bad, lanes, xq, xp, orthogonal, x_growth, vectors_on, sites=None):
    """Advance the first ``lanes`` of the B trajectories (q, p) of ``model`` (a ``chainchaos.system.models``
    Model), shape (N, B), and, if ``tangent``, their deviation vectors (dq, dp) by n_steps steps of
    the scheme (kicks, drifts), in blocks of LANES (the last padded by repeating its last lane).

    inv_mass (N, B); bonds (parameters, N+1, B), the model's bond parameters, bond b
    joining beads b-1 and b (walls at b = 0 and b = N); sites (parameters, N, B), the
    site parameters of a model with a site law (required for one, ignored otherwise). Every ``check_every`` steps and at the
    end: each lane's state is checked for finiteness (``bad[j]`` set to the step count of the
    first failed check if it is still < 0) and, with ``tangent``, its deviation vector
    renormalised, ln|v| added to ``log_growth[j]``. With ``track_gaps`` (a model whose bonds open)
    ``gap_steps[b, j]`` counts the steps bond b of lane j ends open and ``max_gaps[j]`` keeps the
    largest number of simultaneously open bonds. With the tangent map, ``xq, xp`` (K, N, B) are K
    more deviation vectors of every trajectory, evolved by the same tangent map with the
    trajectory's stiffnesses (computed once for all its vectors); at every check the first
    ``orthogonal`` of them are orthonormalised against (dq, dp) and each other (modified
    Gram-Schmidt) and the others normalised, ln of each norm added to ``x_growth[k, j]``; a block
    whose lanes all have ``vectors_on[j]`` False leaves its K vectors as they are (the orbit and
    the mLCE vector run the same either way). All arrays are updated in place.
    """
    check_sites(model, sites)
    N = q.shape[0]
    B = lanes
    extra = xq.shape[0] if tangent else 0
    n_bond, n_site = parameter_counts(model)
    row_size, site_offset = _row(model), _site_offset(model)
    Z = _aligned_zeros((N + 2) * row_size)
    V = _aligned_zeros(max(extra, 1) * (N + 2) * VROW)
    block_gaps = _aligned_zeros((N + 1) * LANES)  # counts as doubles, exact below 2**53
    block_growth = np.zeros(LANES)
    block_max_gaps = _aligned_zeros(LANES)
    block_bad = np.zeros(LANES, dtype=np.int64)
    block_x_growth = np.zeros((max(extra, 1), LANES))
    for first in range(0, B, LANES):
        Z[:] = 0.0
        V[:] = 0.0
        for lane in range(LANES):
            j = min(first + lane, B - 1)  # padding lanes repeat the last trajectory
            for n in range(N):
                Z[(n + 1) * row_size + _U + lane] = q[n, j]
                Z[(n + 1) * row_size + _DQ + lane] = dq[n, j]
                Z[n * row_size + _P + lane] = p[n, j]
                Z[n * row_size + _DP + lane] = dp[n, j]
                Z[n * row_size + _IM + lane] = inv_mass[n, j]
                if sites is not None:
                    for r in range(n_site):
                        Z[n * row_size + site_offset + r * LANES + lane] = sites[r, n, j]
                for k in range(extra):
                    V[_vector_base(N, k) + (n + 1) * VROW + _VQ + lane] = xq[k, n, j]
                    V[_vector_base(N, k) + n * VROW + _VP + lane] = xp[k, n, j]
            for b in range(N + 1):
                for r in range(n_bond):
                    Z[b * row_size + _B + r * LANES + lane] = bonds[r, b, j]
                block_gaps[b * LANES + lane] = gap_steps[b, j]
            block_growth[lane] = log_growth[j]
            block_max_gaps[lane] = max_gaps[j]
            block_bad[lane] = bad[j]
            for k in range(extra):
                block_x_growth[k, lane] = x_growth[k, j]
        # The counts of extra vectors are int64 in both calls, never a literal 0: Numba compiles a
        # function once more for each literal argument (the tangent block again for a
        # block_extra of Literal[int](0), the vectors' helpers again for the no-tangent block's),
        # about 6 s per model. Without the tangent map ``extra`` is 0 and no vector is touched.
        block_extra = extra if np.any(vectors_on[first:min(first + LANES, B)]) else 0
        # the tangent flag literal: each case compiles to its own code without these branches
        if tangent:
            _advance_block(model, True, N, Z, kicks, drifts, dt, n_steps, check_every, track_gaps, block_gaps,
                           block_growth, block_max_gaps, block_bad, V, block_extra, orthogonal, block_x_growth)
        else:
            _advance_block(model, False, N, Z, kicks, drifts, dt, n_steps, check_every, track_gaps,
                           block_gaps, block_growth, block_max_gaps, block_bad, V, extra, extra, block_x_growth)
        for lane in range(min(LANES, B - first)):
            j = first + lane
            for n in range(N):
                q[n, j] = Z[(n + 1) * row_size + _U + lane]
                dq[n, j] = Z[(n + 1) * row_size + _DQ + lane]
                p[n, j] = Z[n * row_size + _P + lane]
                dp[n, j] = Z[n * row_size + _DP + lane]
                for k in range(extra):
                    xq[k, n, j] = V[_vector_base(N, k) + (n + 1) * VROW + _VQ + lane]
                    xp[k, n, j] = V[_vector_base(N, k) + n * VROW + _VP + lane]
            for b in range(N + 1):
                gap_steps[b, j] = np.int64(block_gaps[b * LANES + lane])
            log_growth[j] = block_growth[lane]
            max_gaps[j] = np.int64(block_max_gaps[lane])
            bad[j] = block_bad[lane]
            for k in range(extra):
                x_growth[k, j] = block_x_growth[k, lane]


class Batch:
    """The lanes of a :class:`~chainchaos.engine.problem.Problem` advanced together: the first lanes in
    SIMD blocks by ``advance_batch``, the last ``serial_lanes`` one after the other by the
    single-trajectory engine (``integrators.advance``), with the same numbers either way.

    ``q, p, dq, dp`` are (N, B) arrays (trajectory index last); ``log_growth`` (B,) accumulates
    ln|v| over renormalisations, so Lambda(t) = log_growth / t as in ``integrators.advance``;
    ``gap_steps`` (N+1, B) and ``max_gaps`` (B,) accumulate the gap counts (the caller resets them).
    ``xq, xp`` (K, N, B) are the problem's ``extra_vectors`` more deviation vectors per lane (its
    spectrum's, orthonormalised, then GALI's, normalised, at every renormalisation) and
    ``x_growth`` (K, B) their accumulated ln of the norms; they run in SIMD blocks only, and stop in
    a block once ``vectors_on`` (B,) is False for all its lanes (:meth:`stop_vectors`).
    """

    def __init__(self, problem, q, p, dq=None, dp=None, serial_lanes: int = 0, xq=None, xp=None):
        self.problem, self.model, self.scheme = problem, problem.model, problem.scheme
        self._take_parameters(problem)
        self.q = np.ascontiguousarray(q, dtype=float).copy()
        self.p = np.ascontiguousarray(p, dtype=float).copy()
        shape = self.q.shape
        require(self.p.shape == shape == (problem.N, problem.lanes), "state shape", shape,
                f"(N, B) = {(problem.N, problem.lanes)}")
        self.dq = np.zeros(shape) if dq is None else np.ascontiguousarray(dq, dtype=float).copy()
        self.dp = np.zeros(shape) if dp is None else np.ascontiguousarray(dp, dtype=float).copy()
        N, B = shape
        require(0 <= int(serial_lanes) <= B, "serial_lanes", serial_lanes, f"an integer from 0 to the {B} lanes")
        self.block_lanes = B - int(serial_lanes)
        self._serial = {j: self._serial_lane(j) for j in range(self.block_lanes, B)}
        K = problem.extra_vectors
        require(not (K and serial_lanes), "serial_lanes", serial_lanes, "0 with several deviation vectors per orbit")
        self.xq = np.zeros((K, N, B)) if xq is None else np.ascontiguousarray(xq, dtype=float).copy()
        self.xp = np.zeros((K, N, B)) if xp is None else np.ascontiguousarray(xp, dtype=float).copy()
        require(self.xq.shape == self.xp.shape == (K, N, B), "extra deviation vectors", self.xq.shape,
                f"(K, N, B) = {(K, N, B)}")
        self.x_growth = np.zeros((K, B))
        self.vectors_on = np.ones(B, dtype=np.bool_)
        self.gap_steps = np.zeros((N + 1, B), dtype=np.int64)
        self.max_gaps = np.zeros(B, dtype=np.int64)
        self.log_growth = np.zeros(B)
        self.bad = np.full(B, -1, dtype=np.int64)
        self.steps = 0

    @property
    def size(self) -> int:
        return self.q.shape[1]

    def advance(self, n_steps: int) -> None:
        """Advance every lane by n_steps; a lane that turned non-finite gets ``bad`` >= 0 (its
        absolute step count), the others are unaffected."""
        if n_steps <= 0:
            return
        bad = np.full(self.size, -1, dtype=np.int64)
        if self.block_lanes:
            self._advance_blocks(int(n_steps), bad)
        for j, lane in self._serial.items():
            bad[j] = self._advance_serial(j, lane, int(n_steps))
        newly = (bad >= 0) & (self.bad < 0)
        self.bad[newly] = self.steps + bad[newly]
        self.steps += int(n_steps)

    def new_interval(self) -> None:
        """Start counting gaps afresh (``gap_steps``, ``max_gaps``), as at every sample."""
        self.gap_steps[:] = 0
        self.max_gaps[:] = 0

    def stop_vectors(self, lanes) -> None:
        """Stop evolving the extra deviation vectors of ``lanes`` (they stay as they are): the work
        is saved in every SIMD block all of whose lanes are stopped. Only GALI's vectors may stop;
        the spectrum's are orthonormalised together."""
        require(self.problem.spectrum == 1, "stop_vectors", self.problem.spectrum,
                "a problem without Lyapunov spectrum vectors")
        self.vectors_on[np.asarray(lanes, dtype=np.int64)] = False

    def _take_parameters(self, problem) -> None:
        """The lanes' parameters the compiled engines read."""
        self.inv_mass, self.bonds = problem.lane_parameters
        self._sites = () if problem.site_parameters is None else (problem.site_parameters,)

    def _serial_lane(self, j: int) -> tuple:
        """What the single-trajectory engine reads of lane j."""
        return self.problem.lane(j)

    def _advance_blocks(self, n_steps: int, bad: np.ndarray) -> None:
        """The first ``block_lanes`` lanes by n_steps on ``advance_batch``, their failures in ``bad``."""
        pr = self.problem
        advance_batch(self.model, self.q, self.p, self.dq, self.dp, self.inv_mass, self.bonds, self.scheme.kicks,
                      self.scheme.drifts, pr.dt, n_steps, pr.tangent, pr.check_every, pr.track_gaps,
                      self.gap_steps, self.log_growth, self.max_gaps, bad, self.block_lanes, self.xq, self.xp,
                      pr.spectrum - 1, self.x_growth, self.vectors_on, *self._sites)

    def _advance_serial(self, j: int, lane: tuple, n_steps: int) -> int:
        """Lane j on the single-trajectory engine; returns its ``bad`` of this call."""
        pr = self.problem
        N = self.q.shape[0]
        q, p, dq, dp = (np.ascontiguousarray(a[:, j]) for a in (self.q, self.p, self.dq, self.dp))
        diagnostics = np.array([self.log_growth[j], float(self.max_gaps[j])])
        gaps = np.ascontiguousarray(self.gap_steps[:, j])
        bad = advance(self.model, q, p, dq, dp, *lane, self.scheme.kicks, self.scheme.drifts, pr.dt, n_steps,
                      pr.tangent, pr.check_every, pr.track_gaps, gaps, diagnostics, np.empty(N + 1), np.empty(N + 1),
                      pr.lane_sites(j))  # None as checked.run_chunks passes it: one compiled variant, not two
        self.q[:, j], self.p[:, j], self.dq[:, j], self.dp[:, j] = q, p, dq, dp
        self.gap_steps[:, j] = gaps
        self.log_growth[j], self.max_gaps[j] = diagnostics[0], int(diagnostics[1])
        return bad
