"""chainchaos: chaos and Anderson localisation in disordered Hertzian and FPUT chains.

The physics core of the pipeline: disordered chains and their linear modes, the Hertz and FPUT
bond models, symplectic splitting integrators applied together with their tangent map, and the
observables of the paper, written as CF-style NetCDF through xarray.
"""

from chainchaos._numba_cache import configure_numba_cache

configure_numba_cache()

__version__ = "0.1.0"

from chainchaos.chain import Chain, chain_from_radii, random_chain  # noqa: E402
from chainchaos.linear import (  # noqa: E402
    ensemble_participation,
    mode_participation,
    normal_modes,
    participation_number,
)
from chainchaos.simulate import simulate  # noqa: E402

__all__ = [
    "Chain",
    "chain_from_radii",
    "random_chain",
    "normal_modes",
    "mode_participation",
    "participation_number",
    "ensemble_participation",
    "simulate",
    "__version__",
]
