"""The models: a registry of :class:`~chainchaos.system.models.base.Model`, one module each.

A model of the package is its module (name, label, colour, bond parameters, Numba kernels of its
bond law and, optionally, of its site law: see ``base``) and one line in :data:`MODELS`; the
engines, the initial-state solver, the energy, the configuration's allowed values and every label
take it from here. A model of your own, defined in your own module, joins the registry through
its checks (``chainchaos.engine.model_checks.add_model``).
"""

import numpy as np
from numba import njit

from chainchaos.errors import require
from chainchaos.system.models import dnls, fput, harmonic, hertz, klein_gordon, toda
from chainchaos.system.models.base import (Model, SiteLaw, add_site_energy, bond_force, bond_force_stiffness,
                                           bond_potential, bond_values, check_sites, site_potential, site_values)
from chainchaos.system.models.split import SplitModel, split_energy

#: Every model, by name: the bond models (``base.Model``) and the split ones (``split.SplitModel``).
MODELS: dict[str, Model | SplitModel] = {m.name: m for m in (
    hertz.MODEL,
    fput.MODEL,
    harmonic.MODEL,
    toda.MODEL,
    klein_gordon.MODEL,
    klein_gordon.LINEAR_MODEL,
    dnls.MODEL,
    dnls.LINEAR_MODEL,
)}

#: The bond models (``base.Model``: H = T(p) + V(q), the kick-drift engines), beside the split
#: ones (``split.SplitModel``).
BOND_MODELS: dict[str, Model] = {name: m for name, m in MODELS.items() if not m.is_split}

#: The models of bead chains (``chain.Chain``: their parameters come from the bead radii), the
#: ones the granular studies, the CLI's chain files and the paper's pipeline run.
BEAD_MODELS: dict[str, Model] = {name: m for name, m in MODELS.items() if m.lattice == "beads"}


#: The names of the package's own models, which no model of one's own may take.
PACKAGE_MODELS = tuple(MODELS)


def require_free_name(model: Model) -> None:
    """Require ``model``'s name to be free for it: not a package model's, nor another module's
    model's. The same model from the same modules (an edited version) may take it back.

    Parameters
    ----------
    model : Model
        The model to be added.

    Raises
    ------
    ParameterError
        For something not a Model, or a name already taken (the message names its holder).
    """
    require(isinstance(model, Model), "model", model, "a chainchaos Model")
    earlier = MODELS.get(model.name)
    if earlier is not None and earlier is not model:
        require(model.name not in PACKAGE_MODELS and earlier.modules == model.modules, "model name", model.name,
                f"a name not taken: {earlier.identity.split(':')[0]} has it (package models: {list(PACKAGE_MODELS)})")


def add_to_registry(model: Model) -> None:
    """Put ``model`` in :data:`MODELS` (and :data:`BOND_MODELS`, :data:`BEAD_MODELS`) under a free name
    (:func:`require_free_name`), unchecked: the checks come first
    (``chainchaos.engine.model_checks.add_model``).

    Parameters
    ----------
    model : Model
        The model, already checked.

    Raises
    ------
    ParameterError
        For a name already taken (:func:`require_free_name`).
    """
    require_free_name(model)
    MODELS[model.name] = model
    if not model.is_split:
        BOND_MODELS[model.name] = model
    if model.lattice == "beads":
        BEAD_MODELS[model.name] = model


def get_model(name) -> Model:
    """The model called ``name`` (a Model passes through).

    Parameters
    ----------
    name : str, Model or SplitModel
        A name of :data:`MODELS`, or a model.

    Returns
    -------
    Model or SplitModel
        The registered model (or ``name`` itself, a model).

    Raises
    ------
    ParameterError
        For a name not in the registry (the message lists those that are).
    """
    if isinstance(name, (Model, SplitModel)):
        return name
    require(name in MODELS, "model", name, f"one of {sorted(MODELS)}, or a model of your own added with "
                                           "chainchaos.add_model")
    return MODELS[name]


def model_label(name: str) -> str:
    """How figures and tables name the model (e.g. 'Hertz', 'FPUT').

    Parameters
    ----------
    name : str or Model
        A registered model's name, or a Model.

    Returns
    -------
    str
        Its ``label``.
    """
    return get_model(name).label


@njit(cache=True)
def _bond(model, u, P, b):
    """(parameters, u_{b-1}, u_b) of bond b, the walls at zero displacement."""
    N = u.shape[0]
    return bond_values(model, P, b), u[b - 1] if b > 0 else 0.0, u[b] if b < N else 0.0


