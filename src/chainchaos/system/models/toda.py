"""The Toda chain matched to the FPUT expansion: the integrable reference of the FPUT chain.

    V(D) = (K2 / beta^2) (e^(beta D) - 1 - beta D),  beta = -2 K3 / K2,
    f = dV/dD = (K2 / beta) (e^(beta D) - 1),  k = df/dD = K2 e^(beta D),

with D = u_{b-1} - u_b the compression and K2, K3 those of the chain (``chainchaos.system.chain``). Its
expansion f = K2 D - K3 D^2 + (2 K3^2 / 3 K2) D^3 + ... has the FPUT chain's K2 and K3, and for
the chain's coefficients 2 K3^2 / (3 K2) = h / 96 is the paper's K4 (K4 sign +1): to fourth order
in the potential, the paper's FPUT chain is this Toda chain. Beta > 0 (K3 < 0): the bond hardens
exponentially in compression and its tension saturates at K2 / beta. A chain of equal beads is
integrable: the walls and N beads are the odd-symmetric half of a periodic Toda lattice of 2(N+1)
particles, whose Flaschka-Lax traces are conserved (tests/system/test_toda.py). Bonds never open.

The kernels use e^x - 1 = expm1(x) (the C library's, lane by lane on vectors), exact near x = 0.
"""

import math

import numpy as np
from numba import njit

from chainchaos.system.models.base import Model
from chainchaos.system.appearance import APPEARANCE


@njit(cache=True)
def force(P, left, right):
    """P = (K2, beta, K2 / beta)."""
    return P[2] * np.expm1(P[1] * (left - right))


@njit(cache=True)
def force_stiffness(P, left, right):
    grown = np.expm1(P[1] * (left - right))
    return P[2] * grown, P[0] + P[0] * grown


@njit(cache=True)
def exp_remainder(x):
    """e^x - 1 - x, accurate to rounding for every x: its series below |x| = 1/2."""
    if abs(x) >= 0.5:
        return math.expm1(x) - x
    term, total = x * x / 2.0, 0.0
    n = 2
    while abs(term) > 1e-17 * abs(total) or total == 0.0:
        total += term
        n += 1
        term *= x / n
        if term == 0.0:
            break
    return total


@njit(cache=True)
def potential(P, left, right):
    return P[2] / P[1] * exp_remainder(P[1] * (left - right))


def parameters(chain):
    beta = -2.0 * chain.K3 / chain.K2
    return chain.K2, beta, chain.K2 / beta


MODEL = Model(
    name="toda",
    label=APPEARANCE["toda"].label,
    colour=APPEARANCE["toda"].colour,
    parameter_names=("K2", "beta", "K2/beta"),
    parameters=parameters,
    force=force,
    force_stiffness=force_stiffness,
    potential=potential,
    description="f = (K2/beta) (e^(beta D) - 1), beta = -2 K3/K2",
)
