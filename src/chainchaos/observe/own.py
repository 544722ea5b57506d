"""An observable of one's own: a function of the sampled run, in one file, named in a study file.

A file defines an :class:`~chainchaos.observe.registry.Observable` with dims ``("time",)``, e.g.

    from chainchaos.observe.registry import Observable
    ANISOTROPY = Observable(name="anisotropy", dims=("time",), long_name="...", label=r"$A$",
                            compute=lambda run: ...)

and a study names it among its ``observables`` as ``"file.py:ANISOTROPY"`` (a file, relative to the
study file's folder, else to the working directory) or ``"package.module:ANISOTROPY"``, as it
names a model of its own. :func:`load_observable` imports it, checks what it is and registers it
under its name (``observe.registry.REGISTRY``): the study's jobs then keep it per orbit beside the
package's series. A study runs it on a short orbit of its model before it integrates anything
(``studies.study.spec``): a compute that fails, or does not give one float per sample (NaN where it
is not defined, as Lambda at t = 0), is named then.
``compute(run)`` gets a :class:`~chainchaos.observe.registry.SampledRun` (its states ``Q``, ``P``
(S, N), ``density``, ``times``, its lattice ``run.chain`` and ``run.chain.geometry``).
"""

from chainchaos.errors import require
from chainchaos.observe.registry import REGISTRY, Observable

#: The observables of one's own registered in this process, by name: the reference each came from.
OWN: dict[str, str] = {}


def is_reference(name: str) -> bool:
    """Whether an entry of a study's ``observables`` names an observable of one's own
    (``where:NAME``) rather than one of the registry."""
    from chainchaos.engine.model_checks import _REFERENCE

    return isinstance(name, str) and name not in REGISTRY and _REFERENCE.match(name) is not None


def load_observable(reference: str, relative_to=None) -> Observable:
    """The observable ``reference`` names (``"file.py:NAME"`` or ``"package.module:NAME"``),
    checked and registered under its name.

    Parameters
    ----------
    reference : str
        Where it is defined.
    relative_to : path, optional
        The folder of the study file that names it.

    Returns
    -------
    Observable
        The registered observable.

    Raises
    ------
    ParameterError
        For a reference that cannot be imported or names no Observable, one that is not a time
        series, or a name the registry already gives another observable.
    """
    from chainchaos.engine.model_checks import _REFERENCE, referenced

    match = _REFERENCE.match(reference) if isinstance(reference, str) else None
    require(match is not None, "observable", reference, "a name of the registry, or 'file.py:NAME' or 'module:NAME'")
    found, where = referenced(match, relative_to, "observable", reference)
    require(isinstance(found, Observable), "observable", reference,
            f"the name of a chainchaos Observable in {where} (found {type(found).__name__})")
    require(found.dims == ("time",) and not found.needs - {"tangent", "norm"}, "observable", reference,
            "an Observable with dims ('time',) that needs at most the tangent map (a series of the study's orbits)")
    known = REGISTRY.get(found.name)
    require(known is None or OWN.get(found.name) == reference, "observable", reference,
            f"a name the registry does not give another observable (not {found.name!r})")
    REGISTRY[found.name] = found
    OWN[found.name] = reference
    return found


__all__ = ["OWN", "is_reference", "load_observable"]
