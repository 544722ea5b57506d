"""chainchaos: chaos and Anderson localisation in disordered Hertzian and FPUT chains.

The physics core of the pipeline: disordered chains and their linear modes, the Hertz and FPUT
bond models, symplectic splitting integrators applied together with their tangent map, and the
observables of the paper, written as CF-style NetCDF through xarray.
"""

from chainchaos._numba_cache import configure_numba_cache

configure_numba_cache()

__version__ = "0.1.0"

#: The package's public names and the modules that define them, imported on first use: a job
#: that draws a panel need not load the engines.
_EXPORTS = {
    "Chain": "chainchaos.chain",
    "chain_from_radii": "chainchaos.chain",
    "random_chain": "chainchaos.chain",
    "normal_modes": "chainchaos.linear",
    "mode_participation": "chainchaos.linear",
    "participation_number": "chainchaos.linear",
    "ensemble_participation": "chainchaos.linear",
    "simulate": "chainchaos.simulate",
}
__all__ = [*_EXPORTS, "__version__"]


def __getattr__(name):
    if name in _EXPORTS:
        import importlib

        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'chainchaos' has no attribute {name!r}")
