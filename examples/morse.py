"""A Morse bond between beads, as a model of your own (docs/tutorials/adding-a-model.md).

    V(D) = K2 (1 - exp(a D))^2 / (2 a^2),   f = dV/dD = K2 (exp(a D) - 1) exp(a D) / a,

with D = u_{n-1} - u_n the bond's compression: the Morse potential D_e (1 - exp(-a (r - r_e)))^2
of a bond of length r = r_e - D, a repulsive wall under compression (D > 0) and dissociation
under tension (V -> D_e as D -> -infinity). K2 = 2 a^2 D_e is the chain's linear stiffness, so
that the chain's linear limit (and its time unit, 1/omega_max) is the paper's; a sets the
anharmonicity and the well depth D_e = K2 / (2 a^2) of each bond (:func:`well_depth`): a total
energy H below the smallest well depth keeps every bond inside its well. Use it as
``SceneParameters(model=MORSE, ...)``, ``chainchaos.add_model(MORSE)``, or by where it is defined:
``model: morse.py:MORSE`` in a study file, ``--model examples/morse.py:MORSE`` on the command line.

Each bond carries four parameters, P = (K2, a, K2 / a, K2 / (2 a^2)): the kernels run on the batch
engine's vectors, which have + - * but no division, so the derived constants are computed once
per bond, here, and a may differ from bond to bond (:func:`parameters`).
"""

import numpy as np
from numba import njit

from chainchaos import Model

A = 2.0  # the Morse range a of every bond, per unit of compression D


@njit(cache=True)
def force(P, left, right):
    """f(D) of the bond, P = (K2, a, K2 / a, K2 / (2 a^2))."""
    e = np.expm1((left - right) * P[1])  # exp(a D) - 1
    return P[2] * e * (e + 1.0)


@njit(cache=True)
def force_stiffness(P, left, right):
    """(f, k = df/dD) of the bond."""
    e = np.expm1((left - right) * P[1])
    return P[2] * e * (e + 1.0), P[0] * (e + 1.0) * (e * 2.0 + 1.0)


@njit(cache=True)
def potential(P, left, right):
    """V(D), zero at rest."""
    e = np.expm1((left - right) * P[1])
    return P[3] * e * e


def parameters(chain, a=A):
    """(K2, a, K2 / a, K2 / (2 a^2)) of every bond: K2 the chain's linear stiffness, a the Morse
    range (a number, or one per bond)."""
    K2 = np.asarray(chain.K2, dtype=float)
    a = np.broadcast_to(np.asarray(a, dtype=float), K2.shape)
    return K2, a, K2 / a, K2 / (2.0 * a * a)


def well_depth(chain):
    """The well depth D_e = K2 / (2 a^2) of every bond of ``chain``: the energy that takes a bond
    over the top of its well (to dissociation)."""
    return parameters(chain)[3]


MORSE = Model(name="morse", label="Morse", colour="#2e7d32", parameter_names=("K2", "a", "K2/a", "K2/(2a^2)"),
              parameters=parameters, force=force, force_stiffness=force_stiffness, potential=potential,
              description="V = K2 (1 - exp(a D))^2 / (2 a^2), a = 2, D the compression")
