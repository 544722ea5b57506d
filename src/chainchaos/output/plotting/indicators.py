"""The figure of the Lyapunov spectra (``spectra.scene_spectra``): lambda_i at the end of the run
against i/N, and h_KS against time, per scene, with the spread over its perturbed orbits."""

import numpy as np
from matplotlib.figure import Figure

from chainchaos.output.plotting.style import PAGE_WIDTH, context, model_colour, model_label


def spectra_figure(scenes: list):
    """(a) the finite-time exponents lambda_i(t_end) against i/N (median over the orbits, the band
    their range; the second half mirrors the first, lambda_(2N+1-i) = -lambda_i); (b) h_KS(t)."""
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 2.6), layout="constrained")
        a_spec, a_ks = fig.subplots(1, 2)
        for ds in scenes:
            colour = model_colour(ds.attrs["model"])
            label = f"{model_label(ds.attrs['model'])}, $H = {ds.attrs['energy']:g}$"
            N = int(ds.attrs["N"])
            final = ds["lyapunov_spectrum"].isel(time=-1).values  # (lane, exponent)
            x = ds["exponent"].values / N
            a_spec.fill_between(x, final.min(axis=0), final.max(axis=0), color=colour, alpha=0.25, lw=0)
            a_spec.plot(x, np.median(final, axis=0), ".-", color=colour, ms=2.5, lw=0.8, label=label)
            t = ds.time.values
            ks = ds["ks_entropy"].values
            ok = t > 0
            a_ks.fill_between(t[ok], ks[:, ok].min(axis=0), ks[:, ok].max(axis=0), color=colour, alpha=0.25, lw=0)
            a_ks.plot(t[ok], np.median(ks[:, ok], axis=0), color=colour, lw=1.0, label=label)
        a_spec.axhline(0.0, color="0.5", lw=0.5)
        a_spec.set_xlabel(r"$i/N$")
        a_spec.set_ylabel(r"$\lambda_i(t_{\rm end})$ [$\omega_{\max}$]")
        a_spec.legend(loc="upper right")
        a_ks.set_xscale("log")
        a_ks.set_yscale("log")
        a_ks.set_xlabel(r"$t$ [$1/\omega_{\max}$]")
        a_ks.set_ylabel(r"$h_{\rm KS}$ [$\omega_{\max}$]")
        for ax, tag in zip((a_spec, a_ks), "ab"):
            ax.set_title(f"({tag})", loc="left")
        first = scenes[0]
        fig.suptitle(rf"Lyapunov spectra, {first.sizes['lane']} orbits per scene (median; band: range), "
                     rf"$t_{{\rm end}} = {first.attrs['t_final']:g}$", fontsize=8)
    return fig
