"""The Hertz chain: spheres in contact, whose bonds open when the beads separate.

    f = A [delta + D]_+^(3/2),  k = df/dD = (3/2) A [delta + D]_+^(1/2),
    V = A ((2/5) x^(5/2) - (2/5) delta^(5/2) - delta^(3/2) D),  x = [delta + D]_+,

with D = u_{b-1} - u_b the compression beyond the static overlap delta (so V = 0 and V' = 0 at
rest, V >= 0). A bond with delta + D < 0 is open (a gap) and carries no force (docs/conventions.md).
"""

import numpy as np
from numba import njit

from chainchaos.system.models.base import Model
from chainchaos.system.appearance import APPEARANCE


@njit(cache=True)
def hertz_force(A, overlap):
    """Hertz bond force A [overlap]_+^(3/2), overlap = delta + D."""
    x = max(overlap, 0.0)
    return A * x * np.sqrt(x)


@njit(cache=True)
def hertz_force_stiffness(A, overlap):
    """(force, stiffness df/dD) of a Hertz bond: (A x^(3/2), (3/2) A x^(1/2)), x = [overlap]_+."""
    x = max(overlap, 0.0)
    s = np.sqrt(x)
    return A * x * s, 1.5 * A * s


@njit(cache=True)
def force(P, left, right):
    """P = (A, delta)."""
    return hertz_force(P[0], P[1] + left - right)


@njit(cache=True)
def force_stiffness(P, left, right):
    return hertz_force_stiffness(P[0], P[1] + left - right)


@njit(cache=True)
def potential(P, left, right):
    A, d = P[0], P[1]
    D = left - right
    x = max(d + D, 0.0)
    return A * (0.4 * x * x * np.sqrt(x) - 0.4 * d * d * np.sqrt(d) - d * np.sqrt(d) * D)


@njit(cache=True)
def opening(P, left, right):
    """delta + D: the bond is open where it is negative."""
    return P[1] + left - right


def parameters(chain):
    return chain.A, chain.delta


MODEL = Model(
    name="hertz",
    label=APPEARANCE["hertz"].label,
    colour=APPEARANCE["hertz"].colour,
    parameter_names=("A", "delta"),
    parameters=parameters,
    force=force,
    force_stiffness=force_stiffness,
    potential=potential,
    opening=opening,
    description="f = A [delta + D]_+^(3/2)",
)
