"""Figures of the energy scan and the disorder statistics (issue 7), written byte-stably.

Both figures are drawn from the merged NetCDF files only (results/scan/energy_scan.nc and
results/scan/disorder_statistics.nc). The PDF carries no creation date and the PNG no software
tag, so a rerun on the same data gives the same bytes; files are written atomically.
"""

import numpy as np
from matplotlib.figure import Figure

from chainchaos.output.plotting.style import PAGE_WIDTH, context, model_colour, model_label
from chainchaos.paper.thresholds import PAPER_THRESHOLDS

ENERGY_LABEL = r"$H$"


def _paper_lines(ax, models, what):
    for m in models:
        H = PAPER_THRESHOLDS.get((m, what))
        if H is not None:
            ax.axvline(H, color=model_colour(m), ls=":", lw=0.8, alpha=0.8)


def energy_scan_figure(ds):
    """Four panels against H, both models: final P, final Lambda, final eta, largest number of
    simultaneous gaps; the delocalization and chaos criteria dashed, the paper's thresholds dotted."""
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 4.6), layout="constrained")
        axes = fig.subplots(2, 2, sharex=True)
        (aP, aL), (aE, aG) = axes
        models = [str(m) for m in ds.model.values]
        E = ds.energy.values
        t_f = float(ds.attrs["t_final"])
        for m in models:
            d = ds.sel(model=m)
            ok = d["valid"].values == 1
            kw = dict(color=model_colour(m), marker="o", ms=2.5, lw=0.9, label=model_label(m))
            aP.plot(E[ok], d["participation_final"].values[ok], **kw)
            aL.plot(E[ok], d["mlce_final"].values[ok], **{**kw, "mfc": "white"})
            chaotic = ok & (d["chaotic"].values == 1)
            aL.plot(E[chaotic], d["mlce_final"].values[chaotic], "o", color=model_colour(m), ms=2.5)
            aE.plot(E[ok], d["eta_final"].values[ok], **kw)
            if (d["max_gaps"].values >= 0).any():
                aG.plot(E[ok], d["max_gaps"].values[ok], drawstyle="steps-mid", **kw)
            if (~ok).any():
                aP.plot(E[~ok], np.ones((~ok).sum()), "x", color=model_colour(m), label=f"{model_label(m)}: invalid run")
        aP.axhline(ds.attrs["p_delocalized"], color="k", ls="--", lw=0.7,
                   label=rf"$\bar P = {ds.attrs['p_delocalized']:g}$ (delocalized above)")
        aL.axhline(np.log(t_f) / t_f, color="k", ls="--", lw=0.7,
                   label=r"$\ln t_f / t_f$ (regular orbit); filled: chaotic")
        for ax, what in ((aP, "delocalization"), (aE, "delocalization"), (aL, "chaos"), (aG, "chaos")):
            _paper_lines(ax, models, what)
        aP.set_ylabel(r"$\bar P$ (last decade)")
        aL.set_ylabel(r"$\Lambda(t_f)$")
        aL.set_yscale("log")
        aE.set_ylabel(r"$\bar\eta$ (last decade)")
        aG.set_ylabel("max. simultaneous gaps")
        for ax in axes.flat:
            ax.set_xscale("log")
        for ax in axes[1]:
            ax.set_xlabel(ENERGY_LABEL)
        aP.legend(loc="center left")
        aL.legend(loc="upper left")
        for ax, tag in zip(axes.flat, "abcd"):
            ax.set_title(f"({tag})", loc="left")
        fig.suptitle(rf"Energy scan, $t_f = {t_f:g}$ (dotted: the paper's thresholds)", fontsize=8)
    return fig


ONSET_LABELS = {"delocalization": "delocalization", "chaos": r"chaos ($\Lambda$)", "chaos_gali": "chaos (GALI)"}


def disorder_figure(ds):
    """Probability of delocalization and of chaos against H per model with Wilson 95% bands, and
    the spread of the onset times (median, 25-75% and 10-90% over the realizations)."""
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 2.4), layout="constrained")
        axes = fig.subplots(1, 3)
        models = [str(m) for m in ds.model.values]
        E = ds.energy.values
        q = list(np.round(ds["quantile"].values, 3))
        for ax, what in zip(axes[:2], ("delocalized", "chaotic")):
            for m in models:
                d = ds.sel(model=m)
                c = model_colour(m)
                ax.fill_between(E, d[f"probability_{what}_lower"].values, d[f"probability_{what}_upper"].values,
                                color=c, alpha=0.2, lw=0)
                ax.plot(E, d[f"probability_{what}"].values, "o-", color=c, ms=2.5, label=model_label(m))
                if what == "chaotic" and "probability_chaotic_gali" in d:
                    ax.plot(E, d["probability_chaotic_gali"].values, "s--", color=c, ms=2.5, mfc="white", lw=0.8,
                            label=f"{model_label(m)}, GALI$_{{{int(ds.attrs['gali_order'])}}}$")
            _paper_lines(ax, models, "delocalization" if what == "delocalized" else "chaos")
            ax.set_ylim(-0.03, 1.03)
            ax.set_xscale("log")
            ax.set_xlabel(ENERGY_LABEL)
            ax.set_ylabel(f"probability {what}")
        axes[0].legend(loc="upper left")
        if "probability_chaotic_gali" in ds:
            axes[1].legend(loc="upper left", fontsize=5.5, title=r"solid: $\Lambda$", title_fontsize=5.5)
        ax = axes[2]
        for m in models:
            for what, marker, shift in (("delocalization", "o", 0.95), ("chaos", "s", 1.0), ("chaos_gali", "D", 1.05)):
                if f"{what}_onset_quantiles" not in ds:
                    continue
                Q = ds[f"{what}_onset_quantiles"].sel(model=m).values
                med = Q[:, q.index(0.5)]
                ok = np.isfinite(med)
                if not ok.any():
                    continue
                x = E[ok] * shift
                c = model_colour(m)
                ax.vlines(x, Q[ok, q.index(0.1)], Q[ok, q.index(0.9)], color=c, lw=0.6)
                ax.vlines(x, Q[ok, q.index(0.25)], Q[ok, q.index(0.75)], color=c, lw=2.0, alpha=0.6)
                ax.plot(x, med[ok], marker, color=c, ms=3, ls="none", mfc=c if what == "delocalization" else "white",
                        label=f"{model_label(m)}, {ONSET_LABELS[what]}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(ENERGY_LABEL)
        ax.set_ylabel(r"onset time [$1/\omega_{\max}$]")
        if ax.get_legend_handles_labels()[0]:
            low, high = ax.get_ylim()
            ax.set_ylim(low / 30, high)  # room below the data for the legend
            ax.legend(loc="lower left", fontsize=5, ncols=2)
        for a, tag in zip(axes, "abc"):
            a.set_title(f"({tag})", loc="left")
        n_real = ds.sizes["realization"]
        fig.suptitle(rf"{n_real} realizations, $\alpha = {ds.attrs['alpha']:g}$, $t_f = {ds.attrs['t_final']:g}$; "
                     "bands: Wilson 95%", fontsize=8)
    return fig
