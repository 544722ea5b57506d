"""Initial conditions: one displaced bead, and a random deviation vector
(docs/conventions.md#initial-conditions)."""

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from chainchaos.engine.exactmath import norm
from chainchaos.engine.integrators import gram_schmidt
from chainchaos.errors import ParameterError, require
from chainchaos.system.models import total_energy

U0_LIMIT = 1e6


def excitation_energy(model: int, chain, site: int, u0: float) -> float:
    """Energy of the state with only bead ``site`` (1-based) displaced by u0, all momenta zero."""
    u = np.zeros(chain.N)
    u[site - 1] = u0
    return float(total_energy(model, chain, u, np.zeros(chain.N)))


def initial_displacement(model: int, chain, energy: float, site: int) -> float:
    """The smallest u0 > 0 with excitation_energy(u0) = energy, from the model's exact potential.

    Raises ParameterError naming the energy when no u0 reaches it (the FPUT potential with the
    Taylor sign of K4 has a maximum along this excitation).
    """
    require(np.isfinite(energy) and energy > 0, "energy", energy, "a finite energy > 0")
    require(isinstance(site, (int, np.integer)) and 1 <= site <= chain.N, "excited_site", site,
            f"an integer bead index 1..{chain.N}")

    def residual(u0):
        return excitation_energy(model, chain, site, u0) - energy

    lo, e_lo, hi = 0.0, 0.0, 1e-3
    while hi < U0_LIMIT:
        e_hi = residual(hi) + energy
        if e_hi >= energy:
            return brentq(residual, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        if e_hi < e_lo:
            peak = minimize_scalar(lambda x: -excitation_energy(model, chain, site, x),
                                   bounds=(0.0, hi), method="bounded", options={"xatol": 1e-12})
            e_max = -peak.fun
            if e_max >= energy:
                return brentq(residual, 0.0, peak.x, xtol=1e-15, rtol=4 * np.finfo(float).eps)
            raise ParameterError("energy", energy,
                                 f"at most {e_max:.6g}: the potential along this excitation peaks there")
        lo, e_lo, hi = hi, e_hi, 2.0 * hi
    raise ParameterError("energy", energy, f"an energy reached with u0 < {U0_LIMIT:g}")


def initial_state(model: int, chain, energy: float, site: int) -> tuple[np.ndarray, np.ndarray, float]:
    """(u, p, u0): bead ``site`` displaced by u0 > 0 so that H = energy, all momenta zero."""
    u0 = initial_displacement(model, chain, energy, site)
    u = np.zeros(chain.N)
    u[site - 1] = u0
    return u, np.zeros(chain.N), u0


def extra_deviations(N: int, seed: int, count: int, stream: int) -> tuple[np.ndarray, np.ndarray]:
    """``count`` more deviation vectors (du, dp), each (count, N): du and dp uniform in [-1, 1]
    from default_rng([seed, stream, i]), each normalised to 1 (docs/conventions.md#deviation-vector);
    ``stream`` 1 for the Lyapunov spectrum's, 2 for GALI's."""
    du, dp = np.zeros((count, N)), np.zeros((count, N))
    for i in range(count):
        v = np.random.default_rng([int(seed), int(stream), i + 1]).uniform(-1.0, 1.0, 2 * N)
        v = v / norm(v)
        du[i], dp[i] = v[:N], v[N:]
    return du, dp


def orthonormalised(first: np.ndarray, others: np.ndarray) -> np.ndarray:
    """``others`` (k, 2N) made orthogonal to the unit deviation vector ``first`` (2N,) and to each
    other and normalised (``integrators.gram_schmidt``): the start of a Lyapunov spectrum, whose
    first QR then measures the dynamics only."""
    W = np.vstack([first, others]).astype(float)
    gram_schmidt(W, 1, W.shape[0], np.zeros(W.shape[0]))
    return W[1:]


def initial_deviation(N: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Deviation vector (du, dp) with du = 0 and dp uniform in [-1, 1] from default_rng(seed),
    normalised to |(du, dp)| = 1 (the paper's choice, docs/conventions.md#deviation-vector)."""
    dp = np.random.default_rng(seed).uniform(-1.0, 1.0, N)
    return np.zeros(N), dp / norm(dp)
