"""The equations of motion as a first-order system y' = F(t, y), for scipy's solve_ivp.

The state vector is y = (u_1..u_N, p_1..p_N) and, with the tangent extension used for Lambda,
y = (u, p, du, dp) of length 4N. Everything is in the nondimensional units of docs/conventions.md#units:
displacement in units of the reference static overlap delta_ref, mass in units of the reference
bead mass, time in units of 1/omega_max of the homogeneous linear chain, momentum and energy in
the derived units. The physics is the package's own Numba force kernel
(:func:`chainchaos.system.models.bond_forces`): this module only arranges it as a right-hand side.
"""

import numpy as np
from numba import njit

from chainchaos.system.models import bond_forces, energy_kernel, get_model
from chainchaos.system.models.base import check_sites, site_kick, site_kick_deviation, site_values


@njit(cache=True)
def rhs_kernel(y, out, model, inv_mass, bonds, tangent, f, k, sites=None):
    """Fill ``out`` with dy/dt at state ``y`` (length 2N, or 4N when ``tangent``).

    u' = p/m, p' = f_n - f_{n+1}; tangent: du' = dp/m, dp' = g_n - g_{n+1} with
    g_b = k_b (du_{b-1} - du_b), k the bond stiffness (the variational equations).
    ``f`` and ``k`` are scratch arrays of length N+1. A model with a site law (parameters
    ``sites``) adds -w'(u_n) to p_n' and -w''(u_n) du_n to dp_n'.
    """
    check_sites(model, sites)
    N = inv_mass.shape[0]
    u = y[:N]
    bond_forces(model, u, bonds, f, k, tangent)
    for n in range(N):
        out[n] = inv_mass[n] * y[N + n]
        out[N + n] = site_kick(model, site_values(model, sites, n), u[n], f[n] - f[n + 1])
    if tangent:
        for n in range(N):
            out[2 * N + n] = inv_mass[n] * y[3 * N + n]
        g_prev = -k[0] * y[2 * N]
        for n in range(N):
            if n + 1 < N:
                g_next = k[n + 1] * (y[2 * N + n] - y[2 * N + n + 1])
            else:
                g_next = k[N] * y[2 * N + N - 1]
            site = site_values(model, sites, n)
            out[3 * N + n] = site_kick_deviation(model, site, u[n], y[2 * N + n], g_prev - g_next)
            g_prev = g_next


class RightHandSide:
    """Callable ``rhs(t, y) -> dy/dt`` of one model on one chain, for scipy.integrate.

    ``model`` is a chainchaos.system.models Model or its name; ``tangent`` adds the variational equations
    (state length 4N). The Numba kernel is compiled once and cached on disk; a call costs one
    force evaluation plus Python's call overhead. ``nfev`` counts the calls.
    """

    def __init__(self, model, chain, tangent: bool = False):
        self.model, self.chain, self.tangent = get_model(model), chain, bool(tangent)
        self.N = chain.N
        self.bonds = self.model.bond_parameters(chain)
        sites = self.model.site_parameters(chain)
        self.site_parameters = sites  # None passed, not omitted: the kernels then compile once for every caller
        self._args = (self.model, 1.0 / chain.mass, self.bonds, self.tangent, np.empty(self.N + 1),
                      np.empty(self.N + 1), self.site_parameters)
        self.size = (4 if tangent else 2) * self.N
        self.nfev = 0

    def __call__(self, t, y):
        out = np.empty(self.size)
        rhs_kernel(np.ascontiguousarray(y, dtype=float), out, *self._args)
        self.nfev += 1
        return out

    def energy(self, y) -> float:
        """Total energy of the state part of ``y``."""
        c, N = self.chain, self.N
        return float(energy_kernel(self.model, np.ascontiguousarray(y[:N]), np.ascontiguousarray(y[N:2 * N]),
                                   c.mass, self.bonds, np.empty(N + 1), self.site_parameters))


def rhs(model, chain, tangent: bool = False) -> RightHandSide:
    """The right-hand side ``rhs(t, y)`` for solve_ivp (see :class:`RightHandSide`)."""
    return RightHandSide(model, chain, tangent)
