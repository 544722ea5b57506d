"""What a bond model is, and how the Numba engines call it.

A model is one :class:`Model` (a module of ``chainchaos.system.models`` each, listed in its registry).
Bond b (0-based, b = 0..N) joins beads b-1 and b, with u_{-1} = u_N = 0 the walls; its
compression is D_b = u_{b-1} - u_b and bead n obeys m_n u_n'' = f_n - f_{n+1}, with f the bond
force (positive in compression) of the model's law. A model gives, per bond, its parameters as
rows of one array (at most :data:`MAX_BOND_PARAMETERS`, computed from the chain), and Numba
kernels of the bond law ``force(P, left, right)``, ``force_stiffness(P, left, right)`` (f and
k = df/dD), ``potential(P, left, right)`` (V, zero at rest) and, for a model whose bonds can
open, ``opening(P, left, right)`` (negative where the bond is open). P is the tuple of the bond's
parameters, ``left`` and ``right`` the displacements u_{b-1} and u_b: floats, or vectors of the
batch engine (``chainchaos.kernels.simd``), for which force and stiffness must use only + - *,
``max``, ``np.sqrt`` and ``np.expm1`` (each lane then gets
exactly the scalar result).

A model may also have a site law (:class:`SiteLaw`): an on-site potential w(u) of each bead, with
its own parameters per site (rows of one array, at most :data:`MAX_SITE_PARAMETERS`, computed from
the chain) and kernels ``force(S, u)`` (w'(u), which enters m_n u_n'' = f_n - f_{n+1} - w'(u_n)),
``force_stiffness(S, u)`` (w', w'') and ``potential(S, u)`` (w, zero at rest), under the same
rules for vectors as the bond law's. S is the tuple of the site's parameters, u the bead's
displacement. A model without a site law compiles without one: the dispatchers below
(``site_kick``, ``site_kick_deviation``, ``add_site_energy``) are then the identity at compile
time, not a zero law, so its machine code and its numbers are those of a model that never heard of
site laws.

A model is also a Numba type: passed to a compiled function it selects its kernels at compile
time (``bond_force`` and the other dispatchers below), so one engine source serves every model
and each model gets its own machine code, without a branch on the model in the inner loop.
"""

import hashlib
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar

import numpy as np
from numba import njit, types
from numba.core.errors import TypingError
from numba.extending import (
    NativeValue,
    models,
    overload,
    register_model,
    typeof_impl,
    unbox,
)

from chainchaos.errors import require

#: Rows of bond parameters the engines carry: a model may use up to this many.
MAX_BOND_PARAMETERS = 3

#: Rows of site parameters the engines carry: a site law may use up to this many.
MAX_SITE_PARAMETERS = 2

#: Every Model created, by identity (:attr:`Model.identity`): what its Numba type compiles in
#: (``_kernels``).
_BY_IDENTITY: dict[str, "Model"] = {}


def site_parameter_array(rows, N: int) -> np.ndarray:
    """The engines' site parameter array: ``rows``, then rows of zeros.

    Parameters
    ----------
    rows : sequence of numpy.ndarray
        At most ``MAX_SITE_PARAMETERS`` rows of N values each (a model's site parameters).
    N : int
        The number of sites.

    Returns
    -------
    numpy.ndarray of shape (MAX_SITE_PARAMETERS, N)
        Row i is ``rows[i]``, the rows beyond them zero.
    """
    out = np.zeros((MAX_SITE_PARAMETERS, N))
    for i, row in enumerate(rows):
        out[i] = row
    return out


def _kernel_identity(name: str, kernels) -> str:
    """``name@modules:digest``: the modules that define ``kernels`` (Numba dispatchers or plain
    functions) and a SHA-256 of their source files. The Numba type of a model is named by it, so
    that Numba's on-disk cache, which keys a compiled engine by its argument types, never hands one
    model the kernels of another of the same name, nor of an earlier version of its own module."""
    modules = sorted({getattr(getattr(k, "py_func", k), "__module__", None) or "" for k in kernels})
    digest = hashlib.sha256()
    for module in modules:
        source = getattr(sys.modules.get(module), "__file__", None)
        digest.update(module.encode() + b"\0" + (Path(source).read_bytes() if source else b""))
    return f"{name}@{','.join(modules)}:{digest.hexdigest()[:16]}"


