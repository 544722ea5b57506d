"""The engine of a bond model on a lattice given by its bonds: the square Klein-Gordon lattice.

A lattice's bonds (``system.geometry.Geometry.bonds``: pairs (a, b) of site numbers, -1 for a wall)
are all this engine reads of its shape. One step is the scheme's table (``integrators.SCHEMES``),

    kick(b_0) drift(a_0) kick(b_1) ... drift(a_{s-1}) kick(b_s),

drift(c): u_n += (c dt / m_n) p_n, and kick(d): p_n += d dt (F_n - w'(u_n)) with F_n the sum over
n's bonds of the bond law's force f(u_a, u_b): +f at b, -f at a, accumulated in the order of the
bonds (a wall's u is zero), so that a chain's bonds give its site the chain engine's
(f_n - f_{n+1}), to the bit. The tangent map applies the same maps to (dq, dp) with the bond
stiffness k: G_n the sum of g = k (dq_a - dq_b) alike, dp_n += d dt (G_n - w''(u_n) dq_n) (Skokos
& Gerlach, PRE 82, 036704 (2010)). Every ``check_every`` steps and at the end the state is checked
for finiteness and the deviation vector renormalised, ln of its norm added to the growth, as the
chain's engines do.

:func:`advance_lattice` is a plain loop over the bonds and the sites, one trajectory at a time;
:func:`advance_lattice_block` makes the same operations on the ``LANES`` trajectories of a SIMD
block (``chainchaos.kernels.simd``), each lane's doubles side by side, a wall one more row of
zeros, so that every lane gets the single loop's numbers to the bit. :class:`LatticeBatch` runs a
problem's lanes in blocks, and those beyond the last whole block on the single loop, as the
chain's ``batch.Batch`` does.
"""

import numpy as np
from numba import njit

from chainchaos.engine.batch import Batch
from chainchaos.engine.integrators import _check
from chainchaos.errors import require
from chainchaos.kernels.simd import LANES, vload, vstore
from chainchaos.system.models.base import bond_force, bond_force_stiffness, site_kick, site_kick_deviation


@njit(cache=True, error_model="numpy")
def _forces(model, u, dq, bonds, ends, tangent, F, G):
    """F (and G with ``tangent``): every site's force from its bonds, and its tangent force."""
    F[:] = 0.0
    if tangent:
        G[:] = 0.0
    for b in range(ends.shape[0]):
        a, c = ends[b, 0], ends[b, 1]
        u_a = u[a] if a >= 0 else 0.0
        u_c = u[c] if c >= 0 else 0.0
        parameters = (bonds[0, b], bonds[1, b], bonds[2, b])
        if tangent:
            f, k = bond_force_stiffness(model, parameters, u_a, u_c)
            g = k * ((dq[a] if a >= 0 else 0.0) - (dq[c] if c >= 0 else 0.0))
            if c >= 0:
                G[c] = G[c] + g
            if a >= 0:
                G[a] = G[a] - g
        else:
            f = bond_force(model, parameters, u_a, u_c)
        if c >= 0:
            F[c] = F[c] + f
        if a >= 0:
            F[a] = F[a] - f


@njit(cache=True, error_model="numpy")
def _kick(model, tangent, q, p, dq, dp, sites, F, G, c):
    for n in range(q.shape[0]):
        site = (sites[0, n], sites[1, n])
        p[n] = p[n] + c * site_kick(model, site, q[n], F[n])
        if tangent:
            dp[n] = dp[n] + c * site_kick_deviation(model, site, q[n], dq[n], G[n])


