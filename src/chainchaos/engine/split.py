"""The engines of split models (``models.split``): the three-part schemes with their tangent map.

One step is the stages of a scheme (``split_schemes.SPLIT_SCHEMES``), each the exact flow of one
part for a time c dt, applied to the state and to every deviation vector with the part's exact
derivative (the tangent map method, Skokos & Gerlach, PRE 82, 036704 (2010)):

- A(t): every site turns by theta = w t, w from the model's ``frequency(S, x)`` at
  x = q^2 + p^2 (which A keeps); (s, c) = sincos(theta) from ``kernels.exactmath`` (the same bits on
  every CPU), q' = c q + s p, p' = c p - s q; a deviation (dq, dp) turns with it and shears by
  d theta = t g (q dq + p dp): dq' = (c dq + s dp) + d theta p', dp' = (c dp - s dq) - d theta q';
- B(t): p_l += t (sum of q over l's neighbours), and dp_l likewise with dq;
- C(t): q_l -= t (sum of p over l's neighbours), and dq_l likewise with dp (written as
  q_l + (-t)(...), the same bits),

with q = p = 0 beyond the edges. The lattice is a chain or a square lattice (``system.geometry``),
passed as ``shape2`` = (Nx, Ny): on a chain (Ny = 1) the neighbours of l are l - 1 and l + 1,
summed as (q_{l-1} + q_{l+1}); on a square lattice the pair across the lines, (q_{l-Nx} +
q_{l+Nx}), is added to that sum, so a lattice of width 1 gives the chain's numbers to the bit. Every ``check_every`` steps and at the end of a call the state is
checked for finiteness and the deviation vector renormalised, ln of its norm added to the growth
(``integrators._renormalise``), as the bond engines do.

Two engines, the same numbers lane by lane: :func:`advance_split`, one trajectory, and
:func:`advance_split_batch`, trajectories in blocks of ``LANES`` (one per SIMD lane, the last
block padded by repeating its last trajectory), with K more deviation vectors per trajectory
(the Lyapunov spectrum's, orthonormalised, then GALI's, normalised, at every check, as
``batch.advance_batch`` does). :class:`SplitBatch` is what ``Problem.engine`` returns for a split
model, read by the driver as ``batch.Batch``.
"""

import numpy as np
from numba import njit

from chainchaos.engine.batch import Batch
from chainchaos.engine.integrators import _aligned_zeros, _check, _renormalise
from chainchaos.kernels.exactmath import gram_schmidt, sincos
from chainchaos.kernels.simd import LANES, vload, vstore
from chainchaos.system.models.base import parameter_counts, site_values, site_vectors
from chainchaos.system.models.split import onsite_frequency

#: Which stage is which part (``split_schemes.PARTS``).
A, B, C = 0, 1, 2


# ---- one trajectory ----------------------------------------------------------------------------


@njit(cache=True, error_model="numpy")
def _rotate(model, tangent, q, p, dq, dp, sites, t):
    """A(t) of every site, and of the deviation vector with ``tangent``."""
    for n in range(q.shape[0]):
        qn, pn = q[n], p[n]
        w, g = onsite_frequency(model, site_values(model, sites, n), qn * qn + pn * pn)
        s, c = sincos(w * t)
        q1 = c * qn + s * pn
        p1 = c * pn - s * qn
        q[n], p[n] = q1, p1
        if tangent:
            dqn, dpn = dq[n], dp[n]
            shear = t * (g * (qn * dqn + pn * dpn))
            dq[n] = (c * dqn + s * dpn) + shear * p1
            dp[n] = (c * dpn - s * dqn) - shear * q1


@njit(cache=True, error_model="numpy")
def _hop(y, x, c, shape2):
    """y_l += c (sum of x over l's neighbours), x = 0 beyond the edges, on the lattice of
    ``shape2`` = (Nx, Ny): B(t) with (y, x, c) = (p, q, t), C(t) with (q, p, -t)."""
    nx, ny = shape2
    if ny == 1:
        left = 0.0
        for n in range(nx):
            right = x[n + 1] if n + 1 < nx else 0.0
            here = x[n]
            y[n] = y[n] + c * (left + right)
            left = here
        return
    zero = np.zeros(nx)  # the line beyond an edge
    for j in range(ny):
        first = j * nx
        line, out = x[first:first + nx], y[first:first + nx]
        below = x[first - nx:first] if j > 0 else zero
        above = x[first + nx:first + 2 * nx] if j + 1 < ny else zero
        last = nx - 1  # the line's ends: a zero beyond them
        out[0] = out[0] + c * ((0.0 + (line[1] if nx > 1 else 0.0)) + (below[0] + above[0]))
        if last > 0:
            out[last] = out[last] + c * ((line[last - 1] + 0.0) + (below[last] + above[last]))
        for i in range(1, last):
            out[i] = out[i] + c * ((line[i - 1] + line[i + 1]) + (below[i] + above[i]))


