"""The Lyapunov spectrum of a scene over an ensemble of perturbed orbits.

Every orbit of the ensemble (``orbits.lane_factor``: lane 0 the scene's own, lane j >= 1 with u0
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

from chainchaos.observe.formulas import ks_entropy, lyapunov_spectrum
from chainchaos.output.provenance import provenance_attrs
from chainchaos.run import driver
from chainchaos.run.orbits import OrbitSettings, lane_factor
from chainchaos.system.initial import initial_deviation, initial_displacement
from chainchaos.system.models import get_model


def scene_spectra(chain, model: str, energy: float, site: int, settings: OrbitSettings, lanes: int,
                  progress=None) -> xr.Dataset:
    """The finite-time Lyapunov spectra (lane, time, exponent) of ``lanes`` perturbed orbits of the
    scene (``model`` at total energy ``energy``, bead ``site`` displaced), h_KS (lane, time), the
    relative energy error and, per exponent, the median over the lanes at the last sample."""
    m = get_model(model)
    problem = settings.problem(m, [chain] * lanes, tangent=True, track_gaps=False, spectrum=True)
    N, K = problem.N, problem.extra_vectors
    Q0, P0, DQ0, DP0 = (np.zeros((N, lanes)) for _ in range(4))
    XQ0, XP0 = np.zeros((K, N, lanes)), np.zeros((K, N, lanes))
    u0 = initial_displacement(m, problem.chains[0], float(energy), int(site))
    for j in range(lanes):
        Q0[site - 1, j] = u0 * lane_factor(j, settings)
        DQ0[:, j], DP0[:, j] = initial_deviation(N, settings.deviation_seed + j)
        XQ0[:, :, j], XP0[:, :, j] = replace(settings, deviation_seed=settings.deviation_seed + j).extra_deviations(problem)
    monitors = (driver.progress(progress),) if progress is not None else ()
    samples = driver.sample(problem, Q0, P0, DQ0, DP0, settings.sample_steps(), monitors=monitors,
                            xq0=XQ0, xp0=XP0)
    t = samples.times
    spectra = np.stack([lyapunov_spectrum(samples.spectrum_growth[j], t) for j in range(lanes)])
    one = {"units": "1"}
    ds = xr.Dataset(
        {
            "lyapunov_spectrum": (("lane", "time", "exponent"), spectra,
                                  {**one, "long_name": "finite-time Lyapunov exponent lambda_i(t)",
                                   "comment": "units of omega_max of the homogeneous linear chain"}),
            "ks_entropy": (("lane", "time"), ks_entropy(spectra),
                           {**one, "long_name": "Kolmogorov-Sinai entropy: sum of the positive exponents"}),
            "spectrum_final": ("exponent", np.median(spectra[:, -1], axis=0),
                               {**one, "long_name": "median over the lanes of lambda_i at the last sample"}),
            "energy_error": (("lane", "time"), samples.energy_error,
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
                    excited_site=int(site), N=int(N), integrator=settings.integrator, dt=float(settings.dt),
                    t_final=float(settings.t_final), perturbation=float(settings.perturbation),
                    max_energy_error=float(np.nanmax(samples.energy_error)),
                    seed=-1 if chain.seed is None else int(chain.seed))
    return ds