@dataclass(frozen=True, eq=False, kw_only=True)
class SiteLaw:
    """An on-site potential w(u) of every bead: its parameters per site and its Numba kernels.

    Parameters
    ----------
    parameter_names : tuple of str
        Names of the site parameters (at most :data:`MAX_SITE_PARAMETERS`), e.g. ``("eps",)``.
    parameters : callable
        ``parameters(lattice)``: one array of length N per name.
    force : callable
        Numba kernel ``force(S, u)``: w'(u) of a site with parameters S at displacement u.
    force_stiffness : callable
        Numba kernel ``force_stiffness(S, u)``: (w'(u), w''(u)).
    potential : callable
        Numba kernel ``potential(S, u)``: w(u), zero at u = 0.
    description : str, optional
        The law in one line, for documentation.
    """

    parameter_names: tuple[str, ...]  # the rows of ``parameters(chain)``
    parameters: Callable  # chain -> tuple of arrays (N,), one per parameter name
    force: Callable  # w'(S, u)
    force_stiffness: Callable  # (w', w'')
    potential: Callable  # w, zero at u = 0
    description: str = ""  # the site law, one line, for documentation

    def __post_init__(self):
        require(0 < len(self.parameter_names) <= MAX_SITE_PARAMETERS, "site parameter_names",
                self.parameter_names, f"1 to {MAX_SITE_PARAMETERS} site parameters")


@dataclass(frozen=True, eq=False, kw_only=True)
class Model:
    """A model: its name, its parameters per bond and the Numba kernels of its bond law (and of
    its site law, if any).

    Parameters
    ----------
    name : str
        The key in configs, file names and the registry ``MODELS``.
    label : str
        How figures and tables name it.
    colour : str
        The colour of its curves (a matplotlib colour).
    parameter_names : tuple of str
        Names of the bond parameters (at most :data:`MAX_BOND_PARAMETERS`).
    parameters : callable
        ``parameters(lattice)``: one array of length N + 1 (one value per bond) per name.
    force : callable
        Numba kernel ``force(P, left, right)``: the force f(D) of a bond with parameters P between
        displacements left = u_{n-1} and right = u_n (compression D = left - right).
    force_stiffness : callable
        Numba kernel ``force_stiffness(P, left, right)``: (f, k = df/dD).
    potential : callable
        Numba kernel ``potential(P, left, right)``: V(D), zero at rest.
    opening : callable, optional
        Numba kernel ``opening(P, left, right)``, negative where the bond is open; None (the
        default) for bonds that never open.
    description : str, optional
        The bond law in one line, for documentation.
    site : SiteLaw, optional
        The on-site potential; None (the default): the beads feel only their bonds.
    lattice : {"beads", "kg"}, optional
        The kind of lattice ``parameters`` read (:data:`LATTICES`): a bead ``Chain`` (default) or
        a ``KGLattice``.

    Attributes
    ----------
    identity : str
        ``name@modules:digest``: the name, the modules that define the kernels and a digest of
        their sources. The model's Numba type is named by it, so an edited kernel recompiles and
        two models of one name never share compiled code.

    Notes
    -----
    ``force`` and ``force_stiffness`` also run on the batch engine's vectors: they may use only
    ``+ - *``, ``max``, ``np.sqrt`` and ``np.expm1`` (``chainchaos.engine.model_checks``).
    """

    name: str  # the key in configs, file names and the registry
    label: str  # for figures and tables
    colour: str  # of its curves in figures
    parameter_names: tuple[str, ...]  # the rows of ``parameters(chain)``
    parameters: Callable  # chain -> tuple of arrays (N+1,), one per parameter name
    force: Callable
    force_stiffness: Callable
    potential: Callable
    opening: Callable | None = None  # None: the bonds never open
    description: str = ""  # the bond law, one line, for documentation
    site: SiteLaw | None = None  # the on-site potential; None: the beads feel only their bonds
    lattice: str = "beads"  # what ``parameters`` read: a bead Chain ("beads") or a KGLattice ("kg")
    identity: str = field(init=False, repr=False, default="")  # name, kernels' modules and sources

    #: A bond model is integrated by the kick-drift schemes (``models.split`` for the others).
    is_split: ClassVar[bool] = False

    def __post_init__(self):
        require(0 < len(self.parameter_names) <= MAX_BOND_PARAMETERS, "parameter_names",
                self.parameter_names, f"1 to {MAX_BOND_PARAMETERS} bond parameters")
        require(self.lattice in LATTICES, "lattice", self.lattice, f"one of {list(LATTICES)}")
        kernels = [self.force, self.force_stiffness, self.potential, *filter(None, [self.opening])]
        if self.site is not None:
            kernels += [self.site.force, self.site.force_stiffness, self.site.potential]
        object.__setattr__(self, "identity", _kernel_identity(self.name, kernels))
        _BY_IDENTITY[self.identity] = self

    @property
    def modules(self) -> str:
        """The modules that define the model's kernels, as its identity names them."""
        return self.identity.partition("@")[2].rpartition(":")[0]

    @property
    def has_site_law(self) -> bool:
        """Whether the beads of this model also feel an on-site potential."""
        return self.site is not None

    @property
    def has_gaps(self) -> bool:
        """Whether a bond of this model can open (lose contact) and carry no force."""
        return self.opening is not None

    def bond_parameters(self, chain) -> np.ndarray:
        """The engines' bond parameter array (MAX_BOND_PARAMETERS, bonds): the model's rows, then
        zeros; a chain's N + 1 bonds, a square lattice's in the order of ``geometry.bonds()``.

        Parameters
        ----------
        chain : Chain or KGLattice
            A lattice of the model's kind (``lattice``).

        Returns
        -------
        numpy.ndarray of shape (MAX_BOND_PARAMETERS, N + 1)
            Row i the parameter ``parameter_names[i]`` of every bond, in the units the model's
            law reads them; the rows beyond the model's zero.
        """
        rows = self.parameters(chain)
        out = np.zeros((MAX_BOND_PARAMETERS, chain.geometry.n_bonds))
        for i, row in enumerate(rows):
            out[i] = row
        return out

    def site_parameters(self, chain) -> np.ndarray | None:
        """The engines' site parameter array (MAX_SITE_PARAMETERS, N): the site law's rows, then
        zeros; None for a model without a site law.

        Parameters
        ----------
        chain : Chain or KGLattice
            A lattice of the model's kind (``lattice``).

        Returns
        -------
        numpy.ndarray of shape (MAX_SITE_PARAMETERS, N), or None
            Row i the site parameter ``site.parameter_names[i]`` of every site, the rows beyond
            the law's zero; None without a site law.
        """
        return None if self.site is None else site_parameter_array(self.site.parameters(chain), chain.N)

    def __repr__(self) -> str:
        return f"Model({self.name})"


