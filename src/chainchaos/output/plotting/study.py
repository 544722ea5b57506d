"""A study's standard figures, drawn from its statistics file alone (byte-stable, as every figure).

- ``spreading``: <log10 m2> and <log10 P> against log10 t, one colour per energy, the band
  between the quartiles over realizations shaded; below, the running slope of <log10 m2>;
- ``chaos``: <log10 Lambda> against log10 t with the t^-1 law of a regular orbit, and its
  running slope (-1 regular; dotted, the published slope the study's laws name, else the
  weak-chaos literature's -0.25);
- ``fractions``: the fractions of realizations chaotic (by Lambda, and by GALI_k where kept) and
  delocalized against H, with Wilson 95% bands;
- ``maps``: the density of one orbit (the first valid realization) at the study's map times, as images on a
  logarithmic colour scale (a square lattice), or as profiles on a logarithmic axis (a chain);
- the comparison of several studies: <log10 m2>, <log10 P> and <log10 Lambda> of each (study,
  model, energy) on common axes.
One column of panels per model.
"""

import textwrap

import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure
from matplotlib.ticker import FixedLocator, NullLocator

from chainchaos.output.plotting.style import (
    MAP_CMAP,
    MAP_FLOOR,
    PAGE_WIDTH,
    amount_symbol,
    context,
    model_colour,
    model_label,
    scene_label,
    time_text,
)
from chainchaos.system.models import get_model

LOG_T = r"$\log_{10} t$"
#: Under the time axis of a figure whose models have different time units.
TIME_UNITS_NOTE = "each model in its own time unit"
ENERGY_COLOURS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666")
STUDY_STYLES = ("-", "--", ":", "-.")
#: The verdicts counted in the fractions figure: variable, label, colour, marker.
FRACTIONS = (("chaotic", r"chaotic ($\Lambda$)", "#d95f02", "o"),
             ("chaotic_gali", r"chaotic (GALI$_k$)", "#7570b3", "s"),
             ("delocalized", "delocalized", "#1b9e77", "^"))


def _title(fig, title: str, models: int) -> None:
    if title:
        fig.suptitle(textwrap.fill(title, 48 * models), fontsize="medium")


def _log_t(stats):
    t = stats["time"].values
    with np.errstate(divide="ignore"):
        return np.where(t > 0, np.log10(np.where(t > 0, t, 1.0)), np.nan)


def _energy_colour(k: int) -> str:
    return ENERGY_COLOURS[k % len(ENERGY_COLOURS)]


def _columns(stats, rows: int, height: float):
    models = [str(m) for m in stats.model.values]
    fig = Figure(figsize=(min(PAGE_WIDTH, 3.4 * len(models) + 0.4), height * rows), layout="constrained")
    axes = np.atleast_2d(fig.subplots(rows, len(models), sharex=True, squeeze=False))
    return fig, models, axes


def _mean_with_band(ax, x, stats, name, model, k, energy, label=True):
    mean = stats[f"mean_log10_{name}"].sel(model=model).isel(energy=k).values
    q = stats[f"quantile_log10_{name}"].sel(model=model).isel(energy=k)
    colour = _energy_colour(k)
    ax.fill_between(x, q.sel(quantile=0.25).values, q.sel(quantile=0.75).values, color=colour, alpha=0.18, lw=0)
    ax.plot(x, mean, color=colour, lw=1.0, label=f"${amount_symbol(model)} = {energy:g}$" if label else None)


def _labelled_line(ax, y: float, color: str, ls: str, text: str = "{y:.3g}", below: bool = False) -> None:
    """A published slope or a threshold: a horizontal line with ``text`` (by default its value)
    written above it (``below``: under it) at the right edge."""
    ax.axhline(y, color=color, ls=ls, lw=0.7)
    ax.annotate(text.format(y=y), (1.0, y), xycoords=("axes fraction", "data"), fontsize="x-small", ha="right",
                va="top" if below else "bottom")


