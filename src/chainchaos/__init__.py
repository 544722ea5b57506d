"""chainchaos: chaos and Anderson localisation in disordered nonlinear chains.

Disordered lattices and their linear modes; the Hertz, FPUT, Toda and harmonic bead chains, the
Klein-Gordon lattice and models of your own; symplectic splitting integrators applied together
with their tangent map; the chaos indicators and spreading observables, written as CF-style NetCDF
through xarray; and the observables of the paper the pipeline reproduces.

Importing the package sets two process-wide environment variables
(chainchaos.kernels.cache.configure_numba_cache), which Numba reads when it is first imported; a
variable already set is left as it is:

- ``NUMBA_DISABLE_INTEL_SVML=1``: Numba does not call Intel's SVML vector maths (used when
  ``intel-cmplr-lib-rt`` happens to be installed), whose results depend on the CPU, so that the
  kernels give the same numbers, to the bit, on every x86-64 CPU.
- ``NUMBA_CACHE_DIR``: Numba's on-disk cache of compiled kernels, in a directory keyed by the
  kernels' source: ``<project>/.numba_cache/<key>`` in a checkout (every job of the pipeline reuses
  the kernels compiled once), ``~/.cache/chainchaos/numba/<key>`` for an installed package.

Other Numba code that the process runs afterwards sees them too.
"""

from chainchaos.kernels.cache import configure_numba_cache

configure_numba_cache()

__version__ = "0.1.0"

#: The package's public names: (module, attribute), imported on first use, so that a job that
#: draws a panel need not load the engines. The registries are where a new model, scheme,
#: observable, statement, panel or claim is one entry (docs/architecture.md).
_EXPORTS = {
    "Chain": ("chainchaos.system.chain", "Chain"),
    "chain_from_radii": ("chainchaos.system.chain", "chain_from_radii"),
    "random_chain": ("chainchaos.system.chain", "random_chain"),
    "KGLattice": ("chainchaos.system.chain", "KGLattice"),
    "kg_chain": ("chainchaos.system.chain", "kg_chain"),
    "DNLSLattice": ("chainchaos.system.chain", "DNLSLattice"),
    "dnls_chain": ("chainchaos.system.chain", "dnls_chain"),
    "normal_modes": ("chainchaos.system.linear", "normal_modes"),
    "mode_participation": ("chainchaos.system.linear", "mode_participation"),
    "participation_number": ("chainchaos.system.linear", "participation_number"),
    "ensemble_participation": ("chainchaos.system.linear", "ensemble_participation"),
    "Problem": ("chainchaos.engine.problem", "Problem"),
    "RunSettings": ("chainchaos.run.settings", "RunSettings"),
    "SceneParameters": ("chainchaos.run.scenes", "SceneParameters"),
    "simulate": ("chainchaos.run.scenes", "simulate"),
    "sample": ("chainchaos.run.driver", "sample"),
    "run_study": ("chainchaos.studies.study", "run_study"),
    "load_study": ("chainchaos.studies.study.spec", "load_study"),
    "MODELS": ("chainchaos.system.models", "MODELS"),
    "Model": ("chainchaos.system.models.base", "Model"),
    "SiteLaw": ("chainchaos.system.models.base", "SiteLaw"),
    "add_model": ("chainchaos.engine.model_checks", "add_model"),
    "check_model": ("chainchaos.engine.model_checks", "check_model"),
    "load_model": ("chainchaos.engine.model_checks", "load_model"),
    "SCHEMES": ("chainchaos.engine.integrators", "SCHEMES"),
    "SPLIT_SCHEMES": ("chainchaos.engine.split_schemes", "SPLIT_SCHEMES"),
    "SplitModel": ("chainchaos.system.models.split", "SplitModel"),
    "OBSERVABLES": ("chainchaos.observe.registry", "REGISTRY"),
    "PANELS": ("chainchaos.paper.panels", "PANELS"),
    "STATEMENTS": ("chainchaos.paper.statements", "STATEMENTS"),
    "CLAIMS": ("chainchaos.paper.claims.catalogue", "CATALOGUE"),
}
__all__ = [*_EXPORTS, "__version__"]


def __dir__():
    """The module's own names and the public names imported on first use (tab completion)."""
    return sorted(set(globals()) | set(_EXPORTS))


def __getattr__(name):
    if name in _EXPORTS:
        import importlib

        module, attribute = _EXPORTS[name]
        value = getattr(importlib.import_module(module), attribute)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'chainchaos' has no attribute {name!r}")
