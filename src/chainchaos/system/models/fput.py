"""The FPUT chain: the Hertz force expanded to fourth order in the potential.

With the stretch y = -D = u_b - u_{b-1}:

    V(y) = K2 y^2/2 + K3 y^3/3 + K4 y^4/4,
    f = K2 D - K3 D^2 + K4 D^3,  k = df/dD = K2 - 2 K3 D + 3 K4 D^2,

K2, K3 and K4 from the chain (``chainchaos.system.chain``: K4 with the paper's sign or the Taylor sign).
The polynomial bonds never open (docs/conventions.md).
"""

from numba import njit

from chainchaos.system.models.base import Model
from chainchaos.system.appearance import APPEARANCE


@njit(cache=True)
def fput_force(K2, K3, K4, D):
    """FPUT bond force K2 D - K3 D^2 + K4 D^3 at compression D."""
    return D * (K2 - D * (K3 - D * K4))


@njit(cache=True)
def fput_stiffness(K2, K3, K4, D):
    """FPUT bond stiffness df/dD = K2 - 2 K3 D + 3 K4 D^2."""
    return K2 - D * (2.0 * K3 - 3.0 * K4 * D)


@njit(cache=True)
def force(P, left, right):
    """P = (K2, K3, K4)."""
    return fput_force(P[0], P[1], P[2], left - right)


@njit(cache=True)
def force_stiffness(P, left, right):
    D = left - right
    return fput_force(P[0], P[1], P[2], D), fput_stiffness(P[0], P[1], P[2], D)


@njit(cache=True)
def potential(P, left, right):
    y = -(left - right)
    return y * y * (0.5 * P[0] + y * (P[1] / 3.0 + 0.25 * P[2] * y))


def parameters(chain):
    return chain.K2, chain.K3, chain.K4


MODEL = Model(
    name="fput",
    label=APPEARANCE["fput"].label,
    colour=APPEARANCE["fput"].colour,
    parameter_names=("K2", "K3", "K4"),
    parameters=parameters,
    force=force,
    force_stiffness=force_stiffness,
    potential=potential,
    description="f = K2 D - K3 D^2 + K4 D^3",
)