def _crossover(ax, x, stats, model) -> None:
    """A crossover of <log10 m2> the study names (``laws.crossovers``): the bootstrap band of the
    local derivative over realizations and the published slopes; nothing without one."""
    if "crossover_slope" not in stats or "second_moment" not in stats["crossover"].values:
        return
    c = list(stats["crossover"].values).index("second_moment")
    for k in range(stats.energy.size):
        band = stats.sel(model=model).isel(energy=k, crossover=c)
        lower, upper = band["crossover_lower"].values, band["crossover_upper"].values
        on_grid = np.isfinite(lower) & np.isfinite(upper)  # the log-spaced samples the band is computed on
        ax.fill_between(x[on_grid], lower[on_grid], upper[on_grid], color=_energy_colour(k), alpha=0.25, lw=0,
                        label="95% band over realizations" if k == 0 else None)
    lines = stats["crossover_lines"].isel(crossover=c).values
    for line in lines:
        _labelled_line(ax, line, color="k", ls="--")
    bottom, top = ax.get_ylim()
    ax.set_ylim(bottom, max(top, max(lines) + 0.1 * (max(lines) - bottom)))  # room for the top line's label
    ax.legend(fontsize="x-small", loc="lower right")  # the labels of the lines stand at the right, above them


def spreading_figure(stats, title: str = ""):
    """<log10 m2>, <log10 P> and the running slope of <log10 m2> against log10 t, per model."""
    with context():
        fig, models, axes = _columns(stats, 3, 1.9)
        x = _log_t(stats)
        for c, model in enumerate(models):
            for k, energy in enumerate(stats.energy.values):
                _mean_with_band(axes[0, c], x, stats, "second_moment", model, k, energy)
                _mean_with_band(axes[1, c], x, stats, "participation", model, k, energy, label=False)
                axes[2, c].plot(x, stats["slope_log10_second_moment"].sel(model=model).isel(energy=k).values,
                                color=_energy_colour(k), lw=1.0)
            axes[0, c].set_title(model_label(model))
            axes[0, c].set_ylabel(r"$\langle \log_{10} m_2 \rangle$")
            axes[1, c].set_ylabel(r"$\langle \log_{10} P \rangle$")
            axes[2, c].set_ylabel(r"$d\langle \log_{10} m_2\rangle / d\log_{10} t$")
            axes[2, c].axhline(0.0, color="k", lw=0.5)
            _crossover(axes[2, c], x, stats, model)
            axes[2, c].set_xlabel(LOG_T)
        axes[0, 0].legend(fontsize="small", title="lines: mean; bands: quartiles", title_fontsize="small")
        _title(fig, title, len(models))
    return fig


def chaos_figure(stats, title: str = ""):
    """<log10 Lambda> against log10 t with the regular t^-1 law, and its running slope, per model,
    with the published slope where the study's laws name one (``published_slope_mlce``) and the
    study's chaos threshold (attribute ``chaos_slope``: an orbit whose slope over the last decade
    exceeds it is chaotic by Lambda)."""
    with context():
        fig, models, axes = _columns(stats, 2, 2.3)
        x = _log_t(stats)
        for c, model in enumerate(models):
            for k, energy in enumerate(stats.energy.values):
                _mean_with_band(axes[0, c], x, stats, "mlce", model, k, energy)
                axes[1, c].plot(x, stats["slope_log10_mlce"].sel(model=model).isel(energy=k).values,
                                color=_energy_colour(k), lw=1.0)
            finite = np.isfinite(x)
            x0 = x[finite][0] if finite.any() else 0.0
            y0 = np.nanmax(stats["mean_log10_mlce"].sel(model=model).values[..., finite][..., 0])
            axes[0, c].plot(x[finite], y0 - (x[finite] - x0), color="k", ls="--", lw=0.7,
                            label=r"$\propto t^{-1}$ (regular)")
            axes[1, c].axhline(-1.0, color="k", ls="--", lw=0.7)
            if "published_slope_mlce" in stats:
                _labelled_line(axes[1, c], float(stats["published_slope_mlce"]), color="0.4", ls=":")
            if "chaos_slope" in stats.attrs:
                _labelled_line(axes[1, c], float(stats.attrs["chaos_slope"]), color="#d95f02", ls="-.",
                               text="chaotic above {y:.3g}", below=True)
            axes[0, c].set_title(model_label(model))
            axes[0, c].set_ylabel(r"$\langle \log_{10} \Lambda \rangle$")
            axes[1, c].set_ylabel(r"$d\langle \log_{10}\Lambda\rangle / d\log_{10} t$")
            axes[1, c].set_xlabel(LOG_T)
        axes[0, 0].legend(fontsize="small")
        _title(fig, title, len(models))
    return fig


