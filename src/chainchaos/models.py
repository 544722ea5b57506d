"""Bond models: Hertz (with the non-smooth contact) and FPUT, as Numba kernels.

Bond b (0-based, b = 0..N) joins beads b-1 and b; u_{-1} = u_N = 0 are the walls. With the bond
compression D_b = u_{b-1} - u_b, bead n obeys m_n u_n'' = f_n - f_{n+1} where

    Hertz:  f = A [delta + D]_+^(3/2),            k = df/dD = (3/2) A [delta + D]_+^(1/2)
    FPUT:   f = K2 D - K3 D^2 + K4 D^3,           k = K2 - 2 K3 D + 3 K4 D^2
    harmonic: FPUT with K3 = K4 = 0 (the common linear limit)

(FPUT written with y = -D: V(y) = K2 y^2/2 + K3 y^3/3 + K4 y^4/4, DESIGN section 2). A Hertz bond
whose overlap delta + D is negative is an open gap and carries no force. The model is an integer
so that one compiled engine serves both.
"""

import numpy as np
from numba import njit

from chainchaos.errors import require

HERTZ = 0
FPUT = 1
HARMONIC = 2
MODELS = {"hertz": HERTZ, "fput": FPUT, "harmonic": HARMONIC}


def model_id(name: str) -> int:
    require(name in MODELS, "model", name, f"one of {sorted(MODELS)}")
    return MODELS[name]


def coefficients(model: int, chain) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(K2, K3, K4) of the polynomial kernel; the harmonic model is FPUT with K3 = K4 = 0."""
    if model == HARMONIC:
        return chain.K2, np.zeros_like(chain.K2), np.zeros_like(chain.K2)
    return chain.K2, chain.K3, chain.K4


@njit(cache=True, inline="always")
def hertz_force(A, overlap):
    """Hertz bond force A [overlap]_+^(3/2), overlap = delta + D."""
    x = max(overlap, 0.0)
    return A * x * np.sqrt(x)


@njit(cache=True, inline="always")
def hertz_force_stiffness(A, overlap):
    """(force, stiffness df/dD) of a Hertz bond: (A x^(3/2), (3/2) A x^(1/2)), x = [overlap]_+."""
    x = max(overlap, 0.0)
    s = np.sqrt(x)
    return A * x * s, 1.5 * A * s


@njit(cache=True, inline="always")
def fput_force(K2, K3, K4, D):
    """FPUT bond force K2 D - K3 D^2 + K4 D^3 at compression D."""
    return D * (K2 - D * (K3 - D * K4))


@njit(cache=True, inline="always")
def fput_stiffness(K2, K3, K4, D):
    """FPUT bond stiffness df/dD = K2 - 2 K3 D + 3 K4 D^2."""
    return K2 - D * (2.0 * K3 - 3.0 * K4 * D)


@njit(cache=True)
def bond_forces(model, u, A, delta, K2, K3, K4, f, k, with_stiffness):
    """Fill f[b] (and k[b] if ``with_stiffness``) for every bond b = 0..N at displacements u (N,).

    The stepping engine (integrators.advance) runs the same per-bond kernels in its own padded,
    branch-free loop; this is the plain version for everything else.
    """
    N = u.shape[0]
    for b in range(N + 1):
        left = u[b - 1] if b > 0 else 0.0
        right = u[b] if b < N else 0.0
        if model == HERTZ:
            if with_stiffness:
                f[b], k[b] = hertz_force_stiffness(A[b], delta[b] + left - right)
            else:
                f[b] = hertz_force(A[b], delta[b] + left - right)
        else:
            f[b] = fput_force(K2[b], K3[b], K4[b], left - right)
            if with_stiffness:
                k[b] = fput_stiffness(K2[b], K3[b], K4[b], left - right)


@njit(cache=True)
def bond_potentials(model, u, A, delta, K2, K3, K4, V):
    """Fill V[b], the potential energy of every bond (zero at rest, >= 0 for Hertz)."""
    N = u.shape[0]
    for b in range(N + 1):
        left = u[b - 1] if b > 0 else 0.0
        right = u[b] if b < N else 0.0
        D = left - right
        if model == HERTZ:
            x = max(delta[b] + D, 0.0)
            d = delta[b]
            V[b] = A[b] * (0.4 * x * x * np.sqrt(x) - 0.4 * d * d * np.sqrt(d) - d * np.sqrt(d) * D)
        else:
            y = -D
            V[b] = y * y * (0.5 * K2[b] + y * (K3[b] / 3.0 + 0.25 * K4[b] * y))


def bond_potential_energy(model: int, chain, u: np.ndarray) -> np.ndarray:
    """Bond potentials for one state u (N,) or many states u (..., N): shape (..., N+1)."""
    u = np.ascontiguousarray(u, dtype=float)
    flat = u.reshape(-1, u.shape[-1])
    out = np.empty((flat.shape[0], flat.shape[1] + 1))
    K2, K3, K4 = coefficients(model, chain)
    for i in range(flat.shape[0]):
        bond_potentials(model, flat[i], chain.A, chain.delta, K2, K3, K4, out[i])
    return out.reshape(u.shape[:-1] + (u.shape[-1] + 1,))


def total_energy(model: int, chain, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """H = sum_n p_n^2 / (2 m_n) + sum_b V_b, every bond counted in full (DESIGN section 2)."""
    kinetic = np.sum(p**2 / (2.0 * chain.mass), axis=-1)
    return kinetic + bond_potential_energy(model, chain, u).sum(axis=-1)


def energy_density(model: int, chain, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Normalised energy density h_n = H_n / sum_m H_m with
    H_n = p_n^2/(2 m_n) + (V_n + V_{n+1})/2 (the paper's Eq. 1 read literally)."""
    V = bond_potential_energy(model, chain, u)
    H = p**2 / (2.0 * chain.mass) + 0.5 * (V[..., :-1] + V[..., 1:])
    return H / H.sum(axis=-1, keepdims=True)


def open_gaps(chain, u: np.ndarray) -> np.ndarray:
    """True where a Hertz bond is open: delta_b + u_{b-1} - u_b < 0 (shape (..., N+1))."""
    zeros = np.zeros(u.shape[:-1] + (1,))
    padded = np.concatenate([zeros, u, zeros], axis=-1)
    return chain.delta + padded[..., :-1] - padded[..., 1:] < 0
