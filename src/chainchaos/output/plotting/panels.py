"""Every kind of panel of the paper (panels.KIND_OBSERVABLES) as a function drawing into an Axes.

``draw_<kind>(ax, *datasets, **options)`` takes the Datasets of the data contract
(docs/conventions.md#data-contract): the ensemble Dataset for ``ensemble_participation``, the chain
Dataset for ``chain_spectrum``, and scene Datasets for the others (several only for ``participation`` and ``mlce``). The options are
those of the panel table ``panels.PANELS``. Time axes are logarithmic, so the sample t = 0 is left out.
"""

import matplotlib
import matplotlib.patheffects as path_effects
import numpy as np
import xarray as xr
from matplotlib.colors import LogNorm, Normalize, to_rgb
from matplotlib.figure import Figure
from matplotlib.ticker import LogLocator, MaxNLocator, NullLocator

from chainchaos.output.plotting import style
from chainchaos.paper import panels

LOWESS_FRACTION = 0.08  # share of the samples in each local fit (about half a decade at 40 per decade)
LOWESS_MIN_SAMPLES = 5
MAP_BAR_SHRINK = 0.92  # colour-bar height / map height

# --------------------------------------------------------------------------- helpers


def _after_start(data):
    """The samples at t > 0 of a Dataset or DataArray (a logarithmic time axis cannot show t = 0)."""
    return data.isel(time=np.flatnonzero(data.time.values > 0))


def _log_edges(t: np.ndarray) -> np.ndarray:
    """Cell edges around log-spaced sample times: geometric midpoints, mirrored at both ends."""
    if t.size < 2:
        raise ValueError(f"a map needs at least two samples after t = 0, got {t.size}")
    mid = np.sqrt(t[:-1] * t[1:])
    return np.concatenate(([t[0] ** 2 / mid[0]], mid, [t[-1] ** 2 / mid[-1]]))


def _index_edges(index: np.ndarray) -> np.ndarray:
    """Cell edges around consecutive integers (sites, bonds, modes)."""
    return np.concatenate((index - 0.5, [index[-1] + 0.5]))


def _index_locator():
    """Ticks of a site, bond or mode axis: a few round integers (10, 20, 30, 40 for N = 40)."""
    return MaxNLocator(nbins=5, integer=True, steps=[1, 2, 5, 10])


def _sparse_log_ticks(axis) -> None:
    """A few labelled decades and no minor ticks: the log axes of densities span eight decades."""
    axis.set_major_locator(LogLocator(numticks=5))
    axis.set_minor_locator(NullLocator())


def _time_axis(ax, t_min: float, t_max: float) -> None:
    ax.set_xscale("log")
    ax.set_xlim(t_min, t_max)
    ax.set_xlabel(style.TIME_LABEL)
    # Every second decade labelled once a run spans more than four: readable in narrow panels.
    ax.xaxis.set_major_locator(LogLocator(numticks=5))


def _draw_map(ax, values: xr.DataArray, y_dim: str, norm, cmap: str, colour_label: str,
              y_label: str) -> None:
    """``values(time, y_dim)`` as a colour map, time (log) to the right, with a colour bar."""
    values = _after_start(values).transpose("time", y_dim)
    t_edges = _log_edges(values.time.values)
    # Rasterised: a PDF viewer draws an image, not ten thousand cells.
    mesh = ax.pcolormesh(t_edges, _index_edges(values[y_dim].values), values.values.T, norm=norm,
                         cmap=cmap, shading="flat", rasterized=True)
    _time_axis(ax, t_edges[0], t_edges[-1])
    ax.set_ylabel(y_label)
    ax.yaxis.set_major_locator(_index_locator())
    # A bar a little shorter than the map, level with its bottom: the label of the top tick stays
    # below the map's top edge, clear of a panel title that reaches over the bar in a narrow panel.
    bar = ax.figure.colorbar(mesh, ax=ax, pad=0.02, fraction=0.08, aspect=25, shrink=MAP_BAR_SHRINK,
                             anchor=(0.0, 0.0))
    bar.set_label(colour_label)
    if isinstance(norm, LogNorm):
        _sparse_log_ticks(bar.ax.yaxis)


