"""The numbers of the Lyapunov spectra (``spectra.scene_spectra``) that the manuscript quotes, as
macros: the settings, and per scene lambda_1, h_KS and how well the exponents pair."""

import numpy as np

from chainchaos.records.formatting import tex_math, tex_number, tex_parameter
from chainchaos.system.models import model_label


def pairing_error(final: np.ndarray) -> float:
    """max_i |lambda_i + lambda_(2N+1-i)| / lambda_1 of one spectrum (0 for an exact Hamiltonian
    pairing; the finite-time exponents pair only up to O(1/t))."""
    return float(np.max(np.abs(final + final[::-1])) / final[0])


def spectra_macros(spectra: dict) -> dict[str, str]:
    """Macros ``spectra.*`` from the spectrum files (scene name -> Dataset): ``exponents``,
    ``lanes``, ``tfinal``, ``dt`` and ``summary``, a sentence with per scene the median over the
    orbits of lambda_1 and of h_KS and the largest pairing error of its orbits."""
    first = next(iter(spectra.values()))
    out = {"spectra.exponents": str(first.sizes["exponent"]), "spectra.lanes": str(first.sizes["lane"]),
           "spectra.tfinal": tex_parameter(first.attrs["t_final"]), "spectra.dt": tex_parameter(first.attrs["dt"])}
    parts = []
    for ds in spectra.values():
        final = ds["lyapunov_spectrum"].isel(time=-1).values  # (lane, exponent)
        lam1 = float(np.median(final[:, 0]))
        ks = float(np.median(ds["ks_entropy"].isel(time=-1).values))
        pairing = max(pairing_error(f) for f in final)
        parts.append(f"{model_label(ds.attrs['model'])} $H = {tex_parameter(ds.attrs['energy'])}$ has "
                     f"$\\lambda_1 = {tex_number(lam1)}$ and $h_\\mathrm{{KS}} = {tex_number(ks)}$, and "
                     f"every $|\\lambda_i + \\lambda_{{2N+1-i}}|$ is at most {tex_math(100 * pairing, 2)}\\,\\% "
                     f"of its $\\lambda_1$")
    out["spectra.summary"] = ("At the end of the run (medians over the orbits) " + "; ".join(parts)
                              + ": finite-time exponents pair up to $O(1/t)$.")
    return out
