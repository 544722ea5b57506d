"""Observables of the dynamics, computed from sampled states (vectorised over samples).

Every function takes arrays whose last axis is the site (or bond, or mode) and returns the
observable for every sample; all quantities are dimensionless. Logarithms and products go through
chainchaos.engine.exactmath, so the values are the same on every CPU.
"""

import numpy as np

from chainchaos.engine import exactmath
from chainchaos.system.linear import participation_number

EULER_GAMMA = 0.5772156649015329


def energy_centre(h: np.ndarray) -> np.ndarray:
    """Mean position of the energy distribution, X = sum_n n h_n (sites n = 1..N)."""
    return exactmath.matmul(h, np.arange(1, h.shape[-1] + 1, dtype=np.float64))


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


__all__ = [
    "energy_centre",
    "deviation_vector_density",
    "finite_time_mlce",
    "spectral_entropy",
    "normalised_entropy",
    "equipartition_eta",
    "participation_number",
]
