"""What a bond model is, and how the Numba engines call it.

A model is one :class:`Model` (a module of ``chainchaos.system.models`` each, listed in its registry).
Bond b (0-based, b = 0..N) joins beads b-1 and b, with u_{-1} = u_N = 0 the walls; its
compression is D_b = u_{b-1} - u_b and bead n obeys m_n u_n'' = f_n - f_{n+1}, with f the bond
force (positive in compression) of the model's law. A model gives, per bond, its parameters as
rows of one array (as many as its law needs, computed from the chain), and Numba
kernels of the bond law ``force(P, left, right)``, ``force_stiffness(P, left, right)`` (f and
k = df/dD), ``potential(P, left, right)`` (V, zero at rest) and, for a model whose bonds can
open, ``opening(P, left, right)`` (negative where the bond is open). P is the tuple of the bond's
parameters, ``left`` and ``right`` the displacements u_{b-1} and u_b: floats, or vectors of the
batch engine (``chainchaos.kernels.simd``), for which force and stiffness must use only + - *,
``max``, ``np.sqrt`` and ``np.expm1`` (each lane then gets
exactly the scalar result).

A model may also have a site law (:class:`SiteLaw`): an on-site potential w(u) of each bead, with
its own parameters per site (rows of one array, as many as the law needs, computed from
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

import functools
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
from chainchaos.kernels.simd import vload

#: Every Model created, by identity (:attr:`Model.identity`): what its Numba type compiles in
#: (``_kernels``).
_BY_IDENTITY: dict[str, "Model"] = {}


def parameter_array(rows, names, n: int, what: str) -> np.ndarray:
    """The engines' parameter array of a model's bonds or sites: one row per parameter name.

    Parameters
    ----------
    rows : sequence of numpy.ndarray or float
        What the model's ``parameters(lattice)`` returned: one row of n values (or one value for
        all) per name.
    names : tuple of str
        The parameters' names, one per row.
    n : int
        The number of bonds or sites.
    what : str
        Who returned ``rows``, for the error (e.g. ``"model 'kg': site.parameters(lattice)"``).

    Returns
    -------
    numpy.ndarray of shape (len(names), n)
        Row i is ``rows[i]``, as float64, C-contiguous.

    Raises
    ------
    ParameterError
        Where ``rows`` has another length than ``names``.
    """
    require(len(rows) == len(names), what, f"{len(rows)} rows", f"one row per parameter name, {list(names)}")
    out = np.zeros((len(rows), n))
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
        Names of the site parameters (one or more), e.g. ``("eps",)``.
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
        require(len(self.parameter_names) > 0, "site parameter_names", self.parameter_names,
                "one or more site parameters")


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
        Names of the bond parameters (one or more: as many as the kernels read, derived
        constants included, so that the kernels need no division).
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
        require(len(self.parameter_names) > 0, "parameter_names", self.parameter_names,
                "one or more bond parameters")
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

    @property
    def bond_parameter_count(self) -> int:
        """The rows of :meth:`bond_parameters`: the length of every bond's tuple P."""
        return len(self.parameter_names)

    @property
    def site_parameter_count(self) -> int:
        """The rows of :meth:`site_parameters` (0 without a site law): the length of every
        site's tuple S."""
        return 0 if self.site is None else len(self.site.parameter_names)

    def bond_parameters(self, chain) -> np.ndarray:
        """The engines' bond parameter array (parameters, bonds): one row per parameter name; a
        chain's N + 1 bonds, a square lattice's in the order of ``geometry.bonds()``.

        Parameters
        ----------
        chain : Chain or KGLattice
            A lattice of the model's kind (``lattice``).

        Returns
        -------
        numpy.ndarray of shape (len(parameter_names), bonds)
            Row i the parameter ``parameter_names[i]`` of every bond, in the units the model's
            law reads them.
        """
        return parameter_array(self.parameters(chain), self.parameter_names, chain.geometry.n_bonds,
                               f"model {self.name!r}: parameters(lattice)")

    def site_parameters(self, chain) -> np.ndarray | None:
        """The engines' site parameter array (parameters, N): one row per site parameter name;
        None for a model without a site law.

        Parameters
        ----------
        chain : Chain or KGLattice
            A lattice of the model's kind (``lattice``).

        Returns
        -------
        numpy.ndarray of shape (len(site.parameter_names), N), or None
            Row i the site parameter ``site.parameter_names[i]`` of every site; None without a
            site law.
        """
        if self.site is None:
            return None
        return parameter_array(self.site.parameters(chain), self.site.parameter_names, chain.N,
                               f"model {self.name!r}: site.parameters(lattice)")

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


# ---- a bond's and a site's parameters as the tuple its kernels read --------------------------
# A model has as many parameters per bond (and per site) as its law needs. Numba builds a tuple
# of a length fixed at compile time: the length is the model's, read from its type, and the
# tuple is built by appending one load at a time (``_gather``). The engines keep each kind of
# parameter in its own array, in one of two layouts: a 2D array (parameters, bonds), read one
# float per row (``bond_values``, ``site_values``), or a flat array of SIMD vectors, parameter
# r of an element at ``at + r stride`` (``bond_vectors``, ``site_vectors``).


