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

A plain loop over the bonds and the sites, one trajectory at a time: :class:`LatticeBatch` runs
a problem's lanes one after the other on it (the chain's engines, ``integrators`` and ``batch``,
are the fast ones; a square lattice's SIMD engine is still to come).
"""

import numpy as np
from numba import njit

from chainchaos.engine.batch import Batch
from chainchaos.engine.integrators import _check
from chainchaos.errors import require
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


class LatticeBatch(Batch):
    """The lanes of a bond model's :class:`~chainchaos.engine.problem.Problem` on a square lattice,
    each advanced by :func:`advance_lattice` in turn (every kind of engine gives these numbers); read
    as ``batch.Batch`` is (no bond opens: ``gap_steps`` and ``max_gaps`` stay zero)."""

    def __init__(self, problem, q, p, dq=None, dp=None, serial_lanes: int = 0, xq=None, xp=None):
        require(problem.extra_vectors == 0, "deviation vectors", problem.extra_vectors + 1,
                "the mLCE vector alone on a square lattice (no spectrum or GALI vectors yet)")
        require(problem.model.has_site_law and not problem.track_gaps, "model", problem.model.name,
                "a model with a site law and no gap counting on a square lattice (the Klein-Gordon models)")
        super().__init__(problem, q, p, dq, dp, problem.lanes, xq, xp)

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


__all__ = ["LatticeBatch", "advance_lattice"]