def _log_density_map(ax, values: xr.DataArray, y_dim: str, colour_label: str, y_label: str) -> None:
    """A density normalised to 1 on a logarithmic colour scale from MAP_FLOOR to 1 (values
    below the floor, zeros among them, take the floor's colour)."""
    clipped = values.clip(min=style.MAP_FLOOR)
    _draw_map(ax, clipped, y_dim, LogNorm(style.MAP_FLOOR, 1.0), style.MAP_CMAP, colour_label,
                     y_label)


def _lighten(colour: str, amount: float) -> tuple:
    rgb = np.array(to_rgb(colour))
    return tuple(rgb + (1.0 - rgb) * amount)


def _scene_styles(datasets) -> list[dict]:
    """Line colour, style and label of each scene of a panel: the model's colour, and per model
    the highest energy in full colour and solid, lower ones lighter with other dash patterns."""
    styles = []
    for ds in datasets:
        model, energy = ds.attrs["model"], float(ds.attrs["energy"])
        higher = sum(1 for other in datasets
                     if other.attrs["model"] == model and float(other.attrs["energy"]) > energy)
        rank = min(higher, len(style.ENERGY_LINESTYLES) - 1)
        styles.append({"color": _lighten(style.model_colour(model), style.ENERGY_SHADES[rank]),
                       "linestyle": style.ENERGY_LINESTYLES[rank],
                       "label": style.scene_label(model, energy)})
    return styles


def _scene_title(ax, ds: xr.Dataset) -> None:
    ax.set_title(style.scene_label(ds.attrs["model"], float(ds.attrs["energy"])))


def _smoothed_curve(ax, t: np.ndarray, y: np.ndarray, color, linestyle="-", label=None) -> None:
    """LOWESS smoothing of y against log10 t, with the raw values faintly behind it."""
    from statsmodels.nonparametric.smoothers_lowess import lowess  # only the panels that smooth load it

    ax.plot(t, y, color=color, linewidth=0.5, alpha=style.RAW_ALPHA)
    fraction = max(LOWESS_FRACTION, LOWESS_MIN_SAMPLES / t.size)  # short runs: still a real fit
    fit = lowess(y, np.log10(t), frac=fraction, return_sorted=True)
    ax.plot(10.0 ** fit[:, 0], fit[:, 1], color=color, linestyle=linestyle, linewidth=1.2, label=label)


def _legend_above_data(ax, ncol: int = 1, room: float = 0.3) -> None:
    """Legend at the top left, in headroom added above the data so that it covers no curve; a
    fixed place also keeps PDF and PNG alike (loc="best" may choose differently per renderer)."""
    bottom, top = ax.get_ylim()
    ax.set_ylim(bottom, top + room * (top - bottom))
    ax.legend(loc="upper left", ncol=ncol)


def _time_range(datasets) -> tuple[float, float]:
    times = np.concatenate([_after_start(ds).time.values for ds in datasets])
    return times.min(), times.max()


def _nearest_sample(t: np.ndarray, wanted: float) -> int:
    """Index of the sample (t > 0) nearest to ``wanted`` in log t: samples are log-spaced."""
    return int(np.argmin(np.abs(np.log(t) - np.log(wanted))))


def _profile_line(i: int) -> dict:
    """Colour and dash of the i-th DVD profile time, the same on the map and the profiles."""
    return {"color": style.PROFILE_COLOURS[i % len(style.PROFILE_COLOURS)],
            "linestyle": style.PROFILE_LINESTYLES[i % len(style.PROFILE_LINESTYLES)]}