def _criteria(stats) -> dict:
    """The thresholds behind the fractions (the statistics' attributes), as legend text."""
    a = stats.attrs
    return {"chaotic": rf" slope $> {a['chaos_slope']:g}$" if "chaos_slope" in a else "",
            "chaotic_gali": rf" $< {a['gali_threshold']:g}$" if "gali_threshold" in a else "",
            "delocalized": rf" $P > {a['p_delocalized']:g}$" if "p_delocalized" in a else ""}


def fractions_figure(stats, title: str = ""):
    """Fractions of realizations chaotic and delocalized against H, with Wilson 95% bands; the
    legend names each verdict's threshold (over the last decade: the slope of log Lambda, GALI_k,
    the time-averaged P)."""
    criteria = _criteria(stats)
    flags = [(flag, label + criteria[flag], colour, marker) for flag, label, colour, marker in FRACTIONS
             if f"fraction_{flag}" in stats]
    with context():
        fig, models, axes = _columns(stats, 1, 2.6)
        E = stats.energy.values
        for c, model in enumerate(models):
            ax = axes[0, c]
            for flag, label, colour, marker in flags:
                s = stats.sel(model=model)
                f = s[f"fraction_{flag}"].values
                # the Wilson bounds can sit an ulp on the wrong side of 0 or 1 from the fraction
                err = np.clip(np.vstack([f - s[f"fraction_{flag}_lower"].values,
                                         s[f"fraction_{flag}_upper"].values - f]), 0.0, None)
                ax.errorbar(E, f, yerr=err, marker=marker, ms=3, lw=0.9, capsize=2, label=label, color=colour)
            ax.set_xscale("log")
            ax.xaxis.set_major_locator(FixedLocator(E))
            ax.xaxis.set_minor_locator(NullLocator())
            ax.set_xticklabels([f"{e:g}" for e in E])
            ax.set_ylim(-0.05, 1.05)
            ax.set_xlabel(f"${amount_symbol(model)}$")
            ax.set_ylabel("fraction of realizations")
            ax.set_title(model_label(model))
        axes[0, 0].legend(fontsize="small", title="over the last decade; Wilson 95% bands", title_fontsize="small")
        _title(fig, title, len(models))
    return fig


def comparison_figure(named_stats: dict, title: str = ""):
    """<log10 m2>, <log10 P> and <log10 |Lambda|> of several studies ({name: statistics}) on common
    axes: colour by model, line style by study, the lightest line the lowest energy."""
    series = (("second_moment", r"$\langle \log_{10} m_2 \rangle$"), ("participation", r"$\langle \log_{10} P \rangle$"),
              ("abs_mlce", r"$\langle \log_{10} |\Lambda| \rangle$"))  # |Lambda|: a linear control's may be <= 0
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 3.3), layout="constrained")
        axes = fig.subplots(1, len(series), sharex=True)
        for s, (name, stats) in enumerate(named_stats.items()):
            x = _log_t(stats)
            for model in (str(m) for m in stats.model.values):
                n = stats.energy.size
                for k, energy in enumerate(stats.energy.values):
                    kw = {"color": model_colour(model), "ls": STUDY_STYLES[s % len(STUDY_STYLES)], "lw": 0.9,
                          "alpha": 0.45 + 0.55 * (k + 1) / n}
                    for i, (ax, (variable, _)) in enumerate(zip(axes, series)):
                        label = f"{name}: {scene_label(model, energy)}" if i == 0 else None
                        ax.plot(x, stats[f"mean_log10_{variable}"].sel(model=model).isel(energy=k).values,
                                label=label, **kw)
        kinds = {get_model(str(m)).lattice for stats in named_stats.values() for m in stats.model.values}
        for ax, (_, ylabel) in zip(axes, series):
            ax.set_xlabel(LOG_T if len(kinds) == 1 else LOG_T + "\n" + TIME_UNITS_NOTE)
            ax.set_ylabel(ylabel)
        fig.legend(loc="outside lower center", ncol=3, fontsize="x-small")  # below: it hides no curve
        _title(fig, title, 2)
    return fig


