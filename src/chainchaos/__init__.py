"""chainchaos: chaos and Anderson localisation in disordered Hertzian and FPUT chains.

The physics core of the pipeline: disordered chains and their linear modes, the Hertz and FPUT
bond models, symplectic splitting integrators applied together with their tangent map, and the
observables of the paper, written as CF-style NetCDF through xarray.
"""

from chainchaos.engine.cache import configure_numba_cache

configure_numba_cache()

__version__ = "0.1.0"

#: The package's public names: (module, attribute), imported on first use, so that a job that
#: draws a panel need not load the engines. The registries are where a new model, scheme,
#: observable, statement, panel or claim is one entry (docs/architecture.md).
_EXPORTS = {
    "Chain": ("chainchaos.system.chain", "Chain"),
    "chain_from_radii": ("chainchaos.system.chain", "chain_from_radii"),
    "random_chain": ("chainchaos.system.chain", "random_chain"),
    "normal_modes": ("chainchaos.system.linear", "normal_modes"),
    "mode_participation": ("chainchaos.system.linear", "mode_participation"),
    "participation_number": ("chainchaos.system.linear", "participation_number"),
    "ensemble_participation": ("chainchaos.system.linear", "ensemble_participation"),
    "Problem": ("chainchaos.system.problem", "Problem"),
    "RunSettings": ("chainchaos.run.settings", "RunSettings"),
    "SceneParameters": ("chainchaos.run.scenes", "SceneParameters"),
    "simulate": ("chainchaos.run.scenes", "simulate"),
    "sample": ("chainchaos.run.driver", "sample"),
    "run_study": ("chainchaos.studies.study", "run_study"),
    "load_study": ("chainchaos.studies.study.spec", "load_study"),
    "MODELS": ("chainchaos.system.models", "MODELS"),
    "SCHEMES": ("chainchaos.engine.integrators", "SCHEMES"),
    "OBSERVABLES": ("chainchaos.observe.registry", "REGISTRY"),
    "PANELS": ("chainchaos.paper.panels", "PANELS"),
    "STATEMENTS": ("chainchaos.paper.statements", "STATEMENTS"),
    "CLAIMS": ("chainchaos.paper.claims.catalogue", "CATALOGUE"),
}
__all__ = [*_EXPORTS, "__version__"]


def __getattr__(name):
    if name in _EXPORTS:
        import importlib

        module, attribute = _EXPORTS[name]
        value = getattr(importlib.import_module(module), attribute)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'chainchaos' has no attribute {name!r}")