def _profile_samples(ds: xr.Dataset, times) -> list[tuple[float, int | None]]:
    """For each wanted time the index into the t > 0 samples, or None if beyond the run's end."""
    t = _after_start(ds).time.values
    end = t[-1] * (1.0 + 1e-9)
    return [(wanted, None if wanted > end else _nearest_sample(t, wanted)) for wanted in times]


# --------------------------------------------------------------------------- Fig. 1


def draw_ensemble_participation(ax, ensemble: xr.Dataset) -> None:
    """Mean participation number of the modes sorted in descending order against rank k, with
    standard-deviation error bars, one curve per disorder strength alpha (Fig. 1a)."""
    alphas = ensemble.alpha.values
    colours = matplotlib.colormaps["plasma"](np.linspace(0.0, 0.85, alphas.size))
    for alpha, colour in zip(alphas, colours):
        mean = ensemble.mean_participation.sel(alpha=alpha)
        std = ensemble.std_participation.sel(alpha=alpha)
        ax.errorbar(ensemble["rank"].values, mean.values, yerr=std.values, color=colour, marker="o",
                    markersize=2, linewidth=0.8, elinewidth=0.5, capsize=1.2,
                    label=rf"$\alpha = {alpha:g}$")
    ax.set_xlabel(style.RANK_LABEL)
    ax.set_ylabel(style.MEAN_P_LABEL)
    ax.set_ylim(bottom=0)
    ax.legend(ncol=2, loc="upper right")


def draw_chain_spectrum(ax, chain: xr.Dataset, inset_mode: int = 34) -> None:
    """The chain's linear frequencies against mode number (Fig. 1b); an inset shows the profile
    of mode ``inset_mode`` against site, with its participation number."""
    modes = chain.mode.values
    if inset_mode not in modes:
        raise ValueError(f"inset_mode = {inset_mode} is not a mode of the chain (modes 1..{modes.max()})")
    ax.plot(modes, chain.frequency.values, "o", color="black", markersize=2.5)
    ax.plot([inset_mode], chain.frequency.sel(mode=inset_mode).values, "o", markersize=5,
            markerfacecolor="none", markeredgecolor=style.HERTZ_RED, markeredgewidth=0.9)
    ax.set_xlabel(style.MODE_LABEL)
    ax.set_ylabel(style.FREQUENCY_LABEL)
    ax.set_ylim(bottom=0)

    shape = chain.mode_shape.sel(mode=inset_mode).values
    shape = shape * np.sign(shape[np.argmax(np.abs(shape))])  # sign is arbitrary: peak up
    participation = float(chain.mode_participation.sel(mode=inset_mode))
    inset = ax.inset_axes([0.12, 0.56, 0.46, 0.38])
    inset.plot(chain.site.values, shape, "-o", color=style.HERTZ_RED, markersize=1.5, linewidth=0.7)
    inset.set_xlabel(r"$n$", labelpad=1)
    inset.set_ylabel(rf"$U_{{n,{inset_mode}}}$", labelpad=1)
    inset.tick_params(labelsize=5.5, length=2, pad=1)
    inset.xaxis.label.set_size(6.5)
    inset.yaxis.label.set_size(6.5)
    inset.set_title(rf"mode {inset_mode}, $P = {participation:.2f}$", fontsize=6.5, pad=2)


# --------------------------------------------------------------------------- energy


def draw_energy_map(ax, ds: xr.Dataset) -> None:
    """Energy density h_n(t), site against log time, on a logarithmic colour scale, with the
    energy centre X(t) = sum n h_n as a black line (Figs. 2a,b, 4a,b, 6a,e,i)."""
    _log_density_map(ax, ds.energy_density, "site", style.ENERGY_DENSITY_LABEL, style.SITE_LABEL)
    after = _after_start(ds)
    ax.plot(after.time.values, after.energy_centre.values, color="black", linewidth=0.9,
            path_effects=[path_effects.withStroke(linewidth=1.8, foreground="white")])
    _scene_title(ax, ds)


