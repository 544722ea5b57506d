"""A model of your own: the checks a model passes before the engines run it, and how it joins the registry.

A model (:class:`~chainchaos.system.models.base.Model`) defined in your own module is used by
passing it (``SceneParameters(model=MORSE, ...)``), by adding it (:func:`add_model`, after which
its name works everywhere in the process), or, from a study file or the command line, by naming
where it is defined: ``mypackage.models:MORSE`` (an importable module) or ``morse.py:MORSE`` (a
file, relative to the study file or the working directory) (:func:`load_model`). Each way runs
:func:`check_model` first, so a model that would give wrong numbers is refused with the failed
check named. Its compiled kernels are keyed by its identity (its name, the modules that define
its kernels and the digest of their sources: ``Model.identity``), so an edit recompiles and two
models of one name never share machine code.
"""

import importlib
import importlib.util
import re
import sys
from pathlib import Path

import numpy as np
from numba import njit
from numba.core.errors import TypingError

from chainchaos.errors import ParameterError
from chainchaos.kernels.simd import LANES, vload, vstore
from chainchaos.system.chain import kg_chain, random_chain
from chainchaos.system.models import MODELS, add_to_registry, require_free_name
from chainchaos.system.models.base import (
    Model,
    bond_force,
    bond_force_stiffness,
    bond_opening,
    bond_potential,
    bond_values,
    bond_vectors,
    site_kick,
    site_kick_deviation,
    site_potential,
    site_values,
    site_vectors,
)


class ModelCheckError(ParameterError):
    """A model that fails one of :func:`check_model`'s checks: the message names the model, the
    check and what was found.

    A :class:`~chainchaos.errors.ParameterError` (``name`` "model", ``value`` the model's name).

    Parameters
    ----------
    model : Model
        The model that fails.
    check : str
        The check it fails, a key of :data:`CHECKS`.
    found : str
        What the check found, in words.

    Attributes
    ----------
    check : str
        As given.
    """

    def __init__(self, model: Model, check: str, found: str):
        self.check = check
        super().__init__("model", model.name, f"a model that passes the check {check!r}; found {found}")


#: The checks of :func:`check_model`, in the order they run: name -> what it asks of the model.
CHECKS = {
    "parameters": "its parameters fill at most the engines' rows, finite, one value per bond (and per site)",
    "compiles": "its kernels compile with Numba for floats (each an @njit function)",
    "rest": "at zero displacement every bond has V = 0, the same force on every bond (no net force on a "
            "bead) and a positive stiffness; a site law has w = 0, w' = 0 and w'' >= 0",
    "force = dV/dD": "the bond force is the derivative of the bond potential (up to the force at rest), to "
                     "central differences",
    "stiffness = df/dD": "the bond stiffness is the derivative of the bond force",
    "site force = dw/du": "a site law's force w' is the derivative of its potential w, and w'' that of w'",
    "force alone": "force(P, left, right) is the force of force_stiffness, to the bit",
    "lanes": "the kernels compile for the batch engine's vectors (only + - *, max, np.sqrt or "
             "np.expm1) and give each lane its scalar result, to the bit",
}

_SIZE = 4 * LANES  # bonds of the sample lattice: whole vectors


def _sample_lattice(model: Model):
    """A lattice of ``model``'s kind with ``_SIZE`` bonds, and the scale of its displacements."""
    if model.lattice == "kg":
        return kg_chain(1, 4.0, _SIZE - 1), 0.3
    chain = random_chain(1, 5.0, _SIZE - 1)
    return chain, 0.3 * float(np.median(chain.delta))


@njit(cache=True)
def _scalar_laws(model, P, left, right, out):
    """Row 0..4: V, f, k, the force alone, the opening of every bond b at (left[b], right[b])."""
    for b in range(left.size):
        bond = bond_values(model, P, b)
        out[0, b] = bond_potential(model, bond, left[b], right[b])
        out[1, b], out[2, b] = bond_force_stiffness(model, bond, left[b], right[b])
        out[3, b] = bond_force(model, bond, left[b], right[b])
        out[4, b] = bond_opening(model, bond, left[b], right[b])


@njit(cache=True)
def _vector_laws(model, P, left, right, out):
    """Rows 1..4 of :func:`_scalar_laws` on the batch engine's vectors (the potential is scalar only)."""
    for i in range(0, left.size, LANES):
        bond = bond_vectors(model, P.reshape(P.size), i, P.shape[1])
        u, v = vload(left, i), vload(right, i)
        f, k = bond_force_stiffness(model, bond, u, v)
        vstore(out[1], i, f)
        vstore(out[2], i, k)
        vstore(out[3], i, bond_force(model, bond, u, v))
        vstore(out[4], i, bond_opening(model, bond, u, v))