@njit(cache=True)
def bond_forces(model, u, P, f, k, with_stiffness):
    """Fill f[b] (and k[b] if ``with_stiffness``) for every bond b = 0..N at displacements u (N,),
    P the bond parameters (parameters, N+1). The engines run the same kernels in their
    own vector loops; this is the plain version for everything else."""
    for b in range(u.shape[0] + 1):
        bond, left, right = _bond(model, u, P, b)
        if with_stiffness:
            f[b], k[b] = bond_force_stiffness(model, bond, left, right)
        else:
            f[b] = bond_force(model, bond, left, right)


@njit(cache=True)
def bond_potentials(model, u, P, V):
    """Fill V[b], the potential energy of every bond b = 0..N (zero at rest)."""
    for b in range(u.shape[0] + 1):
        bond, left, right = _bond(model, u, P, b)
        V[b] = bond_potential(model, bond, left, right)


@njit(cache=True)
def lattice_bond_potentials(model, u, P, ends, V):
    """Fill V[b], the potential energy of every bond b of a lattice given by its bonds ``ends``
    (B, 2) site numbers, -1 for a wall (``Geometry.bonds``)."""
    for b in range(ends.shape[0]):
        a, c = ends[b, 0], ends[b, 1]
        V[b] = bond_potential(model, bond_values(model, P, b), u[a] if a >= 0 else 0.0, u[c] if c >= 0 else 0.0)


def bond_potential_energy(model, chain, u: np.ndarray) -> np.ndarray:
    """Bond potentials V_b for one state u (N,) or many states u (..., N): shape (..., N+1).

    Parameters
    ----------
    model : str or Model
        The model.
    chain : Chain or KGLattice
        A lattice of the model's kind.
    u : numpy.ndarray of shape (..., N)
        Displacements (units of docs/conventions.md#units), the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (..., N + 1)
        The potential energy of every bond, zero at rest, in the model's energy unit.
    """
    model = get_model(model)
    u = np.ascontiguousarray(u, dtype=float)
    flat = u.reshape(-1, u.shape[-1])
    geometry = chain.geometry
    out = np.empty((flat.shape[0], geometry.n_bonds))
    P = model.bond_parameters(chain)
    ends = np.ascontiguousarray(geometry.bonds()) if geometry.dimension == 2 else None
    for i in range(flat.shape[0]):
        if ends is None:
            bond_potentials(model, flat[i], P, out[i])
        else:
            lattice_bond_potentials(model, flat[i], P, ends, out[i])
    return out.reshape(u.shape[:-1] + (geometry.n_bonds,))


@njit(cache=True)
def site_potentials(model, u, S, W):
    """Fill W[n], the on-site potential of every bead n = 0..N-1 (a model with a site law; S its
    site parameters (parameters, N))."""
    for n in range(u.shape[0]):
        W[n] = site_potential(model, site_values(model, S, n), u[n])


def site_potential_energy(model, chain, u: np.ndarray) -> np.ndarray | None:
    """On-site potentials w_n for one state u (N,) or many (..., N): shape (..., N); None for a
    model without a site law.

    Parameters
    ----------
    model : str or Model
        The model.
    chain : Chain or KGLattice
        A lattice of the model's kind.
    u : numpy.ndarray of shape (..., N)
        Displacements, the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (..., N), or None
        The on-site potential energy of every site, in the model's energy unit; None without a
        site law.
    """
    model = get_model(model)
    if not model.has_site_law:
        return None
    u = np.ascontiguousarray(u, dtype=float)
    flat = u.reshape(-1, u.shape[-1])
    out = np.empty(flat.shape)
    S = model.site_parameters(chain)
    for i in range(flat.shape[0]):
        site_potentials(model, flat[i], S, out[i])
    return out.reshape(u.shape)


@njit(cache=True)
def energy_kernel(model, q, p, mass, bonds, V, sites=None):
    """H of one state, summed in order (``V`` scratch of length N+1; ``sites`` the site
    parameters of a model with a site law, whose potentials come last): :func:`total_energy` for
    compiled loops (the energy checks of ``engine.checked``); the two agree to rounding."""
    check_sites(model, sites)
    bond_potentials(model, q, bonds, V)
    H = 0.0
    for n in range(q.shape[0]):
        H += 0.5 * p[n] * p[n] / mass[n]
    for b in range(V.shape[0]):
        H += V[b]
    return add_site_energy(model, q, sites, H)