#: The kinds of lattice a model's parameters are read from (``Model.lattice``; a lattice class
#: names its kind in ``kind``), and how to make one.
LATTICES = {
    "beads": "a bead Chain: chainchaos.random_chain(seed, alpha, N), chain_from_radii(radii) or a chain file",
    "kg": "a KGLattice: chainchaos.kg_chain(seed, W, N)",
    "dnls": "a DNLSLattice: chainchaos.dnls_chain(seed, W, N, beta)",
}


class ModelType(types.Type):
    """The Numba type of a :class:`Model`: one per model identity (its name, and the modules and
    sources of its kernels), carrying no data at run time.

    Parameters
    ----------
    identity : str
        The model's :attr:`Model.identity`, ``name@modules:digest``.

    Attributes
    ----------
    identity : str
        As given.
    model_name : str
        The model's name, the part of ``identity`` before ``@``.
    """

    def __init__(self, identity: str):
        self.identity = identity
        self.model_name = identity.partition("@")[0]
        super().__init__(name=f"Model({identity})")


register_model(ModelType)(models.OpaqueModel)


@typeof_impl.register(Model)
def _typeof_model(value, context):
    return ModelType(value.identity)


@unbox(ModelType)
def _unbox_model(typ, obj, c):
    return NativeValue(c.context.get_constant_null(typ))


def _kernels(model_type) -> Model:
    return _BY_IDENTITY[model_type.identity]


@njit(cache=True)
def never_open(P, left, right):
    """The opening of a bond that cannot open: positive (1) for every finite displacement."""
    return left * 0.0 + 1.0


def bond_force(model, P, left, right):
    """f of the bond with parameters P between displacements left = u_{b-1} and right = u_b.

    A dispatcher for Numba-compiled code (it has no Python body): compiled with a model, it calls
    that model's ``force`` kernel.

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the kernel at compile time.
    P : tuple of float
        The bond's parameters (a column of ``Model.bond_parameters``).
    left, right : float or SIMD vector
        The displacements u_{b-1} and u_b of its two beads (units of delta_ref for a bead chain).

    Returns
    -------
    float or SIMD vector
        The bond force f (positive in compression), in the model's force unit.
    """


def bond_force_stiffness(model, P, left, right):
    """(f, k = df/dD) of the bond.

    A dispatcher for Numba-compiled code, as :func:`bond_force`.

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the kernel at compile time.
    P : tuple of float
        The bond's parameters.
    left, right : float or SIMD vector
        The displacements u_{b-1} and u_b.

    Returns
    -------
    tuple
        The force f and the stiffness k = df/dD of the bond (D = left - right).
    """


def bond_potential(model, P, left, right):
    """V of the bond (zero at rest).

    A dispatcher for Numba-compiled code, as :func:`bond_force`.

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the kernel at compile time.
    P : tuple of float
        The bond's parameters.
    left, right : float
        The displacements u_{b-1} and u_b.

    Returns
    -------
    float
        The bond's potential energy V(D), in the model's energy unit.
    """