def draw_participation(ax, *scenes: xr.Dataset) -> None:
    """Participation number P(t) smoothed by LOWESS in log t, raw values faint behind; Hertz red,
    FPUT blue, energies told apart by shade and dash (Figs. 2c, 4c)."""
    for ds, line in zip(scenes, _scene_styles(scenes)):
        after = _after_start(ds)
        _smoothed_curve(ax, after.time.values, after.participation.values, **line)
    _time_axis(ax, *_time_range(scenes))
    ax.set_ylabel(style.P_LABEL)
    _legend_above_data(ax, ncol=2)


def draw_participation_with_dvd(ax, ds: xr.Dataset) -> None:
    """P(t) of the energy and P_D(t) of the deviation vector, both LOWESS-smoothed in log t with
    the raw values faint behind (Figs. 6b,f,j)."""
    after = _after_start(ds)
    t = after.time.values
    _smoothed_curve(ax, t, after.participation.values, style.model_colour(ds.attrs["model"]),
                    label=style.P_LABEL)
    _smoothed_curve(ax, t, after.dvd_participation.values, "black", linestyle="--", label=style.PD_LABEL)
    _time_axis(ax, t[0], t[-1])
    ax.set_ylabel(f"{style.P_LABEL}, {style.PD_LABEL}")
    ax.set_ylim(bottom=0)
    _legend_above_data(ax, ncol=2)
    _scene_title(ax, ds)


# --------------------------------------------------------------------------- chaos


def draw_mlce(ax, *scenes: xr.Dataset) -> None:
    """Finite-time mLCE Lambda(t) on log-log axes with the dashed law Lambda ~ 1/t of regular
    orbits, drawn through the lowest curve at the first sample with t >= 1 (Figs. 2d, 4d, 6d,h,l)."""
    anchors = []
    for ds, line in zip(scenes, _scene_styles(scenes)):
        after = _after_start(ds)
        t, mlce = after.time.values, after.mlce.values
        positive = mlce > 0  # a log axis cannot show Lambda <= 0
        if len(scenes) == 1:
            line["label"] = None  # the title names the scene
        ax.plot(t[positive], mlce[positive], linewidth=1.0, **line)
        late = np.flatnonzero((t >= 1.0) & positive)
        if late.size:
            anchors.append(mlce[late[0]] * t[late[0]])
    t_min, t_max = _time_range(scenes)
    if anchors:
        law = np.array([t_min, t_max])
        ax.plot(law, min(anchors) / law, color="black", linestyle="--", linewidth=0.8,
                label=r"$\propto t^{-1}$")
    _time_axis(ax, t_min, t_max)
    ax.set_yscale("log")
    ax.set_ylabel(style.MLCE_LABEL)
    ax.legend(loc="lower left")
    if len(scenes) == 1:
        _scene_title(ax, scenes[0])


def draw_dvd_map(ax, ds: xr.Dataset, mark_times=()) -> None:
    """Deviation vector density w_n(t), site against log time, logarithmic colour scale
    (Figs. 3a,b, 5a,c, 6c,g,k); ``mark_times`` (those of the DVD profiles) are drawn as
    vertical lines at the samples the profiles use, coloured as the profiles."""
    _log_density_map(ax, ds.dvd, "site", style.DVD_LABEL, style.SITE_LABEL)
    t = _after_start(ds).time.values
    for i, (_, index) in enumerate(_profile_samples(ds, mark_times)):
        if index is not None:
            ax.axvline(t[index], linewidth=1.0, **_profile_line(i))
    _scene_title(ax, ds)


