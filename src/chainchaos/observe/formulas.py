"""Observables of the dynamics, computed from sampled states (vectorised over samples).

Every function takes arrays whose last axis is the site (or bond, or mode) and returns the
observable for every sample; all quantities are dimensionless. Logarithms and products go through
chainchaos.kernels.exactmath, so the values are the same on every CPU.
"""

import numpy as np
from numba import njit

from chainchaos.kernels import exactmath
from chainchaos.kernels.exactmath import gram_schmidt
from chainchaos.system.linear import participation_number

EULER_GAMMA = 0.5772156649015329


def energy_centre(h: np.ndarray) -> np.ndarray:
    """Mean position of the energy distribution, X = sum_n n h_n (sites n = 1..N)."""
    return exactmath.matmul(h, np.arange(1, h.shape[-1] + 1, dtype=np.float64))


def site_positions(geometry) -> np.ndarray:
    """(N, d) positions of the sites of a lattice (``system.geometry``), counted from 1 along
    every axis: n on a chain, (i + 1, j + 1) on a square lattice."""
    return geometry.coordinates().astype(np.float64) + 1.0


def second_moment(h: np.ndarray, positions: np.ndarray | None = None) -> np.ndarray:
    """Second moment of a distribution about its centre, m2 = sum_n |r_n - R|^2 h_n with
    R = sum_n r_n h_n: the packet's squared width, the spreading measure of the disordered-lattice
    literature (m2 ~ t^a while a packet spreads subdiffusively). ``positions`` (N, d) the sites'
    r_n (:func:`site_positions`; default the chain's, n = 1..N); in d dimensions the sum of the
    second moments along each axis."""
    if positions is None:
        positions = np.arange(1, h.shape[-1] + 1, dtype=np.float64)[:, None]
    total = None
    for axis in range(positions.shape[1]):
        r = np.ascontiguousarray(positions[:, axis])
        offset = r - exactmath.matmul(h, r)[..., None]
        along = exactmath.matmul(h * offset * offset, np.ones(h.shape[-1]))
        total = along if total is None else total + along
    return total


#: Sites at each end whose energy ``edge_energy`` sums.
EDGE_MARGIN = 5


def edge_energy(h: np.ndarray, positions: np.ndarray | None = None, margin: int = EDGE_MARGIN) -> np.ndarray:
    """Fraction of the energy on the sites within ``margin`` sites of an edge of the lattice, each
    site counted once: on a chain sum_{n <= margin} h_n + sum_{n > N - margin} h_n, on a square
    lattice the frame of that width along its four edges. ``positions`` (N, d) the sites'
    positions counted from 1 (:func:`site_positions`; default the chain's). A packet that reaches
    the edges is no longer spreading into an infinite lattice."""
    if positions is None:
        positions = np.arange(1, h.shape[-1] + 1, dtype=np.float64)[:, None]
    lengths = positions.max(axis=0)
    near = np.any((positions <= margin) | (positions > lengths - margin), axis=1)
    return exactmath.matmul(h, near.astype(np.float64))