def bond_opening(model, P, left, right):
    """A number that is negative where the bond is open (models without gaps: never).

    A dispatcher for Numba-compiled code, as :func:`bond_force`.

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the kernel at compile time.
    P : tuple of float
        The bond's parameters.
    left, right : float
        The displacements u_{b-1} and u_b.

    Returns
    -------
    float
        Negative where the bond is open; 1 for a model whose bonds never open.
    """


def _dispatch(stub, kernel_of):
    @overload(stub)
    def _select(model, P, left, right):
        if isinstance(model, ModelType):
            kernel = kernel_of(_kernels(model))
            return lambda model, P, left, right: kernel(P, left, right)


_dispatch(bond_force, lambda m: m.force)
_dispatch(bond_force_stiffness, lambda m: m.force_stiffness)
_dispatch(bond_potential, lambda m: m.potential)
_dispatch(bond_opening, lambda m: m.opening or never_open)


def site_kick(model, S, u, f):
    """The force on a bead whose two bonds give it f = f_n - f_{n+1}: f - w'(u) with its site
    law (parameters S, displacement u); f itself, unchanged, for a model without a site law.

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the site law at compile time.
    S : tuple of float
        The site's parameters (a column of ``Model.site_parameters``).
    u : float or SIMD vector
        The bead's displacement.
    f : float or SIMD vector
        The force of its two bonds.

    Returns
    -------
    float or SIMD vector
        The bead's total force.
    """


def site_kick_deviation(model, S, u, dq, g):
    """The tangent force on a bead whose bonds give it g = g_n - g_{n+1}: g - w''(u) dq with its
    site law; g itself for a model without one.

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the site law at compile time.
    S : tuple of float
        The site's parameters.
    u : float or SIMD vector
        The bead's displacement.
    dq : float or SIMD vector
        The bead's component of the deviation vector.
    g : float or SIMD vector
        The tangent force of its two bonds.

    Returns
    -------
    float or SIMD vector
        The bead's total tangent force.
    """


def add_site_energy(model, u, sites, H):
    """H + sum_n w(u_n) (summed in order, sites the (MAX_SITE_PARAMETERS, N) parameters); H itself
    for a model without a site law.

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the site law at compile time.
    u : numpy.ndarray of shape (N,)
        The displacements.
    sites : numpy.ndarray of shape (MAX_SITE_PARAMETERS, N)
        The site parameters (``Model.site_parameters``).
    H : float
        The energy so far (the bonds' and the kinetic), in the model's energy unit.

    Returns
    -------
    float
        H plus the on-site energy.
    """


def site_potential(model, S, u):
    """w(u) of one site (models with a site law only).

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        A model with a site law.
    S : tuple of float
        The site's parameters.
    u : float
        The site's displacement.

    Returns
    -------
    float
        The on-site potential energy w(u), zero at u = 0.
    """


def check_sites(model, sites):
    """Nothing at run time; a compile-time error where a model with a site law is given no site
    parameters (``sites`` None or omitted).

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model.
    sites : numpy.ndarray or None
        The site parameters given to the compiled function.

    Raises
    ------
    numba.core.errors.TypingError
        At compile time, for a model with a site law and no ``sites``.
    """


def _site_law(model_type) -> SiteLaw | None:
    return _kernels(model_type).site if isinstance(model_type, ModelType) else None


@overload(site_kick)
def _site_kick(model, S, u, f):
    if isinstance(model, ModelType):
        law = _site_law(model)
        if law is None:
            return lambda model, S, u, f: f
        kernel = law.force
        return lambda model, S, u, f: f - kernel(S, u)


@overload(site_kick_deviation)
def _site_kick_deviation(model, S, u, dq, g):
    if isinstance(model, ModelType):
        law = _site_law(model)
        if law is None:
            return lambda model, S, u, dq, g: g
        kernel = law.force_stiffness

        def with_site(model, S, u, dq, g):
            return g - kernel(S, u)[1] * dq

        return with_site


@overload(site_potential)
def _site_potential(model, S, u):
    if isinstance(model, ModelType) and _site_law(model) is not None:
        kernel = _site_law(model).potential
        return lambda model, S, u: kernel(S, u)


@overload(add_site_energy)
def _add_site_energy(model, u, sites, H):
    if isinstance(model, ModelType):
        law = _site_law(model)
        if law is None:
            return lambda model, u, sites, H: H
        kernel = law.potential

        def with_site(model, u, sites, H):
            for n in range(u.shape[0]):
                H += kernel((sites[0, n], sites[1, n]), u[n])
            return H

        return with_site


@overload(check_sites)
def _check_sites(model, sites):
    if isinstance(model, ModelType):
        if _site_law(model) is not None and isinstance(sites, (types.NoneType, types.Omitted)):
            raise TypingError(f"model {model.model_name!r} has a site law: pass its site parameters (sites)")
        return lambda model, sites: None