@njit(cache=True, error_model="numpy")
def advance_split(model, q, p, dq, dp, sites, shape2, parts, coefficients, dt, n_steps, tangent, check_every,
                  diagnostics):
    """Advance one trajectory (q, p) of a split ``model`` and, with ``tangent``, its deviation
    vector (dq, dp), each (N,), by n_steps steps of the scheme (parts, coefficients).

    sites (parameters, N): the model's site parameters (``SplitModel.site_parameters``);
    shape2 (Nx, Ny): the lattice (``Geometry.shape2``), N = Nx Ny.
    Every ``check_every`` steps and at the end the state is checked for finiteness and the
    deviation vector renormalised, ln of its norm added to diagnostics[0]. Returns -1, or the
    number of steps done when a non-finite state stopped the run.
    """
    bad = -1
    for step in range(n_steps):
        for i in range(parts.shape[0]):
            t = coefficients[i] * dt
            if parts[i] == A:
                _rotate(model, tangent, q, p, dq, dp, sites, t)
            elif parts[i] == B:
                _hop(p, q, t, shape2)
                if tangent:
                    _hop(dp, dq, t, shape2)
            else:
                _hop(q, p, -t, shape2)
                if tangent:
                    _hop(dq, dp, -t, shape2)
        if ((step + 1) % check_every == 0 or step + 1 == n_steps) and not _check(q, p, dq, dp, tangent,
                                                                                 diagnostics):
            bad = step + 1
            break
    return bad


# ---- blocks of LANES trajectories ------------------------------------------------------------

#: A block's buffer, row r = site r - pad (``_pad``: rows before the first site and after the last,
#: zero, where the neighbours beyond the edges are read): the LANES lanes of q and p, dq and dp of
#: each deviation vector in turn, then the site's parameters (as many as the model has).
_Q, _P, _V = 0, LANES, 2 * LANES


@njit(cache=True)
def _pad(shape2):
    """Zero rows before and after the sites: one on a chain, a line on a square lattice."""
    return shape2[0] if shape2[1] > 1 else 1


@njit(cache=True)
def _row(model, vectors):
    """Doubles per row of a block with ``vectors`` deviation vectors."""
    _, n_site = parameter_counts(model)
    return (2 + 2 * vectors + n_site) * LANES


@njit(cache=True)
def _sites(model, row):
    """Where a row's site parameters start: its last n_site vectors."""
    _, n_site = parameter_counts(model)
    return row - n_site * LANES


@njit(cache=True, error_model="numpy")
def _rotate_block(model, N, pad, Z, row, vectors, t):
    """A(t) of every site of a block and of its first ``vectors`` deviation vectors."""
    for r in range(pad, N + pad):
        base = r * row
        q, p = vload(Z, base + _Q), vload(Z, base + _P)
        w, g = onsite_frequency(model, site_vectors(model, Z, base + _sites(model, row), LANES), q * q + p * p)
        s, c = sincos(w * t)
        q1 = c * q + s * p
        p1 = c * p - s * q
        vstore(Z, base + _Q, q1)
        vstore(Z, base + _P, p1)
        for k in range(vectors):
            at = base + _V + 2 * k * LANES
            dq, dp = vload(Z, at), vload(Z, at + LANES)
            shear = t * (g * (q * dq + p * dp))
            vstore(Z, at, (c * dq + s * dp) + shear * p1)
            vstore(Z, at + LANES, (c * dp - s * dq) - shear * q1)


@njit(cache=True, error_model="numpy")
def _hop_block(shape2, pad, Z, row, y, x, c):
    """y_l += c (sum of x over l's neighbours) on every site of a block: y and x the offsets of
    two of a row's quantities (the pad rows hold zero; row 0 stands for a neighbour beyond the
    end of a line)."""
    nx, ny = shape2
    if ny == 1:  # a chain: the pad rows are its ends, no branch in the loop
        for r in range(pad, nx + pad):
            base = r * row
            vstore(Z, base + y, vload(Z, base + y) + c * (vload(Z, base - row + x) + vload(Z, base + row + x)))
        return
    for j in range(ny):
        for i in range(nx):
            base = (j * nx + i + pad) * row
            left = vload(Z, base - row + x) if i > 0 else vload(Z, x)
            right = vload(Z, base + row + x) if i + 1 < nx else vload(Z, x)
            around = left + right
            if ny > 1:
                around = around + (vload(Z, base - nx * row + x) + vload(Z, base + nx * row + x))
            vstore(Z, base + y, vload(Z, base + y) + c * around)


