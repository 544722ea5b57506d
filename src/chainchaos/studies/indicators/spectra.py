"""The Lyapunov spectrum of a scene over an ensemble of perturbed orbits.

Every orbit of the ensemble (``orbits.integrate`` with ``spectrum``: lane 0 the scene's own, lane j >= 1 with u0
perturbed at the ``perturbation`` level and its deviation vectors from ``deviation_seed + j``)
carries 2N deviation vectors (``RunSettings.exponents`` = 0) kept orthonormal by modified
Gram-Schmidt every ``check_every`` steps, so that lambda_i(t) = (1/t) sum ln R_ii
(docs/conventions.md#chaos-indicators). The lanes fill the SIMD block a single orbit would leave
mostly empty, and their spread says how far the finite-time exponents are from converged. The
Kolmogorov-Sinai entropy h_KS is the sum of the positive exponents (Pesin). Units: exponents and
h_KS in omega_max, times in 1/omega_max.
"""

from dataclasses import replace

import numpy as np
import xarray as xr

from chainchaos.errors import require
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate


def scene_spectra(chain, model: str, energy: float, site: int, settings: OrbitSettings, lanes: int,
                  progress=None) -> xr.Dataset:
    """The finite-time Lyapunov spectra (lane, time, exponent) of ``lanes`` perturbed orbits of the
    scene (``model`` at total energy ``energy``, bead ``site`` displaced), h_KS (lane, time), the
    relative energy error and, per exponent, the median over the lanes at the last sample. The
    orbits run through ``orbits.integrate`` with ``spectrum`` on; ``progress(done, total)``."""
    settings = replace(settings, spectrum=True)
    orbits = [Orbit(model=model, energy=energy, chain=chain, site=site, lane=lane) for lane in range(lanes)]
    t, runs = integrate(orbits, settings, progress)
    require(all(r["valid"] for r in runs), "scene", f"{model} at H = {energy:g}",
            f"orbits with an initial state whose energy error stays <= {settings.max_energy_error:g}")
    spectra = np.stack([r["lyapunov_spectrum"] for r in runs])
    one = {"units": "1"}
    ds = xr.Dataset(
        {
            "lyapunov_spectrum": (("lane", "time", "exponent"), spectra,
                                  {**one, "long_name": "finite-time Lyapunov exponent lambda_i(t)",
                                   "comment": "units of omega_max of the homogeneous linear chain"}),
            "ks_entropy": (("lane", "time"), np.stack([r["ks_entropy"] for r in runs]),
                           {**one, "long_name": "Kolmogorov-Sinai entropy: sum of the positive exponents"}),
            "spectrum_final": ("exponent", np.median(spectra[:, -1], axis=0),
                               {**one, "long_name": "median over the lanes of lambda_i at the last sample"}),
            "energy_error": (("lane", "time"), np.stack([r["energy_error"] for r in runs]),
                             {**one, "long_name": "relative energy error |H(t) - H(0)|/H(0)"}),
        },
        coords={"lane": ("lane", np.arange(lanes), {"units": "1", "long_name": "orbit of the ensemble, 0 the scene's own"}),
                "time": ("time", t, {"units": "1", "long_name": "time",
                                     "comment": "nondimensional time, unit 1/omega_max of the homogeneous linear chain"}),
                "exponent": ("exponent", np.arange(1, spectra.shape[-1] + 1),
                             {"units": "1", "long_name": "index i of lambda_i, decreasing order"})},
    )
    ds.attrs.update(provenance_attrs({"model": model, "energy": float(energy), "site": int(site), "lanes": int(lanes),
                                      "settings": vars(settings)}))
    ds.attrs.update(title=f"Lyapunov spectra of {model} at H = {energy:g}", model=model, energy=float(energy),
                    excited_site=int(site), N=int(chain.N), integrator=settings.integrator, dt=float(settings.dt),
                    t_final=float(settings.t_final), perturbation=float(settings.perturbation),
                    max_energy_error=float(max(np.nanmax(r["energy_error"]) for r in runs)),
                    seed=-1 if chain.seed is None else int(chain.seed))
    return ds
