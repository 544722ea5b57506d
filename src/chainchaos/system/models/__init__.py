"""The bond models: a registry of :class:`~chainchaos.system.models.base.Model`, one module each.

Adding a model is its module (name, label, colour, bond parameters, Numba kernels of its bond
law: see ``base``) and one line in :data:`MODELS`; the engines, the initial-state solver, the
energy, the configuration's allowed values and every label take it from here.
"""

import numpy as np
from numba import njit

from chainchaos.errors import require
from chainchaos.system.models import fput, harmonic, hertz, toda
from chainchaos.system.models.base import MAX_BOND_PARAMETERS, Model, bond_force, bond_force_stiffness, bond_potential

#: Every model, by name.
MODELS: dict[str, Model] = {m.name: m for m in (
    hertz.MODEL,
    fput.MODEL,
    harmonic.MODEL,
    toda.MODEL,
)}


def get_model(name) -> Model:
    """The model called ``name`` (a Model passes through)."""
    if isinstance(name, Model):
        return name
    require(name in MODELS, "model", name, f"one of {sorted(MODELS)}")
    return MODELS[name]


def model_label(name: str) -> str:
    """How figures and tables name the model (e.g. 'Hertz', 'FPUT')."""
    return get_model(name).label


@njit(cache=True, inline="always")
def _bond(u, P, b):
    """(parameters, u_{b-1}, u_b) of bond b, the walls at zero displacement."""
    N = u.shape[0]
    return (P[0, b], P[1, b], P[2, b]), u[b - 1] if b > 0 else 0.0, u[b] if b < N else 0.0


@njit(cache=True)
def bond_forces(model, u, P, f, k, with_stiffness):
    """Fill f[b] (and k[b] if ``with_stiffness``) for every bond b = 0..N at displacements u (N,),
    P the bond parameters (MAX_BOND_PARAMETERS, N+1). The engines run the same kernels in their
    own vector loops; this is the plain version for everything else."""
    for b in range(u.shape[0] + 1):
        bond, left, right = _bond(u, P, b)
        if with_stiffness:
            f[b], k[b] = bond_force_stiffness(model, bond, left, right)
        else:
            f[b] = bond_force(model, bond, left, right)


@njit(cache=True)
def bond_potentials(model, u, P, V):
    """Fill V[b], the potential energy of every bond b = 0..N (zero at rest)."""
    for b in range(u.shape[0] + 1):
        bond, left, right = _bond(u, P, b)
        V[b] = bond_potential(model, bond, left, right)


def bond_potential_energy(model, chain, u: np.ndarray) -> np.ndarray:
    """Bond potentials V_b for one state u (N,) or many states u (..., N): shape (..., N+1)."""
    model = get_model(model)
    u = np.ascontiguousarray(u, dtype=float)
    flat = u.reshape(-1, u.shape[-1])
    out = np.empty((flat.shape[0], flat.shape[1] + 1))
    P = model.bond_parameters(chain)
    for i in range(flat.shape[0]):
        bond_potentials(model, flat[i], P, out[i])
    return out.reshape(u.shape[:-1] + (u.shape[-1] + 1,))


@njit(cache=True)
def energy_kernel(model, q, p, mass, bonds, V):
    """H of one state, summed in order (``V`` scratch of length N+1): :func:`total_energy` for
    compiled loops (the energy checks of ``engine.checked``); the two agree to rounding."""
    bond_potentials(model, q, bonds, V)
    H = 0.0
    for n in range(q.shape[0]):
        H += 0.5 * p[n] * p[n] / mass[n]
    for b in range(V.shape[0]):
        H += V[b]
    return H


def total_energy(model, chain, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """H = sum_n p_n^2 / (2 m_n) + sum_b V_b, every bond counted in full, for one state or many
    (docs/conventions.md#hamiltonian); NumPy's sums (the initial state is solved on it)."""
    kinetic = np.sum(p**2 / (2.0 * chain.mass), axis=-1)
    return kinetic + bond_potential_energy(model, chain, u).sum(axis=-1)


def energy_density(model, chain, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Normalised energy density h_n = H_n / sum_m H_m with
    H_n = p_n^2/(2 m_n) + (V_n + V_{n+1})/2 (the paper's Eq. 1 read literally)."""
    V = bond_potential_energy(model, chain, u)
    H = p**2 / (2.0 * chain.mass) + 0.5 * (V[..., :-1] + V[..., 1:])
    return H / H.sum(axis=-1, keepdims=True)


def open_bonds(model, chain, u: np.ndarray) -> np.ndarray:
    """True where a bond is open, for one state u (N,) or many (..., N): shape (..., N+1); all
    False for a model whose bonds never open. The model's opening kernel, on whole arrays."""
    model = get_model(model)
    u = np.ascontiguousarray(u, dtype=float)
    walls = np.zeros(u.shape[:-1] + (1,))
    padded = np.concatenate([walls, u, walls], axis=-1)
    if not model.has_gaps:
        return np.zeros(padded.shape[:-1] + (padded.shape[-1] - 1,), dtype=bool)
    P = tuple(model.bond_parameters(chain))
    return model.opening(P, np.ascontiguousarray(padded[..., :-1]), np.ascontiguousarray(padded[..., 1:])) < 0


__all__ = ["MAX_BOND_PARAMETERS", "MODELS", "Model", "bond_forces", "bond_potential_energy", "bond_potentials",
           "energy_density", "energy_kernel", "get_model", "model_label", "open_bonds", "total_energy"]
