"""What a model given as exactly solvable parts is: an on-site rotation and the hopping.

A :class:`SplitModel` is a lattice Hamiltonian that is not T(p) + V(q) but splits into three
parts whose flows are exact (Skokos, Gerlach, Bodyfelt, Papamikos & Eggl, Phys. Lett. A 378, 1809
(2014)), in real canonical coordinates (q_l, p_l) of every site, x_l = q_l^2 + p_l^2:

    H = A + B + C,   A = sum_l a(x_l),   B = -sum_l q_l q_{l+1},   C = -sum_l p_l p_{l+1},

fixed ends (q = p = 0 beyond the lattice). A's flow turns every site at its own frequency
w = 2 a'(x), constant on the flow because A keeps every x_l: (q, p) -> (q cos wt + p sin wt,
p cos wt - q sin wt); B's shifts p_l by t (q_{l-1} + q_{l+1}), C's shifts q_l by
-t (p_{l-1} + p_{l+1}). A and B + C are invariant under a common phase, so the norm
S = sum_l x_l / 2 is conserved beside H. The disordered DNLS chain is one (``models.dnls``).

A model gives its on-site part as Numba kernels: ``frequency(S, x)``, the pair (w, g) with
w = 2 a'(x) and g = 2 dw/dx (so that dw = g (q dq + p dp): the tangent map of A), and
``onsite_energy(S, x)``, a(x); S is the tuple of the site's parameters (rows of one array, at
as many as the law needs), x the site's q^2 + p^2. The kernels run on floats and on the
batch engine's vectors (+ - * only), as a bond model's do. A split model is a Numba type like a
:class:`~chainchaos.system.models.base.Model`: the engine of ``chainchaos.engine.split``
compiles its kernels in.
"""

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numba import njit
from numba.extending import overload, typeof_impl

from chainchaos.errors import require
from chainchaos.system.models.base import (
    _BY_IDENTITY,
    LATTICES,
    ModelType,
    _kernel_identity,
    parameter_array,
    site_values,
)


@dataclass(frozen=True, eq=False, kw_only=True)
class SplitModel:
    """A model whose Hamiltonian splits into the on-site rotation A and the hopping B and C.

    Parameters
    ----------
    name : str
        The key in configs, file names and the registry ``MODELS``.
    label : str
        How figures and tables name it.
    colour : str
        The colour of its curves (a matplotlib colour).
    parameter_names : tuple of str
        Names of the site parameters (one or more), e.g. ``("eps", "beta")``.
    parameters : callable
        ``parameters(lattice)``: one array of length N per name.
    frequency : callable
        Numba kernel ``frequency(S, x)``: (w, g), the rotation frequency w = 2 a'(x) of a site
        with parameters S at x = q^2 + p^2 and g = 2 dw/dx.
    onsite_energy : callable
        Numba kernel ``onsite_energy(S, x)``: a(x), the site's part of H.
    description : str, optional
        The on-site law in one line, for documentation.
    lattice : str, optional
        The kind of lattice ``parameters`` reads (default ``"dnls"``).
    integrator : str, optional
        Its default scheme, a key of ``chainchaos.engine.split_schemes.SPLIT_SCHEMES``.

    Attributes
    ----------
    identity : str
        ``name@modules:digest`` of its kernels, as a Model's.
    """

    name: str
    label: str
    colour: str
    parameter_names: tuple[str, ...]
    parameters: Callable
    frequency: Callable
    onsite_energy: Callable
    description: str = ""
    lattice: str = "dnls"
    integrator: str = "s9ABC6"
    identity: str = field(init=False, repr=False, default="")

    #: A split model has no bond law: no bond opens, no site law is kicked.
    has_gaps: ClassVar[bool] = False
    has_site_law: ClassVar[bool] = False
    is_split: ClassVar[bool] = True

    def __post_init__(self):
        require(len(self.parameter_names) > 0, "parameter_names", self.parameter_names,
                "one or more site parameters")
        require(self.lattice in LATTICES, "lattice", self.lattice, f"one of {list(LATTICES)}")
        object.__setattr__(self, "identity", _kernel_identity(self.name, [self.frequency, self.onsite_energy]))
        _BY_IDENTITY[self.identity] = self

    @property
    def modules(self) -> str:
        """The modules that define the model's kernels, as its identity names them."""
        return self.identity.partition("@")[2].rpartition(":")[0]

    @property
    def bond_parameter_count(self) -> int:
        """Parameters per bond: none (every bond of a split model hops with unit strength)."""
        return 0

    @property
    def site_parameter_count(self) -> int:
        """The rows of :meth:`site_parameters`: the length of every site's tuple S."""
        return len(self.parameter_names)

    def site_parameters(self, lattice) -> np.ndarray:
        """The engines' site parameter array (parameters, N): one row per parameter name.

        Parameters
        ----------
        lattice : DNLSLattice
            A lattice of the model's kind.

        Returns
        -------
        numpy.ndarray of shape (len(parameter_names), N)
            Row i the parameter ``parameter_names[i]`` of every site.
        """
        return parameter_array(self.parameters(lattice), self.parameter_names, lattice.N,
                               f"model {self.name!r}: parameters(lattice)")

    def __repr__(self) -> str:
        return f"SplitModel({self.name})"