def draw_dvd_profiles(ax, ds: xr.Dataset, times=()) -> None:
    """DVD profiles w_n against site (log scale) at the sample nearest to each of ``times``, each
    labelled with the time actually used; a time beyond the run's last sample is not drawn (never
    extrapolated) and the legend says so (Figs. 3c,d, 5b,d)."""
    after = _after_start(ds)
    t = after.time.values
    sites = after.site.values
    for i, (wanted, index) in enumerate(_profile_samples(ds, times)):
        if index is None:  # an invisible handle: the legend names the time left out
            ax.plot([], [], " ", label=rf"$t = {style.time_text(wanted)}$ beyond run "
                                       rf"($t_{{\rm final}} = {style.time_text(t[-1])}$)")
            continue
        profile = np.clip(after.dvd.isel(time=index).values, style.MAP_FLOOR, None)
        ax.plot(sites, profile, label=rf"$t = {style.time_text(t[index])}$", **_profile_line(i))
    ax.set_yscale("log")
    ax.set_ylim(style.MAP_FLOOR, 1.0)
    ax.set_xlim(sites[0] - 0.5, sites[-1] + 0.5)
    _sparse_log_ticks(ax.yaxis)
    ax.xaxis.set_major_locator(_index_locator())
    ax.set_xlabel(style.SITE_LABEL)
    ax.set_ylabel(style.DVD_LABEL)
    ax.legend(loc="lower center")
    _scene_title(ax, ds)


def draw_dvd_participation(ax, ds: xr.Dataset) -> None:
    """Participation number P_D(t) of the DVD, LOWESS-smoothed in log t with the raw values
    faint behind (Figs. 3e,f)."""
    after = _after_start(ds)
    t = after.time.values
    _smoothed_curve(ax, t, after.dvd_participation.values, style.model_colour(ds.attrs["model"]))
    _time_axis(ax, t[0], t[-1])
    ax.set_ylabel(style.PD_LABEL)
    ax.set_ylim(bottom=0)
    _scene_title(ax, ds)


# --------------------------------------------------------------------------- gaps


def draw_gap_map(ax, ds: xr.Dataset) -> None:
    """Open bonds (gaps) against log time and bond index: the fraction of the steps since the
    previous sample that each bond was open, 0 to 1 (Figs. 7a,b)."""
    _draw_map(ax, ds.gap_fraction, "bond", Normalize(0.0, 1.0), style.GAP_CMAP,
              style.GAP_FRACTION_LABEL, style.BOND_LABEL)
    _scene_title(ax, ds)


def draw_gap_count(ax, ds: xr.Dataset) -> None:
    """Number of open gaps at each sample against log time, and the largest number since the
    previous sample as a light step area where it is recorded (Figs. 7c,d)."""
    after = _after_start(ds)
    t = after.time.values
    colour = style.model_colour(ds.attrs["model"])
    top = int(after.n_gaps.max())
    if "n_gaps_max" in after:
        ax.fill_between(t, after.n_gaps_max.values, step="pre", color=_lighten(colour, 0.75),
                        linewidth=0, label="largest since previous sample")
        top = max(top, int(after.n_gaps_max.max()))
    ax.plot(t, after.n_gaps.values, color=colour, linewidth=0.8, marker="o", markersize=1.2,
            label="at the sample")
    _time_axis(ax, t[0], t[-1])
    ax.set_ylabel(style.GAP_COUNT_LABEL)
    ax.set_ylim(0, 1.45 * max(top, 1))  # headroom for the legend above the counts
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.legend(loc="upper left", ncol=2)
    _scene_title(ax, ds)


# --------------------------------------------------------------------------- modes


def draw_eta(ax, ds: xr.Dataset, equipartition: bool = False) -> None:
    """Normalised spectral entropy eta(t) against log time; with ``equipartition`` the expected
    value <eta> at equipartition as a dashed horizontal line (Figs. 8a-d, 9a-d)."""
    after = _after_start(ds)
    t = after.time.values
    ax.plot(t, after.eta.values, color=style.model_colour(ds.attrs["model"]), linewidth=0.8)
    if equipartition:
        value = float(ds.eta.attrs["equipartition_value"])
        ax.axhline(value, color="black", linestyle="--", linewidth=0.8)
        # Labelled at the left end, where eta is still near 1 and the line runs free.
        ax.annotate(rf"$\langle\eta\rangle = {value:.3f}$", (0.03, value),
                    xycoords=ax.get_yaxis_transform(), xytext=(0, 2), textcoords="offset points",
                    va="bottom", ha="left", fontsize=style.RC["legend.fontsize"])
    _time_axis(ax, t[0], t[-1])
    ax.set_ylabel(style.ETA_LABEL)
    ax.set_ylim(bottom=0)
    _scene_title(ax, ds)