@njit(cache=True, error_model="numpy")
def _normalise_block_vectors(N, pad, Z, row, lane, extra, orthogonal, growth, W, lane_growth):
    """Lane ``lane``'s extra deviation vectors at a check, gathered with its first (already
    normalised) into W (extra + 1, 2N), the first ``orthogonal`` orthonormalised against it and
    each other and the rest normalised (``exactmath.gram_schmidt``), ln of their norms added to
    growth[:, lane]."""
    for k in range(extra + 1):
        at = _V + 2 * k * LANES + lane
        for n in range(N):
            W[k, n] = Z[(n + pad) * row + at]
            W[k, N + n] = Z[(n + pad) * row + at + LANES]
    lane_growth[:] = 0.0
    gram_schmidt(W, 1, orthogonal + 1, lane_growth)
    for k in range(1, extra + 1):
        growth[k - 1, lane] += lane_growth[k - 1]
        at = _V + 2 * k * LANES + lane
        for n in range(N):
            Z[(n + pad) * row + at] = W[k, n]
            Z[(n + pad) * row + at + LANES] = W[k, N + n]


@njit(cache=True, error_model="numpy")
def _advance_block(model, shape2, Z, row, vectors, parts, coefficients, dt, n_steps, check_every, log_growth, bad,
                   extra, orthogonal, x_growth):
    """``advance_split_batch`` for one block in its buffer Z: ``vectors`` deviation vectors (0
    without the tangent map; the first is each lane's mLCE vector, ``extra`` more follow it)."""
    N, pad = shape2[0] * shape2[1], _pad(shape2)
    W = np.empty((extra + 1, 2 * N))
    lane_growth = np.empty(max(extra, 1))
    for step in range(n_steps):
        for i in range(parts.shape[0]):
            t = coefficients[i] * dt
            if parts[i] == A:
                _rotate_block(model, N, pad, Z, row, vectors, t)
            elif parts[i] == B:
                _hop_block(shape2, pad, Z, row, _P, _Q, t)
                for k in range(vectors):
                    _hop_block(shape2, pad, Z, row, _V + (2 * k + 1) * LANES, _V + 2 * k * LANES, t)
            else:
                _hop_block(shape2, pad, Z, row, _Q, _P, -t)
                for k in range(vectors):
                    _hop_block(shape2, pad, Z, row, _V + 2 * k * LANES, _V + (2 * k + 1) * LANES, -t)
        if (step + 1) % check_every == 0 or step + 1 == n_steps:
            for j in range(LANES):
                s = 0.0
                for n in range(N):
                    s += Z[(n + pad) * row + _Q + j] + Z[(n + pad) * row + _P + j]
                if vectors:
                    log_growth[j] += _renormalise(Z[pad * row + _V + j:(N + pad) * row + _V + j:row],
                                                  Z[pad * row + _V + LANES + j:(N + pad) * row + _V + LANES + j:row])
                    s += Z[pad * row + _V + j]
                    if extra:
                        _normalise_block_vectors(N, pad, Z, row, j, extra, orthogonal, x_growth, W, lane_growth)
                if bad[j] < 0 and not np.isfinite(s):
                    bad[j] = step + 1