@typeof_impl.register(SplitModel)
def _typeof_split_model(value, context):
    return ModelType(value.identity)


def onsite_frequency(model, S, x):
    """(w, g) of a site with parameters S at x = q^2 + p^2: its rotation frequency and
    g = 2 dw/dx.

    A dispatcher for Numba-compiled code (it has no Python body): compiled with a split model, it
    calls that model's ``frequency`` kernel.

    Parameters
    ----------
    model : SplitModel
        The model, whose Numba type selects the kernel at compile time.
    S : tuple of float or of SIMD vectors
        The site's parameters.
    x : float or SIMD vector
        q^2 + p^2 of the site.

    Returns
    -------
    tuple
        (w, g).
    """


def onsite_energy(model, S, x):
    """a(x), the site's part of the Hamiltonian.

    A dispatcher for Numba-compiled code, as :func:`onsite_frequency`.

    Parameters
    ----------
    model : SplitModel
        The model.
    S : tuple of float
        The site's parameters.
    x : float
        q^2 + p^2 of the site.

    Returns
    -------
    float
        The on-site energy, in the model's energy unit.
    """


def _split_kernels(model_type) -> SplitModel | None:
    model = _BY_IDENTITY.get(model_type.identity) if isinstance(model_type, ModelType) else None
    return model if isinstance(model, SplitModel) else None


@overload(onsite_frequency)
def _onsite_frequency(model, S, x):
    split = _split_kernels(model)
    if split is not None:
        kernel = split.frequency
        return lambda model, S, x: kernel(S, x)


@overload(onsite_energy)
def _onsite_energy(model, S, x):
    split = _split_kernels(model)
    if split is not None:
        kernel = split.onsite_energy
        return lambda model, S, x: kernel(S, x)


@njit(cache=True)
def energy_kernel(model, q, p, sites, shape2):
    """H of one state (q, p) (N,) of a split model on the lattice ``shape2`` = (Nx, Ny)
    (``Geometry.shape2``), sites its (parameters, N) array: the on-site energies,
    then the hopping -(q_a q_b + p_a p_b) of every bond, along the lines, then across them,
    summed in order."""
    nx, ny = shape2
    H = 0.0
    for n in range(q.shape[0]):
        H += onsite_energy(model, site_values(model, sites, n), q[n] * q[n] + p[n] * p[n])
    for j in range(ny):
        for n in range(j * nx, (j + 1) * nx - 1):
            H -= q[n] * q[n + 1] + p[n] * p[n + 1]
    for n in range(q.shape[0] - nx):
        H -= q[n] * q[n + nx] + p[n] * p[n + nx]
    return H


@njit(cache=True)
def norm_kernel(q, p):
    """S = sum_l (q_l^2 + p_l^2) / 2 of one state, summed in order."""
    s = 0.0
    for n in range(q.shape[0]):
        s += q[n] * q[n] + p[n] * p[n]
    return 0.5 * s


def _states(*arrays):
    return [np.ascontiguousarray(a, dtype=float).reshape(-1, np.shape(a)[-1]) for a in arrays]


def split_energy(model: SplitModel, lattice, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """H of one state or many, (..., N) each: shape (...) (a NumPy float for one state).

    Parameters
    ----------
    model : SplitModel
        The model.
    lattice : DNLSLattice
        A lattice of its kind (its ``geometry`` says which sites are bonded).
    q, p : numpy.ndarray of shape (..., N)
        The real canonical coordinates, psi = (q + i p)/sqrt(2), the site on the last axis (in
        the geometry's flat order).

    Returns
    -------
    numpy.ndarray of shape (...)
        The total energy of every state, in the model's energy unit.
    """
    sites = model.site_parameters(lattice)
    Q, P = _states(q, p)
    shape2 = lattice.geometry.shape2
    out = np.array([energy_kernel(model, Q[i], P[i], sites, shape2) for i in range(Q.shape[0])])
    return out.reshape(np.shape(q)[:-1])[()]


def norm(q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """The norm S = sum_l |psi_l|^2 = sum_l (q_l^2 + p_l^2)/2 of one state or many (..., N).

    Parameters
    ----------
    q, p : numpy.ndarray of shape (..., N)
        The real canonical coordinates, the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (...)
        The norm of every state (a NumPy float for one state).
    """
    Q, P = _states(q, p)
    out = np.array([norm_kernel(Q[i], P[i]) for i in range(Q.shape[0])])
    return out.reshape(np.shape(q)[:-1])[()]