@njit(cache=True)
def _scalar_sites(model, S, u, out):
    """Rows 0..2: w, w', w'' of every site at u (through the engines' site dispatchers)."""
    for n in range(u.size):
        site = site_values(model, S, n)
        out[0, n] = site_potential(model, site, u[n])
        out[1, n] = 0.0 - site_kick(model, site, u[n], 0.0)
        out[2, n] = 0.0 - site_kick_deviation(model, site, u[n], 1.0, 0.0)


@njit(cache=True)
def _vector_sites(model, S, u, out):
    """Rows 1..2 of :func:`_scalar_sites` on vectors."""
    for i in range(0, u.size, LANES):
        site = site_vectors(model, S.reshape(S.size), i, S.shape[1])
        x = vload(u, i)
        zero = x * 0.0
        vstore(out[1], i, zero - site_kick(model, site, x, zero))
        vstore(out[2], i, zero - site_kick_deviation(model, site, x, zero + 1.0, zero))


def _fail(model, check, found):
    raise ModelCheckError(model, check, found)


def _typing_detail(err: TypingError, kind: str = " vector") -> str:
    """The operation Numba found no (vector) version of, and where: from its typing error's text."""
    text = re.sub(r"\x1b\[[0-9;]*m", "", str(err))
    missing = re.findall(r">>> (.+)", text)
    where = re.findall(r"During: typing of [^\n]* at (\S+ \(\d+\))", text)
    what = f"{missing[-1].strip()} has no{kind} version" if missing else text.strip().splitlines()[-1][:200]
    return what + (f", at {where[0]}" if where else "")


def _site_laws(model, S, u):
    """Rows 0..2: w, w', w'' of sites with parameters ``S`` (one column each) at ``u``."""
    out = np.empty((3, u.size))
    _scalar_sites(model, np.ascontiguousarray(S), np.ascontiguousarray(u), out)
    return out


def _bond_laws(model, P, D):
    out = np.empty((5, D.size))
    _scalar_laws(model, P, np.ascontiguousarray(D), np.zeros(D.size), out)
    return out


def _derivative(law, x, rows, step: float):
    """The derivative of the elementwise ``law(rows, x)`` at ``x`` and its error estimate, by
    ``scipy.differentiate.derivative`` (adaptive: the step shrinks from ``step`` until its
    estimate stops improving). ``rows``: the parameters of each element, one row per parameter."""
    from scipy.differentiate import derivative

    def f(xi, *r):  # xi: the elements still iterating, at several steps each
        flat = np.ascontiguousarray(xi.ravel())
        return law(np.stack([np.broadcast_to(a, xi.shape).ravel() for a in r]), flat).reshape(xi.shape)

    res = derivative(f, x, args=tuple(rows), initial_step=step, tolerances={"atol": 0.0, "rtol": 1e-12})
    return res.df, res.error


def _close(analytic, numeric, error, scale) -> np.ndarray:
    """Where an analytic derivative agrees with a numerical one: within ten times the numerical
    one's own error estimate, or 1e-10 of ``scale`` (a derivative that is zero, or the last bits
    of a function of order ``scale``)."""
    return np.abs(analytic - numeric) <= 10.0 * error + 1e-10 * scale


