"""The disordered discrete nonlinear Schroedinger (DNLS) chain, a model split into exact parts.

    H = sum_l [ eps_l |psi_l|^2 + (beta/2) |psi_l|^4 ] - sum_l (psi_{l+1} psi_l^* + psi_{l+1}^* psi_l)

(Flach, Krimer & Skokos, PRL 102, 024101 (2009)), eps_l uniform in [-W/2, W/2], fixed ends. In
real canonical coordinates psi = (q + i p)/sqrt(2), x = q^2 + p^2 = 2 |psi|^2, the on-site part
is a(x) = eps x/2 + beta x^2/8, which turns every site at w = 2 a'(x) = eps + beta x/2, with
g = 2 dw/dx = beta; the hopping is -sum (q_l q_{l+1} + p_l p_{l+1}) (``models.split``).
``dnls_linear`` drops the quartic term (beta read as 0): the linear chain, whose eigenvalues are
those of the tridiagonal matrix with diagonal eps_l and off-diagonal -1.

Units: the Hamiltonian's own (hopping 1; time in the unit in which the linear frequencies are
those eigenvalues), not the bead chains' (docs/conventions.md#dnls). The amount of an excitation
is its norm S = sum |psi_l|^2 = sum x_l / 2.
"""

from numba import njit

from chainchaos.system.models.split import SplitModel
from chainchaos.system.appearance import APPEARANCE


@njit(cache=True)
def cubic_frequency(S, x):
    """(w, g) = (eps + beta x/2, beta), S = (eps, beta)."""
    return S[0] + 0.5 * S[1] * x, S[1]


@njit(cache=True)
def cubic_energy(S, x):
    """a(x) = eps x/2 + beta x^2/8."""
    return x * (0.5 * S[0] + 0.125 * S[1] * x)


@njit(cache=True)
def linear_frequency(S, x):
    """(w, g) = (eps, 0)."""
    return S[0] + 0.0 * x, 0.0 * x


@njit(cache=True)
def linear_energy(S, x):
    """a(x) = eps x/2."""
    return x * (0.5 * S[0])


def site_parameters(lattice):
    """(eps, beta) of every site of a DNLS lattice."""
    return lattice.eps, lattice.eps * 0.0 + lattice.beta


MODEL = SplitModel(
    name="dnls", label=APPEARANCE["dnls"].label, colour=APPEARANCE["dnls"].colour, parameter_names=("eps", "beta"),
    parameters=site_parameters,
    frequency=cubic_frequency, onsite_energy=cubic_energy,
    description="a(x) = eps x/2 + beta x^2/8, hopping -(q q' + p p')"
)
LINEAR_MODEL = SplitModel(
    name="dnls_linear", label=APPEARANCE["dnls_linear"].label, colour=APPEARANCE["dnls_linear"].colour,
    parameter_names=("eps", "beta"),
    parameters=site_parameters, frequency=linear_frequency, onsite_energy=linear_energy,
    description="a(x) = eps x/2, hopping -(q q' + p p')"
)