@njit(cache=True, error_model="numpy")
def advance_lattice(model, q, p, dq, dp, inv_mass, bonds, ends, sites, kicks, drifts, dt, n_steps, tangent,
                    check_every, diagnostics):
    """Advance one trajectory (q, p) of a bond ``model`` with a site law on the lattice of bonds
    ``ends`` (B, 2) and, with ``tangent``, its deviation vector (dq, dp), each (N,), by n_steps
    steps of the scheme (kicks, drifts).

    inv_mass (N,); bonds (MAX_BOND_PARAMETERS, B), the model's parameters of each bond
    (``Model.bond_parameters``); sites (MAX_SITE_PARAMETERS, N). Every ``check_every`` steps and
    at the end the state is checked for finiteness and the deviation vector renormalised, ln of
    its norm added to diagnostics[0]. Returns -1, or the number of steps done when a non-finite
    state stopped the run.
    """
    N = q.shape[0]
    F, G = np.empty(N), np.empty(N)
    bad = -1
    for step in range(n_steps):
        for i in range(kicks.shape[0]):
            if i > 0:
                a = drifts[i - 1] * dt
                for n in range(N):
                    im = inv_mass[n]
                    q[n] = q[n] + a * im * p[n]
                    if tangent:
                        dq[n] = dq[n] + a * im * dp[n]
            c = kicks[i] * dt
            if c != 0.0:
                _forces(model, q, dq, bonds, ends, tangent, F, G)
                _kick(model, tangent, q, p, dq, dp, sites, F, G, c)
        if ((step + 1) % check_every == 0 or step + 1 == n_steps) and not _check(q, p, dq, dp, tangent,
                                                                                 diagnostics):
            bad = step + 1
            break
    return bad


@njit(cache=True, error_model="numpy")
def _block_forces(model, U, DQ, BP, ends, nb, tangent, F, G):
    """:func:`_forces` on a block: rows of LANES doubles, row N of U, DQ the walls' zeros (and of
    F, G a sink that is never read)."""
    F[:] = 0.0
    if tangent:
        G[:] = 0.0
    for b in range(nb):
        a, c = ends[b, 0] * LANES, ends[b, 1] * LANES
        u_a, u_c = vload(U, a), vload(U, c)
        parameters = (vload(BP, b * LANES), vload(BP, (nb + b) * LANES), vload(BP, (2 * nb + b) * LANES))
        if tangent:
            f, k = bond_force_stiffness(model, parameters, u_a, u_c)
            g = k * (vload(DQ, a) - vload(DQ, c))
            vstore(G, c, vload(G, c) + g)
            vstore(G, a, vload(G, a) - g)
        else:
            f = bond_force(model, parameters, u_a, u_c)
        vstore(F, c, vload(F, c) + f)
        vstore(F, a, vload(F, a) - f)


@njit(cache=True, error_model="numpy")
def advance_lattice_block(model, U, P, DQ, DP, IM, BP, S, ends, kicks, drifts, dt, n_steps, tangent, F, G):
    """Advance the LANES trajectories of a block by n_steps steps of the scheme (no check).

    U, DQ ((N + 1) LANES,): displacements and deviations, site n's lanes at n LANES, row N zeros
    (the walls, ``ends`` -1 read as N); P, DP, IM (N LANES,); BP (MAX_BOND_PARAMETERS B LANES,),
    row r of bond b at (r B + b) LANES; S (MAX_SITE_PARAMETERS N LANES,), row r of site n at
    (r N + n) LANES; F, G ((N + 1) LANES,) work rows.
    """
    N = P.shape[0] // LANES
    nb = ends.shape[0]
    for step in range(n_steps):
        for i in range(kicks.shape[0]):
            if i > 0:
                a = drifts[i - 1] * dt
                for n in range(0, N * LANES, LANES):
                    im = vload(IM, n)
                    vstore(U, n, vload(U, n) + a * im * vload(P, n))
                    if tangent:
                        vstore(DQ, n, vload(DQ, n) + a * im * vload(DP, n))
            c = kicks[i] * dt
            if c != 0.0:
                _block_forces(model, U, DQ, BP, ends, nb, tangent, F, G)
                for n in range(N):
                    at = n * LANES
                    site = (vload(S, at), vload(S, (N + n) * LANES))
                    u = vload(U, at)
                    vstore(P, at, vload(P, at) + c * site_kick(model, site, u, vload(F, at)))
                    if tangent:
                        vstore(DP, at, vload(DP, at) + c * site_kick_deviation(model, site, u, vload(DQ, at),
                                                                                vload(G, at)))