def _check_bonds(model, lattice, scale):
    rows = model.parameters(lattice)
    if len(rows) != len(model.parameter_names):
        _fail(model, "parameters", f"{len(rows)} rows for parameter_names {model.parameter_names}")
    P = model.bond_parameters(lattice)
    if not np.all(np.isfinite(P)):
        _fail(model, "parameters", "non-finite bond parameters")
    try:
        rest = _bond_laws(model, P, np.zeros(_SIZE))
    except TypingError as err:
        raise ModelCheckError(model, "compiles", f"a bond kernel does not compile: {_typing_detail(err, '')}") from None
    V0, f0, k0 = rest[0], rest[1], rest[2]
    if np.any(np.abs(V0) > 1e-15 * (1 + np.abs(f0) * scale)) or np.any(np.abs(f0 - f0[0]) > 1e-14 * np.abs(f0[0])) or not np.all(k0 > 0):
        _fail(model, "rest", f"V(0) = {V0[:3]}, f(0) = {f0[:3]}, k(0) = {k0[:3]} on the first bonds")
    D = np.random.default_rng(0).uniform(-1.0, 1.0, _SIZE) * scale
    here = _bond_laws(model, P, D)
    f, k = here[1], here[2]
    force_scale = np.max(np.abs(f - f0)) + np.max(np.abs(f0))
    dV, dV_error = _derivative(lambda p, d: _bond_laws(model, p, d)[0], D, P, 1e-2 * scale)
    bad = ~_close(f - f0, dV, dV_error, force_scale)
    if bad.any():
        b = int(np.argmax(bad))
        _fail(model, "force = dV/dD", f"f - f(0) = {f[b] - f0[b]:.9g} against dV/dD = {dV[b]:.9g} at D = {D[b]:.6g}")
    df, df_error = _derivative(lambda p, d: _bond_laws(model, p, d)[1], D, P, 1e-2 * scale)
    bad = ~_close(k, df, df_error, np.max(np.abs(k)))
    if bad.any():
        b = int(np.argmax(bad))
        _fail(model, "stiffness = df/dD", f"k = {k[b]:.9g} against df/dD = {df[b]:.9g} at D = {D[b]:.6g}")
    if not np.array_equal(here[3], f):
        _fail(model, "force alone", "force differs from the force of force_stiffness")
    left, right = np.random.default_rng(1).normal(scale=scale, size=(2, _SIZE))
    scalar, vector = np.zeros((5, _SIZE)), np.zeros((5, _SIZE))
    _scalar_laws(model, P, left, right, scalar)
    try:
        _vector_laws(model, P, left, right, vector)
    except TypingError as err:
        raise ModelCheckError(model, "lanes", f"a bond kernel does not compile for vectors: {_typing_detail(err)}") from None
    if not np.array_equal(scalar[1:].view(np.int64), vector[1:].view(np.int64)):
        _fail(model, "lanes", "a lane of the vector bond law differs from its scalar result")


def _check_sites(model, lattice, scale):
    law = model.site
    rows = law.parameters(lattice)
    if len(rows) != len(law.parameter_names):
        _fail(model, "parameters", f"{len(rows)} site rows for parameter_names {law.parameter_names}")
    S = model.site_parameters(lattice)
    if not np.all(np.isfinite(S)):
        _fail(model, "parameters", "non-finite site parameters")
    S = np.ascontiguousarray(np.concatenate([S, S[:, -1:]], axis=1))  # whole vectors

    def laws(u):
        return _site_laws(model, S, u)

    try:
        rest = laws(np.zeros(_SIZE))
    except TypingError as err:
        raise ModelCheckError(model, "compiles", f"a site kernel does not compile: {_typing_detail(err, '')}") from None
    if np.any(rest[0] != 0.0) or np.any(rest[1] != 0.0) or np.any(rest[2] < 0):
        _fail(model, "rest", f"w(0) = {rest[0][:3]}, w'(0) = {rest[1][:3]}, w''(0) = {rest[2][:3]} on the first sites")
    u = np.random.default_rng(2).uniform(-1.0, 1.0, _SIZE) * scale
    here = laws(u)
    for row, name in ((1, "w'"), (2, "w''")):
        slope, error = _derivative(lambda p, x, row=row: _site_laws(model, p, x)[row - 1], u, S, 1e-2 * scale)
        bad = ~_close(here[row], slope, error, np.max(np.abs(here[row])))
        if bad.any():
            n = int(np.argmax(bad))
            _fail(model, "site force = dw/du", f"{name} = {here[row][n]:.9g} against the derivative {slope[n]:.9g} "
                                               f"at u = {u[n]:.6g}")
    x = np.random.default_rng(3).normal(scale=scale, size=_SIZE)
    scalar, vector = np.zeros((3, _SIZE)), np.zeros((3, _SIZE))
    _scalar_sites(model, S, x, scalar)
    try:
        _vector_sites(model, S, x, vector)
    except TypingError as err:
        raise ModelCheckError(model, "lanes", f"a site kernel does not compile for vectors: {_typing_detail(err)}") from None
    if not np.array_equal(scalar[1:].view(np.int64), vector[1:].view(np.int64)):
        _fail(model, "lanes", "a lane of the vector site law differs from its scalar result")


def check_model(model: Model) -> None:
    """Run every check of :data:`CHECKS` on ``model``'s kernels, on a sample lattice of its kind.

    Parameters
    ----------
    model : Model
        The model to check (its bond law, and its site law if it has one).

    Raises
    ------
    ModelCheckError
        Naming the first check that fails and what it found.

    Examples
    --------
    >>> from chainchaos import MODELS, check_model
    >>> check_model(MODELS["fput"])  # the package's models pass; compiles the checks once
    """
    if not isinstance(model, Model):
        raise ParameterError("model", model, "a chainchaos Model")
    lattice, scale = _sample_lattice(model)
    _check_bonds(model, lattice, scale)
    if model.has_site_law:
        _check_sites(model, lattice, scale)