@njit(cache=True, error_model="numpy")
def advance_split_batch(model, q, p, dq, dp, sites, shape2, parts, coefficients, dt, n_steps, tangent, check_every,
                        log_growth, bad, lanes, xq, xp, orthogonal, x_growth, vectors_on):
    """Advance the first ``lanes`` of the B trajectories (q, p) of a split ``model``, shape (N, B),
    and, with ``tangent``, their deviation vectors (dq, dp) and the K more (xq, xp) (K, N, B), by
    n_steps steps of the scheme (parts, coefficients), in blocks of LANES.

    sites (parameters, N, B): the model's site parameters of every trajectory; shape2
    (Nx, Ny): their lattice (``Geometry.shape2``). Every
    ``check_every`` steps and at the end: each lane's state checked for finiteness (``bad[j]``
    set to the step count of the first failed check if it is still < 0) and, with ``tangent``,
    its deviation vector renormalised, ln|v| added to ``log_growth[j]``; the first ``orthogonal``
    of its K vectors orthonormalised against it and each other, the rest normalised, ln of their
    norms added to ``x_growth[k, j]``. A block whose lanes all have ``vectors_on[j]`` False leaves
    its K vectors as they are. All arrays are updated in place; per lane the numbers are those of
    :func:`advance_split`, to the bit.
    """
    N = q.shape[0]
    extra = xq.shape[0] if tangent else 0
    vectors_max = 1 + extra if tangent else 0
    row = _row(model, vectors_max)
    pad = _pad(shape2)
    Z = _aligned_zeros((N + 2 * pad) * row)
    block_growth = np.zeros(LANES)
    block_bad = np.zeros(LANES, dtype=np.int64)
    block_x_growth = np.zeros((max(extra, 1), LANES))
    for first in range(0, lanes, LANES):
        Z[:] = 0.0
        for lane in range(LANES):
            j = min(first + lane, lanes - 1)  # padding lanes repeat the last trajectory
            for n in range(N):
                base = (n + pad) * row
                Z[base + _Q + lane] = q[n, j]
                Z[base + _P + lane] = p[n, j]
                for r in range(sites.shape[0]):
                    Z[base + _sites(model, row) + r * LANES + lane] = sites[r, n, j]
                if tangent:
                    Z[base + _V + lane] = dq[n, j]
                    Z[base + _V + LANES + lane] = dp[n, j]
                for k in range(extra):
                    Z[base + _V + 2 * (k + 1) * LANES + lane] = xq[k, n, j]
                    Z[base + _V + (2 * k + 3) * LANES + lane] = xp[k, n, j]
            block_growth[lane] = log_growth[j]
            block_bad[lane] = bad[j]
            for k in range(extra):
                block_x_growth[k, lane] = x_growth[k, j]
        block_extra = extra if np.any(vectors_on[first:min(first + LANES, lanes)]) else 0
        vectors = 1 + block_extra if tangent else 0
        _advance_block(model, shape2, Z, row, vectors, parts, coefficients, dt, n_steps, check_every, block_growth,
                       block_bad, block_extra, orthogonal, block_x_growth)
        for lane in range(min(LANES, lanes - first)):
            j = first + lane
            for n in range(N):
                base = (n + pad) * row
                q[n, j] = Z[base + _Q + lane]
                p[n, j] = Z[base + _P + lane]
                if tangent:
                    dq[n, j] = Z[base + _V + lane]
                    dp[n, j] = Z[base + _V + LANES + lane]
                for k in range(extra):
                    xq[k, n, j] = Z[base + _V + 2 * (k + 1) * LANES + lane]
                    xp[k, n, j] = Z[base + _V + (2 * k + 3) * LANES + lane]
            log_growth[j] = block_growth[lane]
            bad[j] = block_bad[lane]
            for k in range(extra):
                x_growth[k, j] = block_x_growth[k, lane]


class SplitBatch(Batch):
    """The lanes of a split model's :class:`~chainchaos.engine.problem.Problem` advanced together:
    the first lanes in SIMD blocks by :func:`advance_split_batch`, the last ``serial_lanes`` by
    :func:`advance_split`, the same numbers either way; read as ``batch.Batch`` is (no bond
    opens: ``gap_steps`` and ``max_gaps`` stay zero).
    """

    def _take_parameters(self, problem) -> None:
        self._sites = problem.site_parameters
        self._shape2 = problem.geometry.shape2  # the moving sites' (a window's, when restricted)
        self._stages = (self.scheme.parts, self.scheme.coefficients)

    def _serial_lane(self, j: int) -> tuple:
        return (self.problem.lane_sites(j),)

    def _advance_blocks(self, n_steps: int, bad: np.ndarray) -> None:
        pr = self.problem
        advance_split_batch(self.model, self.q, self.p, self.dq, self.dp, self._sites, self._shape2, *self._stages,
                            pr.dt, n_steps, pr.tangent, pr.check_every, self.log_growth, bad, self.block_lanes,
                            self.xq, self.xp, pr.spectrum - 1, self.x_growth, self.vectors_on)

    def _advance_serial(self, j: int, lane: tuple, n_steps: int) -> int:
        pr = self.problem
        q, p, dq, dp = (np.ascontiguousarray(a[:, j]) for a in (self.q, self.p, self.dq, self.dp))
        diagnostics = np.array([self.log_growth[j], 0.0])
        bad = advance_split(self.model, q, p, dq, dp, lane[0], self._shape2, *self._stages, pr.dt, n_steps,
                            pr.tangent, pr.check_every, diagnostics)
        self.q[:, j], self.p[:, j], self.dq[:, j], self.dp[:, j] = q, p, dq, dp
        self.log_growth[j] = diagnostics[0]
        return bad


__all__ = ["SplitBatch", "advance_split", "advance_split_batch"]