@njit(cache=True)
def _value(A, r, at, stride):
    """Row r of a 2D array at column ``at`` (``stride`` unused)."""
    return A[r, at]


@njit(cache=True)
def _vector(A, r, at, stride):
    """The SIMD vector of a flat array at ``at + r stride``."""
    return vload(A, at + r * stride)


@functools.cache
def _gather(count: int, load):
    """A compiled ``take(A, at, stride)`` -> ``(load(A, 0, at, stride), ...,
    load(A, count - 1, at, stride))``: the empty tuple for ``count`` 0."""
    take = njit(lambda A, at, stride: ())
    for r in range(count):
        take = _append(take, load, r)
    return take


def _append(take, load, r: int):
    """``take``, with the load of row r appended to its tuple."""
    return njit(lambda A, at, stride: take(A, at, stride) + (load(A, r, at, stride),))


def _parameter_count(model_type, kind: str) -> int:
    return getattr(_kernels(model_type), f"{kind}_parameter_count")


def bond_values(model, A, b):
    """The tuple P of bond b's parameters, ``(A[0, b], ..., A[n - 1, b])`` with n the model's
    count (``Model.bond_parameter_count``).

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model, whose Numba type gives the length of the tuple at compile time.
    A : numpy.ndarray of shape (parameters, bonds)
        The bond parameters (``Model.bond_parameters``).
    b : int
        The bond.

    Returns
    -------
    tuple of float
        The bond's parameters, as its kernels read them.
    """


def site_values(model, A, n):
    """The tuple S of site n's parameters, ``(A[0, n], ...)``, one per site parameter of the
    model (the empty tuple without a site law).

    A dispatcher for Numba-compiled code, as :func:`bond_values`.

    Parameters
    ----------
    model : Model or SplitModel
        The model, whose Numba type gives the length of the tuple at compile time.
    A : numpy.ndarray of shape (parameters, N), or None
        The site parameters (``Model.site_parameters``); None for a model without a site law
        (its tuple is empty: nothing is read).
    n : int
        The site.

    Returns
    -------
    tuple of float
        The site's parameters, as its kernels read them.
    """


def bond_vectors(model, A, at, stride):
    """The tuple P of a bond's parameters on the SIMD lanes: parameter r the vector of the flat
    array A at ``at + r stride``, one per bond parameter of the model.

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model, whose Numba type gives the length of the tuple at compile time.
    A : numpy.ndarray of shape (n,)
        The engine's flat array of bond parameters.
    at : int
        Where the bond's first parameter vector starts (an element index).
    stride : int
        Elements from one parameter's vector to the next's.

    Returns
    -------
    tuple of SIMD vectors
        The bond's parameters, as its kernels read them.
    """


def site_vectors(model, A, at, stride):
    """The tuple S of a site's parameters on the SIMD lanes, as :func:`bond_vectors` (the empty
    tuple without a site law).

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model or SplitModel
        The model, whose Numba type gives the length of the tuple at compile time.
    A : numpy.ndarray of shape (n,)
        The engine's flat array of site parameters.
    at : int
        Where the site's first parameter vector starts (an element index).
    stride : int
        Elements from one parameter's vector to the next's.

    Returns
    -------
    tuple of SIMD vectors
        The site's parameters, as its kernels read them.
    """


def _dispatch_values(stub, kind: str):
    @overload(stub)
    def _select(model, A, n):
        if isinstance(model, ModelType):
            take = _gather(_parameter_count(model, kind), _value)
            return lambda model, A, n: take(A, n, 0)


def _dispatch_vectors(stub, kind: str):
    @overload(stub)
    def _select(model, A, at, stride):
        if isinstance(model, ModelType):
            take = _gather(_parameter_count(model, kind), _vector)
            return lambda model, A, at, stride: take(A, at, stride)


def parameter_counts(model):
    """(parameters per bond, parameters per site) of the model, constants at compile time (a
    model without a site law has none per site).

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model or SplitModel
        The model.

    Returns
    -------
    tuple of int
        ``(bond_parameter_count, site_parameter_count)``.
    """


@overload(parameter_counts)
def _parameter_counts(model):
    if isinstance(model, ModelType):
        counts = (_parameter_count(model, "bond"), _parameter_count(model, "site"))
        return lambda model: counts


_dispatch_values(bond_values, "bond")
_dispatch_values(site_values, "site")
_dispatch_vectors(bond_vectors, "bond")
_dispatch_vectors(site_vectors, "site")


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
    """H + sum_n w(u_n) (summed in order, sites the (parameters, N) array); H itself
    for a model without a site law.

    A dispatcher for Numba-compiled code (it has no Python body).

    Parameters
    ----------
    model : Model
        The model, whose Numba type selects the site law at compile time.
    u : numpy.ndarray of shape (N,)
        The displacements.
    sites : numpy.ndarray of shape (parameters, N)
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
                H += kernel(site_values(model, sites, n), u[n])
            return H

        return with_site


@overload(check_sites)
def _check_sites(model, sites):
    if isinstance(model, ModelType):
        if _site_law(model) is not None and isinstance(sites, (types.NoneType, types.Omitted)):
            raise TypingError(f"model {model.model_name!r} has a site law: pass its site parameters (sites)")
        return lambda model, sites: None
