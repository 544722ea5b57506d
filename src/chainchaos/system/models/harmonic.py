"""The harmonic chain: the common linear limit of every model, f = K2 D, V = K2 D^2 / 2.

Its dynamics is a superposition of the chain's linear modes (``chainchaos.system.linear``): regular,
with Lambda(t) t bounded, the reference case of the chaos tests (docs/conventions.md).
"""

from numba import njit

from chainchaos.system.models.base import Model
from chainchaos.system.appearance import APPEARANCE


@njit(cache=True)
def force(P, left, right):
    """P = (K2,)."""
    return (left - right) * P[0]


@njit(cache=True)
def force_stiffness(P, left, right):
    return (left - right) * P[0], P[0]


@njit(cache=True)
def potential(P, left, right):
    y = -(left - right)
    return y * y * (0.5 * P[0])


def parameters(chain):
    return (chain.K2,)


MODEL = Model(
    name="harmonic", label=APPEARANCE["harmonic"].label, colour=APPEARANCE["harmonic"].colour,
    parameter_names=("K2",), parameters=parameters,
    force=force, force_stiffness=force_stiffness, potential=potential, description="f = K2 D"
)
