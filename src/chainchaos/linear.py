"""Linear normal modes of a chain and their participation numbers (DESIGN section 3).

The generalised eigenproblem K U = omega^2 M U, with K tridiagonal from the bond stiffness K2 and
M = diag(m), is solved as the symmetric tridiagonal problem S V = omega^2 V with
S = M^(-1/2) K M^(-1/2) and U = M^(-1/2) V, so that U^T M U = I.
"""

import numpy as np
from scipy.linalg import eigh_tridiagonal

from chainchaos.chain import Chain, random_radii
from chainchaos.errors import require

CONVENTIONS = ("potential", "period_averaged")


def normal_modes(chain: Chain) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies omega_k (increasing, units of omega_max of the homogeneous chain) and mode
    shapes U[n, k], mass-orthonormal (U^T M U = I), each with its largest component positive."""
    K2 = chain.K2
    m = chain.mass
    diag = (K2[:-1] + K2[1:]) / m
    off = -K2[1:-1] / np.sqrt(m[:-1] * m[1:])
    w2, V = eigh_tridiagonal(diag, off)
    U = V / np.sqrt(m)[:, None]
    peak = np.argmax(np.abs(U), axis=0)
    U *= np.sign(U[peak, np.arange(U.shape[1])])
    return np.sqrt(np.clip(w2, 0.0, None)), U


def harmonic_bond_energy(chain: Chain, u: np.ndarray) -> np.ndarray:
    """K2_b y_b^2 / 2 for every bond b = 1..N+1, with y_b = u_b - u_{b-1} and fixed walls.

    ``u`` has the site as its first axis; further axes (e.g. modes) are carried along."""
    padded = np.concatenate([np.zeros((1,) + u.shape[1:]), u, np.zeros((1,) + u.shape[1:])])
    y = np.diff(padded, axis=0)
    K2 = chain.K2.reshape((-1,) + (1,) * (u.ndim - 1))
    return 0.5 * K2 * y**2


def mode_energy_density(chain: Chain, omega: np.ndarray, U: np.ndarray, convention: str = "potential") -> np.ndarray:
    """Normalised energy density h[n, k] of each mode (sum over n is 1).

    ``potential``: u = mode shape, p = 0; each bond's harmonic energy split half-half to its two
    beads, the wall bonds' outer halves belonging to the walls (DESIGN section 3).
    ``period_averaged``: the mean over one period of that density and the kinetic one
    m_n omega_k^2 U_nk^2 / 2, i.e. the time-averaged energy density of the oscillating mode.
    """
    require(convention in CONVENTIONS, "convention", convention, f"one of {CONVENTIONS}")
    bond = harmonic_bond_energy(chain, U)
    density = 0.5 * (bond[:-1] + bond[1:])
    if convention == "period_averaged":
        kinetic = 0.5 * chain.mass[:, None] * (omega[None, :] * U) ** 2
        density = density / density.sum(axis=0) + kinetic / kinetic.sum(axis=0)
    return density / density.sum(axis=0)


def participation_number(h: np.ndarray, axis: int = 0) -> np.ndarray:
    """P = 1 / sum_n h_n^2 of a normalised density h (sum_n h_n = 1); 1 <= P <= N."""
    return 1.0 / np.sum(h**2, axis=axis)


def mode_participation(chain: Chain, convention: str = "potential") -> np.ndarray:
    """Participation number of every normal mode, ordered by increasing frequency."""
    omega, U = normal_modes(chain)
    return participation_number(mode_energy_density(chain, omega, U, convention))


def modal_coordinates(chain: Chain, U: np.ndarray, u: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q = U^T M u and P = U^T p (site on the last axis of u and p, mode on the last axis of the result)."""
    return (u * chain.mass) @ U, p @ U


def modal_energies(chain: Chain, omega: np.ndarray, U: np.ndarray, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Harmonic energy E_k = (P_k^2 + omega_k^2 Q_k^2) / 2 of every mode (DESIGN section 3)."""
    Q, P = modal_coordinates(chain, U, u, p)
    return 0.5 * (P**2 + (omega * Q) ** 2)


def ensemble_participation(
    alphas, n_realizations: int, N: int = 40, first_seed: int = 0, convention: str = "potential"
) -> dict[str, np.ndarray]:
    """Statistics of the mode participation numbers, sorted in descending order per realization.

    Realization i of every alpha is ``random_radii(first_seed + i, alpha, N)`` (DESIGN section 1):
    the same seeds as the realization search, so any member can be rebuilt from its seed.
    Returns ``mean`` and ``std`` of shape (len(alphas), N), indexed by rank k = 1..N.
    """
    alphas = np.atleast_1d(np.asarray(alphas, dtype=float))
    require(isinstance(n_realizations, (int, np.integer)) and n_realizations >= 2,
            "n_realizations", n_realizations, "an integer >= 2")
    P = np.empty((alphas.size, n_realizations, N))
    for a, alpha in enumerate(alphas):
        for i in range(n_realizations):
            chain = Chain(random_radii(first_seed + i, alpha, N), alpha)
            P[a, i] = np.sort(mode_participation(chain, convention))[::-1]
    return {"mean": P.mean(axis=1), "std": P.std(axis=1, ddof=1), "participation": P}