def draw_mode_energy_map(ax, ds: xr.Dataset) -> None:
    """Normalised harmonic energies v_k = E_k / sum_j E_j of the linear modes, numbered by
    increasing frequency, against log time, logarithmic colour scale (Figs. 8e-h, 9e-h)."""
    energy = ds.mode_energy
    _log_density_map(ax, energy / energy.sum("mode"), "mode", style.MODE_ENERGY_LABEL,
                     style.MODE_LABEL)
    _scene_title(ax, ds)


# --------------------------------------------------------------------------- dispatch

DRAW = {
    "ensemble_participation": draw_ensemble_participation,
    "chain_spectrum": draw_chain_spectrum,
    "energy_map": draw_energy_map,
    "participation": draw_participation,
    "participation_with_dvd": draw_participation_with_dvd,
    "mlce": draw_mlce,
    "dvd_map": draw_dvd_map,
    "dvd_profiles": draw_dvd_profiles,
    "dvd_participation": draw_dvd_participation,
    "gap_map": draw_gap_map,
    "gap_count": draw_gap_count,
    "eta": draw_eta,
    "mode_energy_map": draw_mode_energy_map,
}
# Panels of these kinds read the Dataset under this key of ``data`` instead of scene Datasets.
WHOLE_DATASET = {"ensemble_participation": "ensemble", "chain_spectrum": "chain"}


def _panel(panel_id: str) -> panels.Panel:
    if panel_id not in panels.PANELS:
        raise KeyError(f"unknown panel {panel_id!r}; panels are {sorted(panels.PANELS)}")
    return panels.PANELS[panel_id]


def _inputs(panel_id: str, panel: panels.Panel, data: dict) -> list[xr.Dataset]:
    """The Datasets a panel draws, checked for the variables its kind reads."""
    names = [WHOLE_DATASET[panel.kind]] if panel.kind in WHOLE_DATASET else [s.name for s in panel.scenes]
    missing = [name for name in names if name not in data]
    if missing:
        raise KeyError(f"panel {panel_id} needs data {missing}; given {sorted(data)}")
    for name in names:
        absent = [v for v in panels.KIND_OBSERVABLES[panel.kind] if v not in data[name]]
        if absent:
            raise KeyError(f"panel {panel_id} ({panel.kind}) needs variable(s) {absent} in {name!r}")
    return [data[name] for name in names]


def _profile_times(scene: panels.Scene) -> tuple:
    """The DVD profile times of the scene's profile panel, to be marked on its DVD map."""
    for panel in panels.PANELS.values():
        if panel.kind == "dvd_profiles" and panel.scenes == (scene,):
            return tuple(panel.options["times"])
    return ()


def draw_panel(ax, panel_id: str, data: dict) -> None:
    """Draw panel ``panel_id`` of ``panels.PANELS`` into ``ax`` from ``data`` (scene name ->
    Dataset, plus "chain" and "ensemble")."""
    panel = _panel(panel_id)
    options = dict(panel.options)
    if panel.kind == "dvd_map":
        options.setdefault("mark_times", _profile_times(panel.scenes[0]))
    DRAW[panel.kind](ax, *_inputs(panel_id, panel, data), **options)


def plot_panel(panel_id: str, data: dict) -> Figure:
    """Panel ``panel_id`` (e.g. "4d") alone on a new one-column figure."""
    with style.context():
        fig = Figure(figsize=(style.COLUMN_WIDTH, style.PANEL_HEIGHT), layout="constrained")
        draw_panel(fig.add_subplot(), panel_id, data)
    return fig
