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
block (``chainchaos.kernels.simd``), each lane's doubles side by side, sweeping the lattice line
after line so that each bond's force is computed once and no site is gathered by index, in the
order of the loop's sums, so that every lane gets the single loop's numbers to the bit. :class:`LatticeBatch` runs a
problem's lanes in blocks, and those beyond the last whole block on the single loop, as the
chain's ``batch.Batch`` does.
"""

import numpy as np
from numba import njit

from chainchaos.engine.batch import Batch
from chainchaos.engine.integrators import _check
from chainchaos.errors import require
from chainchaos.kernels.simd import LANES, vload, vstore
from chainchaos.system.models.base import (
    bond_force,
    bond_force_stiffness,
    bond_values,
    bond_vectors,
    site_kick,
    site_kick_deviation,
    site_values,
    site_vectors,
)


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
        parameters = bond_values(model, bonds, b)
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
        site = site_values(model, sites, n)
        p[n] = p[n] + c * site_kick(model, site, q[n], F[n])
        if tangent:
            dp[n] = dp[n] + c * site_kick_deviation(model, site, q[n], dq[n], G[n])


@njit(cache=True, error_model="numpy")
def advance_lattice(model, q, p, dq, dp, inv_mass, bonds, ends, sites, kicks, drifts, dt, n_steps, tangent,
                    check_every, diagnostics):
    """Advance one trajectory (q, p) of a bond ``model`` with a site law on the lattice of bonds
    ``ends`` (B, 2) and, with ``tangent``, its deviation vector (dq, dp), each (N,), by n_steps
    steps of the scheme (kicks, drifts).

    inv_mass (N,); bonds (parameters, B), the model's parameters of each bond
    (``Model.bond_parameters``); sites (parameters, N). Every ``check_every`` steps and
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
def _bond(model, PX, at, stride, tangent, u_a, u_c, dq_a, dq_c):
    """f and, with ``tangent``, g = k (dq_a - dq_c) of the bond whose parameters start at ``at``
    of PX (rows ``stride`` apart); without, the second value is u_a, summed into a tangent force
    that no kick reads (one type for both cases)."""
    parameters = bond_vectors(model, PX, at, stride)
    if tangent:
        f, k = bond_force_stiffness(model, parameters, u_a, u_c)
        return f, k * (dq_a - dq_c)
    return bond_force(model, parameters, u_a, u_c), u_a


@njit(cache=True, error_model="numpy")
def _square_kick(model, U, P, DQ, DP, S, PX, PY, nx, ny, fixed_x, fixed_y, tangent, c, FY, GY, zero):
    """kick(c) of a block on the square lattice, line after line: each site's force the sum, in
    the order of ``Geometry.bonds`` (its left bond, its right bond, the bond below, the bond
    above), of its bonds' forces, each bond's computed once (a line's bonds carried along it, the
    bonds above a line kept for the next, FY and GY), so each lane gets :func:`_forces` and
    :func:`_kick`'s numbers to the bit."""
    N = nx * ny
    sx, sy = ny * (nx + 1) * LANES, (ny + 1) * nx * LANES  # the parameter rows' strides
    z = vload(zero, 0)
    if fixed_y:  # the bonds below the first line: to the wall
        for i in range(nx):
            at = i * LANES
            f, g = _bond(model, PY, at, sy, tangent, z, vload(U, at), z, vload(DQ, at))
            vstore(FY, at, f)
            vstore(GY, at, g)
    for j in range(ny):
        row = j * nx * LANES
        f_left, g_left = z, z
        if fixed_x:  # the wall's bond to the line's first site
            f_left, g_left = _bond(model, PX, j * (nx + 1) * LANES, sx, tangent, z, vload(U, row), z, vload(DQ, row))
        for i in range(nx):
            at = row + i * LANES
            u, dq = vload(U, at), vload(DQ, at)
            F, G = z, z
            if fixed_x or i > 0:
                F, G = F + f_left, G + g_left
            if fixed_x or i < nx - 1:
                u_r, dq_r = (vload(U, at + LANES), vload(DQ, at + LANES)) if i < nx - 1 else (z, z)
                f_left, g_left = _bond(model, PX, (j * (nx + 1) + i + 1) * LANES, sx, tangent, u, u_r, dq, dq_r)
                F, G = F - f_left, G - g_left
            if fixed_y or j > 0:
                F, G = F + vload(FY, i * LANES), G + vload(GY, i * LANES)
            if fixed_y or j < ny - 1:
                u_up, dq_up = (vload(U, at + nx * LANES), vload(DQ, at + nx * LANES)) if j < ny - 1 else (z, z)
                f, g = _bond(model, PY, ((j + 1) * nx + i) * LANES, sy, tangent, u, u_up, dq, dq_up)
                F, G = F - f, G - g
                vstore(FY, i * LANES, f)
                vstore(GY, i * LANES, g)
            site = site_vectors(model, S, at, N * LANES)
            vstore(P, at, vload(P, at) + c * site_kick(model, site, u, F))
            if tangent:
                vstore(DP, at, vload(DP, at) + c * site_kick_deviation(model, site, u, dq, G))