def add_model(model: Model) -> Model:
    """Check ``model`` (:func:`check_model`) and add it to the registry ``MODELS``, so that its
    name works everywhere in this process (``SceneParameters``, studies, ``Problem``).

    Adding the same model again does nothing; a model whose name is taken by another model of
    another module, or by one of the package's models, is refused. The same model edited and
    defined again (same name, same modules) replaces the earlier one: its kernels recompile.

    Parameters
    ----------
    model : Model
        A model defined outside the package, e.g. in your own module.

    Returns
    -------
    Model
        ``model`` itself.

    Raises
    ------
    ModelCheckError
        When a check fails (the check is named).
    ParameterError
        When the name is taken by another model.
    """
    if MODELS.get(getattr(model, "name", None)) is model:
        return model
    require_free_name(model)
    check_model(model)
    add_to_registry(model)
    return model


_REFERENCE = re.compile(r"^(?P<where>[^:\s]+):(?P<name>[A-Za-z_][A-Za-z0-9_]*)$")


def _module_of_file(path: Path):
    """The module defined by the Python file ``path``, imported once per process under the file's
    stem (Numba's cache and ``Model.identity`` name kernels by their module)."""
    name = path.stem
    loaded = sys.modules.get(name)
    if loaded is not None and Path(getattr(loaded, "__file__", "") or "").resolve() == path.resolve():
        return loaded
    if loaded is not None:
        raise ParameterError("model", str(path), f"a file whose module name {name!r} is not taken by "
                                                 f"{getattr(loaded, '__file__', 'a loaded module')}")
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module


def load_model(model, relative_to: Path | str | None = None) -> Model:
    """The model ``model`` names, in the registry: a registered name (``"hertz"``), a ``Model``
    (added with :func:`add_model`), or where one is defined, ``"package.module:NAME"`` (an
    importable module) or ``"path/to/file.py:NAME"`` (a file, relative to ``relative_to`` if given
    and the file is there, else to the working directory).

    Parameters
    ----------
    model : str or Model
        The model or its reference.
    relative_to : path, optional
        The directory of the study file that names the model.

    Returns
    -------
    Model
        The registered model.

    Raises
    ------
    ParameterError
        For an unknown name, a reference that cannot be imported or does not name a Model, or a
        model that fails its checks (:class:`ModelCheckError`).
    """
    if isinstance(model, Model):
        return add_model(model)
    if not isinstance(model, str):
        raise ParameterError("model", model, f"a name among {sorted(MODELS)}, a Model, or 'module:NAME'")
    if model in MODELS:
        return MODELS[model]
    match = _REFERENCE.match(model)
    if match is None:
        raise ParameterError("model", model, f"a model of the registry {sorted(MODELS)}, or one of your own as "
                                             "'package.module:NAME' or 'file.py:NAME'")
    found, where = referenced(match, relative_to, "model", model)
    if not isinstance(found, Model):
        raise ParameterError("model", model, f"the name of a chainchaos Model in {where} (found {type(found).__name__})")
    return add_model(found)


def referenced(match, relative_to, key: str, reference: str):
    """The object a reference ``where:NAME`` names: ``NAME`` of the file ``where`` (``file.py``,
    relative to ``relative_to`` if given and the file is there, else to the working directory) or
    of the importable module ``where``. A model or an observable of one's own is looked up so.

    Parameters
    ----------
    match : re.Match
        :data:`_REFERENCE` matched on the reference.
    relative_to : path or None
        The folder of the study file that names it.
    key : str
        What the reference is for, as an error names it ("model", "observable").
    reference : str
        The reference as given.

    Returns
    -------
    found : object or None
        What the module calls ``NAME`` (None where it has no such name).
    where : str
        The file or module.

    Raises
    ------
    ParameterError
        Under ``key``, for a file that does not exist or a module that cannot be imported.
    """
    where, name = match["where"], match["name"]
    try:
        if where.endswith(".py"):
            path = Path(where)
            if relative_to is not None and (Path(relative_to) / path).is_file():
                path = Path(relative_to) / path
            if not path.is_file():
                raise ParameterError(key, reference, f"an existing Python file before ':' (no file {path})")
            module = _module_of_file(path)
        else:
            module = importlib.import_module(where)
    except ImportError as err:
        raise ParameterError(key, reference, f"an importable module before ':' ({err})") from None
    return getattr(module, name, None), where


__all__ = ["CHECKS", "ModelCheckError", "add_model", "check_model", "load_model"]
