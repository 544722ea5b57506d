"""The disordered Klein-Gordon (KG) lattice: harmonic coupling and an anharmonic on-site potential.

    H = sum_l [ p_l^2/2 + eps_l u_l^2/2 + u_l^4/4 ] + sum_b (u_b - u_{b-1})^2 / (2W)

(Flach, Krimer & Skokos, PRL 102, 024101 (2009)), fixed ends u_0 = u_{N+1} = 0: masses 1, every
bond the harmonic bond law with K2 = 1/W (``harmonic``), and on every site the site law
w(u) = eps_l u^2/2 + u^4/4, w'(u) = u (eps_l + u^2), w''(u) = eps_l + 3 u^2, with eps_l uniform
in [1/2, 3/2] (``chain.kg_chain``). ``kg_linear`` drops the quartic term (w = eps_l u^2/2): the
linear KG chain, regular, whose squared frequencies are the eigenvalues of the tridiagonal matrix
with diagonal eps_l + 2/W and off-diagonal -1/W.

Units: the Hamiltonian's own (mass 1, the coefficients above; time in the unit in which the
linear frequencies are those square roots), not the bead chains' 1/omega_max of the homogeneous
chain (docs/conventions.md#klein-gordon). The energy of an excitation is the total H.
"""

from numba import njit

from chainchaos.system.models import harmonic
from chainchaos.system.models.base import Model, SiteLaw
from chainchaos.system.appearance import APPEARANCE


@njit(cache=True)
def quartic_force(S, u):
    """w'(u) = u (eps + u^2), S = (eps,)."""
    return u * (S[0] + u * u)


@njit(cache=True)
def quartic_force_stiffness(S, u):
    """(w', w'') = (u (eps + u^2), eps + 3 u^2)."""
    uu = u * u
    return u * (S[0] + uu), S[0] + 3.0 * uu


@njit(cache=True)
def quartic_potential(S, u):
    """w(u) = eps u^2/2 + u^4/4."""
    uu = u * u
    return uu * (0.5 * S[0] + 0.25 * uu)


@njit(cache=True)
def linear_force(S, u):
    """w'(u) = eps u, S = (eps,)."""
    return S[0] * u


@njit(cache=True)
def linear_force_stiffness(S, u):
    return S[0] * u, S[0]


@njit(cache=True)
def linear_potential(S, u):
    """w(u) = eps u^2/2."""
    return u * u * (0.5 * S[0])


def bond_parameters(lattice):
    """(K2,) = 1/W on every bond of a KG lattice, in the harmonic bond law's row."""
    return (lattice.K2,)


def site_parameters(lattice):
    """(eps,) of every site of a KG lattice."""
    return (lattice.eps,)


QUARTIC = SiteLaw(
    parameter_names=("eps",), parameters=site_parameters, force=quartic_force,
    force_stiffness=quartic_force_stiffness, potential=quartic_potential, description="w = eps u^2/2 + u^4/4"
)
LINEAR = SiteLaw(
    parameter_names=("eps",), parameters=site_parameters, force=linear_force,
    force_stiffness=linear_force_stiffness, potential=linear_potential, description="w = eps u^2/2"
)

MODEL = Model(
    name="kg", label=APPEARANCE["kg"].label, colour=APPEARANCE["kg"].colour, parameter_names=("K2",),
    parameters=bond_parameters,
    force=harmonic.force, force_stiffness=harmonic.force_stiffness, potential=harmonic.potential,
    description="f = D / W, on-site w = eps u^2/2 + u^4/4", site=QUARTIC, lattice="kg"
)
LINEAR_MODEL = Model(
    name="kg_linear", label=APPEARANCE["kg_linear"].label, colour=APPEARANCE["kg_linear"].colour,
    parameter_names=("K2",),
    parameters=bond_parameters, force=harmonic.force, force_stiffness=harmonic.force_stiffness,
    potential=harmonic.potential, description="f = D / W, on-site w = eps u^2/2", site=LINEAR, lattice="kg"
)
