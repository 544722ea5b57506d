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
batch engine (``chainchaos.engine.simd``), for which force and stiffness must use only + - *,
``max``, ``np.sqrt`` (or ``chainchaos.engine.sqrt.root``) and ``np.expm1`` (each lane then gets
exactly the scalar result).

A model is also a Numba type: passed to a compiled function it selects its kernels at compile
time (``bond_force`` and the other dispatchers below), so one engine source serves every model
and each model gets its own machine code, without a branch on the model in the inner loop.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numba import njit, types
from numba.extending import NativeValue, models, overload, register_model, typeof_impl, unbox

from chainchaos.errors import require

#: Rows of bond parameters the engines carry: a model may use up to this many.
MAX_BOND_PARAMETERS = 3

#: Every Model created, by name: what its Numba type compiles in (``_kernels``).
_BY_NAME: dict[str, "Model"] = {}


@dataclass(frozen=True, eq=False)
class Model:
    """A bond model: its identity, its parameters per bond and its Numba bond-law kernels."""

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

    def __post_init__(self):
        require(0 < len(self.parameter_names) <= MAX_BOND_PARAMETERS, "parameter_names",
                self.parameter_names, f"1 to {MAX_BOND_PARAMETERS} bond parameters")
        _BY_NAME[self.name] = self

    @property
    def has_gaps(self) -> bool:
        """Whether a bond of this model can open (lose contact) and carry no force."""
        return self.opening is not None

    def bond_parameters(self, chain) -> np.ndarray:
        """The engines' bond parameter array (MAX_BOND_PARAMETERS, N+1): the model's rows, then
        zeros."""
        rows = self.parameters(chain)
        out = np.zeros((MAX_BOND_PARAMETERS, chain.N + 1))
        for i, row in enumerate(rows):
            out[i] = row
        return out

    def __repr__(self) -> str:
        return f"Model({self.name})"


class ModelType(types.Type):
    """The Numba type of a :class:`Model`: one per model name, carrying no data at run time."""

    def __init__(self, name: str):
        self.model_name = name
        super().__init__(name=f"Model({name})")


register_model(ModelType)(models.OpaqueModel)


@typeof_impl.register(Model)
def _typeof_model(value, context):
    return ModelType(value.name)


@unbox(ModelType)
def _unbox_model(typ, obj, c):
    return NativeValue(c.context.get_constant_null(typ))


def _kernels(model_type) -> Model:
    return _BY_NAME[model_type.model_name]


@njit(cache=True, inline="always")
def never_open(P, left, right):
    """The opening of a bond that cannot open: positive (1) for every finite displacement."""
    return left * 0.0 + 1.0


def bond_force(model, P, left, right):
    """f of the bond with parameters P between displacements left = u_{b-1} and right = u_b."""


def bond_force_stiffness(model, P, left, right):
    """(f, k = df/dD) of the bond."""


def bond_potential(model, P, left, right):
    """V of the bond (zero at rest)."""


def bond_opening(model, P, left, right):
    """A number that is negative where the bond is open (models without gaps: never)."""


def _dispatch(stub, kernel_of):
    @overload(stub, inline="always")
    def _select(model, P, left, right):
        if isinstance(model, ModelType):
            kernel = kernel_of(_kernels(model))
            return lambda model, P, left, right: kernel(P, left, right)


_dispatch(bond_force, lambda m: m.force)
_dispatch(bond_force_stiffness, lambda m: m.force_stiffness)
_dispatch(bond_potential, lambda m: m.potential)
_dispatch(bond_opening, lambda m: m.opening or never_open)