def compactness(P: np.ndarray, m2: np.ndarray) -> np.ndarray:
    """Compactness index zeta = P^2 / m2 of an energy distribution: 12 L^2 / (L^2 - 1) for energy
    spread evenly over L sites, about 3 for a thermalized packet (site energies exponentially
    distributed), much smaller for a sparse one of far-apart peaks."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return P * P / m2


def norm_density(q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """z_n = (q_n^2 + p_n^2) / sum_m (q_m^2 + p_m^2) = |psi_n|^2 / S, over the last axis: the
    distribution whose spreading the DNLS literature measures (its energy density may be
    negative)."""
    x = q * q + p * p
    return x / x.sum(axis=-1, keepdims=True)


def deviation_vector_density(dq: np.ndarray, dp: np.ndarray) -> np.ndarray:
    """DVD w_n = (dq_n^2 + dp_n^2) / sum_m (dq_m^2 + dp_m^2) (the paper's Eq. 9)."""
    w = dq**2 + dp**2
    return w / w.sum(axis=-1, keepdims=True)


def finite_time_mlce(log_growth: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Lambda(t) = ln(|v(t)| / |v(0)|) / t from the accumulated log growth; NaN at t = 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t > 0, log_growth / np.where(t > 0, t, 1.0), np.nan)


def spectral_entropy(E: np.ndarray) -> np.ndarray:
    """S = -sum_k v_k ln v_k with v_k = E_k / sum E_k (0 ln 0 = 0)."""
    v = E / E.sum(axis=-1, keepdims=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        terms = np.where(v > 0, v * exactmath.log(np.where(v > 0, v, 1.0)), 0.0)
    return -terms.sum(axis=-1)


def normalised_entropy(S: np.ndarray, S0: float, N: int) -> np.ndarray:
    """eta = (S - ln N) / (S(0) - ln N): 1 at t = 0, 0 at equal modal energies."""
    ln_N = exactmath.log(float(N))
    return (S - ln_N) / (S0 - ln_N)


def equipartition_eta(S0: float, N: int) -> float:
    """Mean eta at equipartition, <eta> = (1 - C) / (ln N - S(0)) with Euler's constant C."""
    return (1.0 - EULER_GAMMA) / (exactmath.log(float(N)) - S0)


def lyapunov_spectrum(growth: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Finite-time Lyapunov exponents lambda_i(t) = (1/t) sum ln R_ii (Benettin, Galgani,
    Giorgilli & Strelcyn, Meccanica 15, 9 (1980)): ``growth`` (S, k) holds the accumulated ln of
    the norms of k deviation vectors kept orthonormal (QR every check); NaN at t = 0."""
    return finite_time_mlce(growth, np.asarray(t)[:, None])


def ks_entropy(spectrum: np.ndarray) -> np.ndarray:
    """Kolmogorov-Sinai entropy estimate h_KS = sum of the positive exponents (Pesin), per sample
    (units of omega_max); NaN where the exponents are not measured."""
    with np.errstate(invalid="ignore"):
        total = np.where(spectrum > 0, spectrum, 0.0).sum(axis=-1)
    return np.where(np.isnan(spectrum).all(axis=-1), np.nan, total)


def log_volume(W: np.ndarray) -> float:
    """ln of the k-dimensional volume of the parallelepiped spanned by the rows of W (k, 2N, each
    a deviation vector du then dp): sum_i ln R_ii of the QR factorisation of W^T by modified
    Gram-Schmidt (``kernels.exactmath.gram_schmidt``), (1/2) ln det(W W^T). For unit rows (normalised
    deviation vectors) it is ln GALI_k (Skokos, Bountis & Antonopoulos, Physica D 231, 30 (2007)),
    the product of the singular values; the log form does not underflow where GALI_k goes far
    below the smallest double."""
    logs = np.zeros(W.shape[0])
    gram_schmidt(np.array(W, dtype=float), 0, W.shape[0], logs)
    return float(exactmath.matmul(logs, np.ones(logs.size)))


@njit(cache=True)
def sali(w1: np.ndarray, w2: np.ndarray) -> float:
    """Smaller alignment index SALI = min(|w1 + w2|, |w1 - w2|) of two unit deviation vectors
    (Skokos, J. Phys. A 34, 10029 (2001)): of order one on a regular orbit, decaying as
    exp(-(lambda_1 - lambda_2) t) on a chaotic one."""
    plus, minus = 0.0, 0.0
    for m in range(w1.size):
        plus += (w1[m] + w2[m]) ** 2
        minus += (w1[m] - w2[m]) ** 2
    return min(np.sqrt(plus), np.sqrt(minus))


__all__ = [
    "lyapunov_spectrum",
    "ks_entropy",
    "log_volume",
    "sali",
    "energy_centre",
    "second_moment",
    "site_positions",
    "deviation_vector_density",
    "finite_time_mlce",
    "spectral_entropy",
    "normalised_entropy",
    "equipartition_eta",
    "participation_number",
]