def total_energy(model, chain, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """H = sum_n p_n^2 / (2 m_n) + sum_b V_b (+ sum_n w_n with a site law), every bond counted in
    full, for one state or many (docs/conventions.md#hamiltonian); NumPy's sums (the initial state
    is solved on it). For a split model, its own H (``split.split_energy``).

    Parameters
    ----------
    model : str, Model or SplitModel
        The model.
    chain : Chain, KGLattice or DNLSLattice
        A lattice of the model's kind (its masses and parameters).
    u, p : numpy.ndarray of shape (..., N)
        Displacements and momenta, the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (...)
        The total energy H of every state, in the model's energy unit (a NumPy float for one
        state).
    """
    model = get_model(model)
    if model.is_split:
        return split_energy(model, chain, u, p)
    kinetic = np.sum(p**2 / (2.0 * chain.mass), axis=-1)
    H = kinetic + bond_potential_energy(model, chain, u).sum(axis=-1)
    W = site_potential_energy(model, chain, u)
    return H if W is None else H + W.sum(axis=-1)


def energy_density(model, chain, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Normalised energy density h_n = H_n / sum_m H_m with
    H_n = p_n^2/(2 m_n) + (V_n + V_{n+1})/2 (the paper's Eq. 1 read literally), plus the bead's own
    on-site potential w_n for a model with a site law.

    Parameters
    ----------
    model : str or Model
        The model.
    chain : Chain or KGLattice
        A lattice of the model's kind.
    u, p : numpy.ndarray of shape (..., N)
        Displacements and momenta, the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (..., N)
        h_n, dimensionless, summing to 1 over the last axis.
    """
    V = bond_potential_energy(model, chain, u)
    if chain.geometry.dimension == 1:
        H = p**2 / (2.0 * chain.mass) + 0.5 * (V[..., :-1] + V[..., 1:])
    else:
        H = p**2 / (2.0 * chain.mass)
        add_bond_halves(H, V, chain.geometry.bonds())
    W = site_potential_energy(model, chain, u)
    if W is not None:
        H = H + W
    return H / H.sum(axis=-1, keepdims=True)


def add_bond_halves(H: np.ndarray, V: np.ndarray, ends: np.ndarray) -> None:
    """Add half of each bond's potential to each of its two sites (a wall takes none), in place.

    Parameters
    ----------
    H : numpy.ndarray of shape (..., N)
        Energies per site, the site on the last axis (a view is written through).
    V : numpy.ndarray of shape (..., B)
        The potential of every bond, in the order of ``ends``.
    ends : numpy.ndarray of shape (B, 2)
        Each bond's two site numbers, -1 for a wall (``Geometry.bonds``).
    """
    for sites in ends.T:  # the bonds' first sites, then their second
        np.add.at(np.moveaxis(H, -1, 0), sites[sites >= 0], np.moveaxis(0.5 * V[..., sites >= 0], -1, 0))


def open_bonds(model, chain, u: np.ndarray) -> np.ndarray:
    """True where a bond is open, for one state u (N,) or many (..., N): shape (..., N+1); all
    False for a model whose bonds never open. The model's opening kernel, on whole arrays.

    Parameters
    ----------
    model : str or Model
        The model.
    chain : Chain or KGLattice
        A lattice of the model's kind.
    u : numpy.ndarray of shape (..., N)
        Displacements, the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (..., N + 1), dtype bool
        Whether each bond is open.
    """
    model = get_model(model)
    u = np.ascontiguousarray(u, dtype=float)
    walls = np.zeros(u.shape[:-1] + (1,))
    padded = np.concatenate([walls, u, walls], axis=-1)
    if not model.has_gaps:
        return np.zeros(padded.shape[:-1] + (padded.shape[-1] - 1,), dtype=bool)
    P = tuple(model.bond_parameters(chain))
    return model.opening(P, np.ascontiguousarray(padded[..., :-1]), np.ascontiguousarray(padded[..., 1:])) < 0


__all__ = ["BEAD_MODELS", "BOND_MODELS", "MODELS", "PACKAGE_MODELS", "Model", "SiteLaw",
           "add_bond_halves", "add_to_registry", "bond_forces", "require_free_name",
           "bond_potential_energy", "bond_potentials", "energy_density", "energy_kernel", "get_model", "model_label",
           "open_bonds", "site_potential_energy", "site_potentials", "total_energy"]