def _map_extent(maps: np.ndarray, shape: tuple) -> tuple[slice, slice]:
    """The smallest square about the lattice's centre holding every site of ``maps`` (flat, over
    the last axis) at or above MAP_FLOOR, and 2 sites more: the packet, not the empty lattice."""
    nx, ny = shape
    above = np.nanmax(maps.reshape(-1, ny, nx), axis=0) >= MAP_FLOOR
    j, i = np.nonzero(above)
    if i.size == 0:
        return slice(0, nx), slice(0, ny)
    ci, cj = (nx - 1) / 2, (ny - 1) / 2
    r = int(np.ceil(max(np.abs(i - ci).max(), np.abs(j - cj).max()))) + 2
    return (slice(max(int(ci) - r, 0), min(int(np.ceil(ci)) + r + 1, nx)),
            slice(max(int(cj) - r, 0), min(int(np.ceil(cj)) + r + 1, ny)))


def maps_figure(stats, title: str = ""):
    """The density of one orbit (``shown_density_map``: the first valid realization's) at each map
    time: a row per (model, energy), a column per
    time; on a square lattice an image of sites (i, j) on a log colour scale from MAP_FLOOR to 1
    (one colour bar), on a chain the profile on a logarithmic axis."""
    maps = stats["shown_density_map"]
    shape = tuple(int(n) for n in np.ravel(stats.attrs.get("lattice_shape", [maps.sizes["site"]])))
    rows = [(str(m), k, float(e)) for m in stats.model.values for k, e in enumerate(stats.energy.values)]
    times = maps["map_time"].values
    with context():
        if len(shape) == 1:
            fig = Figure(figsize=(PAGE_WIDTH, 1.0 + 2.0 * len(rows)), layout="constrained")
            axes = np.atleast_1d(fig.subplots(len(rows), 1, squeeze=False)[:, 0])
            n = np.arange(1, shape[0] + 1)
            for ax, (model, k, energy) in zip(axes, rows):
                for t, profile in zip(times, maps.sel(model=model).isel(energy=k).values):
                    ax.semilogy(n, np.clip(profile, MAP_FLOOR, None), lw=0.8, label=f"$t = {time_text(t)}$")
                ax.set_ylim(MAP_FLOOR, 1.0)
                ax.set_xlabel("site $n$")
                ax.set_ylabel(LABELS_DENSITY[get_model(model).is_split])
                ax.set_title(scene_label(model, energy), fontsize="small")
            axes[0].legend(fontsize="x-small")
        else:
            fig = Figure(figsize=(PAGE_WIDTH, 1.0 + 1.9 * len(rows)), layout="constrained")
            axes = fig.subplots(len(rows), times.size, squeeze=False)
            norm = LogNorm(MAP_FLOOR, 1.0)
            xs, ys = _map_extent(maps.values, shape)
            image = None
            for r, (model, k, energy) in enumerate(rows):
                for c, t in enumerate(times):
                    z = maps.sel(model=model).isel(energy=k, map_time=c).values.reshape(shape[1], shape[0])
                    ax = axes[r, c]
                    # i to the right, j up, sites counted from 1 as m2 counts them
                    image = ax.imshow(np.clip(z[ys, xs], MAP_FLOOR, None), norm=norm, cmap=MAP_CMAP, origin="lower",
                                      interpolation="nearest", extent=(xs.start + 0.5, xs.stop + 0.5,
                                                                       ys.start + 0.5, ys.stop + 0.5))
                    ax.set_title(f"$t = {time_text(t)}$" + (f"\n{scene_label(model, energy)}" if c == 0 else ""),
                                 fontsize="small")
                    ax.set_xlabel("$i$")
                    if c == 0:
                        ax.set_ylabel("$j$")
            bar = fig.colorbar(image, ax=axes, shrink=0.9, aspect=30)
            bar.set_label(LABELS_DENSITY[get_model(rows[0][0]).is_split])
        _title(fig, title, 2)
    return fig


#: The colour bar's label: a bond model's energy density, a split model's norm density.
LABELS_DENSITY = {False: r"energy density $h_n$", True: r"norm density $z_n$"}


def study_figure(kind: str, stats, title: str = ""):
    """The study figure ``kind`` (one of :data:`FIGURES`)."""
    return {"spreading": spreading_figure, "chaos": chaos_figure, "fractions": fractions_figure,
            "maps": maps_figure}[kind](stats, title)