class LatticeBatch(Batch):
    """The lanes of a bond model's :class:`~chainchaos.engine.problem.Problem` on a square lattice:
    blocks of LANES lanes on :func:`advance_lattice_block`, the last ``serial_lanes`` on
    :func:`advance_lattice`, the same numbers either way; read as ``batch.Batch`` is (no bond opens:
    ``gap_steps`` and ``max_gaps`` stay zero). A block stops at every ``check_every`` steps and at
    the end of a call for each lane's check (``integrators._check``), as the single loop does."""

    def __init__(self, problem, q, p, dq=None, dp=None, serial_lanes: int = 0, xq=None, xp=None):
        require(problem.extra_vectors == 0, "deviation vectors", problem.extra_vectors + 1,
                "the mLCE vector alone on a square lattice (no spectrum or GALI vectors yet)")
        require(problem.model.has_site_law and not problem.track_gaps, "model", problem.model.name,
                "a model with a site law and no gap counting on a square lattice (the Klein-Gordon models)")
        super().__init__(problem, q, p, dq, dp, serial_lanes, xq, xp)

    def _take_parameters(self, problem) -> None:
        self.inv_mass, self.bonds = problem.lane_parameters
        self._ends = np.ascontiguousarray(problem.geometry.bonds())

    def _serial_lane(self, j: int) -> tuple:
        return (np.ascontiguousarray(self.inv_mass[:, j]), np.ascontiguousarray(self.bonds[:, :, j]),
                self.problem.lane_sites(j))

    def _advance_serial(self, j: int, lane: tuple, n_steps: int) -> int:
        pr = self.problem
        q, p, dq, dp = (np.ascontiguousarray(a[:, j]) for a in (self.q, self.p, self.dq, self.dp))
        diagnostics = np.array([self.log_growth[j], 0.0])
        inv_mass, bonds, sites = lane
        bad = advance_lattice(self.model, q, p, dq, dp, inv_mass, bonds, self._ends, sites, self.scheme.kicks,
                              self.scheme.drifts, pr.dt, n_steps, pr.tangent, pr.check_every, diagnostics)
        self.q[:, j], self.p[:, j], self.dq[:, j], self.dp[:, j] = q, p, dq, dp
        self.log_growth[j] = diagnostics[0]
        return bad

    def _advance_blocks(self, n_steps: int, bad: np.ndarray) -> None:
        pr = self.problem
        N = pr.N
        ends = np.where(self._ends < 0, N, self._ends)  # a wall: the row of zeros after the sites
        sites = pr.site_parameters
        for first in range(0, self.block_lanes, LANES):
            lanes = np.minimum(np.arange(first, first + LANES), self.block_lanes - 1)  # padding repeats the last

            def rows(a, extra=0):  # (N, B) -> the block's rows, ``extra`` rows of zeros after them
                out = np.zeros((a.shape[0] + extra, LANES))
                out[: a.shape[0]] = a[:, lanes]
                return out.ravel()

            U, DQ = rows(self.q, 1), rows(self.dq, 1)
            P, DP, IM = rows(self.p), rows(self.dp), rows(self.inv_mass)
            BP = np.ascontiguousarray(self.bonds[:, :, lanes]).ravel()
            S = np.ascontiguousarray(sites[:, :, lanes]).ravel()
            F, G = np.empty((N + 1) * LANES), np.empty((N + 1) * LANES)
            done, block_bad = 0, np.full(LANES, -1, dtype=np.int64)
            while done < n_steps:
                steps = min(pr.check_every - (done % pr.check_every), n_steps - done)
                advance_lattice_block(self.model, U, P, DQ, DP, IM, BP, S, ends, self.scheme.kicks,
                                      self.scheme.drifts, pr.dt, steps, pr.tangent, F, G)
                done += steps
                for lane in range(min(LANES, self.block_lanes - first)):
                    if block_bad[lane] >= 0:
                        continue
                    j = first + lane
                    q, p = U[lane:N * LANES:LANES].copy(), P[lane::LANES].copy()
                    dq, dp = DQ[lane:N * LANES:LANES].copy(), DP[lane::LANES].copy()
                    diagnostics = np.array([self.log_growth[j], 0.0])
                    if not _check(q, p, dq, dp, pr.tangent, diagnostics):
                        block_bad[lane] = done
                    self.log_growth[j] = diagnostics[0]
                    DQ[lane:N * LANES:LANES], DP[lane::LANES] = dq, dp  # renormalised
            for lane in range(min(LANES, self.block_lanes - first)):
                j = first + lane
                self.q[:, j], self.p[:, j] = U[lane:N * LANES:LANES], P[lane::LANES]
                self.dq[:, j], self.dp[:, j] = DQ[lane:N * LANES:LANES], DP[lane::LANES]
                bad[j] = block_bad[lane]


__all__ = ["LatticeBatch", "advance_lattice", "advance_lattice_block"]