@njit(cache=True, error_model="numpy")
def advance_lattice_block(model, U, P, DQ, DP, IM, PX, PY, S, nx, ny, fixed_x, fixed_y, kicks, drifts, dt, n_steps,
                          tangent):
    """Advance the LANES trajectories of a block on the nx x ny lattice by n_steps steps of the
    scheme (no check).

    U, P, DQ, DP, IM (N LANES,): site n's lanes at n LANES; PX (R ny (nx + 1) LANES,), R the
    model's parameters per bond,: row r of the bond left of site (i, j) at ((r ny + j) (nx + 1) + i) LANES (i = nx: right
    of the last site); PY (R (ny + 1) nx LANES,): row r of the bond below (i, j)
    at ((r (ny + 1) + j) nx + i) LANES; S (R_site N LANES,), row r of site n at
    (r N + n) LANES. A bond that the boundary does not have is never read.
    """
    N = nx * ny
    FY, GY, zero = np.zeros(nx * LANES), np.zeros(nx * LANES), np.zeros(LANES)
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
                _square_kick(model, U, P, DQ, DP, S, PX, PY, nx, ny, fixed_x, fixed_y, tangent, c, FY, GY, zero)


def line_bonds(geometry, bonds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The bond parameters (R, n_bonds, ...) of ``geometry.bonds()``'s order on the lines: (R, ny,
    nx + 1, ...) the bond left of each site (i = nx: right of a line's last) and (R, ny + 1, nx, ...)
    the bond below each site (j = ny: above the last line), zeros where the boundary has none."""
    nx, ny = geometry.shape2
    fixed_x, fixed_y = geometry.fixed
    px = np.zeros((bonds.shape[0], ny, nx + 1, *bonds.shape[2:]))
    py = np.zeros((bonds.shape[0], ny + 1, nx, *bonds.shape[2:]))
    per_line = nx + 1 if fixed_x else nx - 1
    per_column = ny + 1 if fixed_y else ny - 1
    first_x, first_y = (0 if fixed_x else 1), (0 if fixed_y else 1)
    for j in range(ny):
        px[:, j, first_x:first_x + per_line] = bonds[:, j * per_line:(j + 1) * per_line]
    base = ny * per_line
    for i in range(nx):
        py[:, first_y:first_y + per_column, i] = bonds[:, base + i * per_column:base + (i + 1) * per_column]
    return px, py


class LatticeBatch(Batch):
    """The lanes of a bond model's :class:`~chainchaos.engine.problem.Problem` on a square lattice:
    blocks of LANES lanes on :func:`advance_lattice_block`, the last ``serial_lanes`` on
    :func:`advance_lattice`, the same numbers either way (but for a lane that turned non-finite:
    the loop stops it, a block carries it on; ``bad`` is the same); read as ``batch.Batch`` is (no bond opens:
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
        (nx, ny), (fixed_x, fixed_y) = pr.geometry.shape2, pr.geometry.fixed
        sites = pr.site_parameters
        for first in range(0, self.block_lanes, LANES):
            lanes = np.minimum(np.arange(first, first + LANES), self.block_lanes - 1)  # padding repeats the last
            U, P, DQ, DP, IM = (np.ascontiguousarray(a[:, lanes]).ravel()
                                for a in (self.q, self.p, self.dq, self.dp, self.inv_mass))
            PX, PY = (np.ascontiguousarray(a).ravel() for a in line_bonds(pr.geometry, self.bonds[:, :, lanes]))
            S = np.ascontiguousarray(sites[:, :, lanes]).ravel()
            done, block_bad = 0, np.full(LANES, -1, dtype=np.int64)
            while done < n_steps:
                steps = min(pr.check_every - (done % pr.check_every), n_steps - done)
                advance_lattice_block(self.model, U, P, DQ, DP, IM, PX, PY, S, nx, ny, fixed_x, fixed_y,
                                      self.scheme.kicks, self.scheme.drifts, pr.dt, steps, pr.tangent)
                done += steps
                for lane in range(min(LANES, self.block_lanes - first)):
                    if block_bad[lane] >= 0:
                        continue
                    j = first + lane
                    q, p, dq, dp = (a[lane::LANES].copy() for a in (U, P, DQ, DP))
                    diagnostics = np.array([self.log_growth[j], 0.0])
                    if not _check(q, p, dq, dp, pr.tangent, diagnostics):
                        block_bad[lane] = done
                    self.log_growth[j] = diagnostics[0]
                    DQ[lane::LANES], DP[lane::LANES] = dq, dp  # renormalised
            for lane in range(min(LANES, self.block_lanes - first)):
                j = first + lane
                self.q[:, j], self.p[:, j], self.dq[:, j], self.dp[:, j] = (a[lane::LANES] for a in (U, P, DQ, DP))
                bad[j] = block_bad[lane]


__all__ = ["LatticeBatch", "advance_lattice", "advance_lattice_block"]
