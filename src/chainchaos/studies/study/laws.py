"""Power laws of a study's ensemble means: exponents with bootstrap intervals over realizations.

The disordered-lattice literature reads spreading and chaos as power laws of averages over
realizations: <log10 m2> ~ a_m log10 t, <log10 P> ~ (a_m / 2) log10 t, <log10 Lambda> ~ alpha_L
log10 t (Flach, Krimer & Skokos, PRL 102, 024101 (2009); Skokos, Gkolias & Flach, PRL 111, 064101
(2013); Senyange, Many Manda & Skokos, PRE 98, 052229 (2018)). For each law a study's file names
(key ``laws``), over the valid realizations (lane 0) of every (model, energy):

1. **The samples**: those of the log-spaced grid only (t = t_first 10^(k / samples_per_decade));
   the run's extra final samples would weigh its last decade more in a least-squares fit.
2. **The window, by rule** (:func:`fit_window`): the running slope s(t) of the mean (least
   squares over ``window_decades`` decades centred on each sample) is compared with its median
   over the run's last ``min_decades`` decades, s_end. The window is the longest final stretch
   of the run, starting no earlier than ``t_min``, on which every running slope lies within
   ``band`` of s_end; at least the last ``min_decades`` decades. A window that the band cuts to
   that minimum is reported as not settled (``settled`` = 0): the slope still drifts.
3. **The exponent**: the least-squares slope of the mean over the window.
4. **Its interval**: the 2.5 and 97.5 % quantiles of the exponent over ``bootstrap`` resamples
   of the realizations that enter (valid ones) with replacement (``numpy.random.default_rng(seed)``),
   the window kept; none with fewer than two realizations.
5. **The walls** (key ``laws.walls``, :func:`walls_time`): on a finite chain the run is cut, before
   steps 2-4, at the first sample where the ends are felt: for m2, where the realization mean of
   log10 of the edge energy (-inf while one of them has none) exceeds log10 ``edge_energy`` (the
   packet's tail, which m2 weighs by its distance squared, reached them); for every law, where the mean of log10 P exceeds
   log10(``participation_fraction`` N) (its core fills that much of the chain). A law whose run so
   cut is shorter than ``min_decades`` after ``t_min`` is not fitted (NaN): the chain is too short.

Sums in index order and fdlibm's logarithms (``kernels.exactmath``): the same bits on every CPU.

A crossover is not a power law (key ``laws.crossovers``, :func:`local_derivative`): the strong
chaos of Laptyeva et al., EPL 91, 30001 (2010), where <log10 m2> grows as t^(1/2) and crosses over
to t^(1/3), is read from the local derivative d<log10 m2>/d log10 t (the running slope of step 2)
with its band over realizations (2.5 and 97.5 % over the same bootstrap resamples, at every
sample), drawn against the published lines; its largest value after ``t_min`` and when it is
reached are reported with the band there. No exponent is fitted.

A self-trapped packet keeps most of the distribution on one site while a small part spreads: the
exponent of its m2 or P is not a spreading law. Where a study keeps ``largest_share``, a law of
m2 or P records the fraction of its realizations whose largest share on one site, averaged over
the fit window, exceeds :data:`SELF_TRAPPED_SHARE` (``self_trapped``); the table says so.
"""

#: The share of the distribution on one site above which a packet counts as self-trapped.
SELF_TRAPPED_SHARE = 0.5

import warnings

import numpy as np
import xarray as xr

from chainchaos.errors import require
from chainchaos.kernels import exactmath
from chainchaos.studies.study.statistics import (
    log10,
    ordered_mean,
    running_slope,
)

#: The series a law may fit: a study's observable, or |Lambda| (a linear chain's finite-time mLCE
#: ln|v(t)| / t may be negative: its deviation vector does not grow, and |Lambda| t stays bounded).
LAW_SERIES = {"participation": "P", "second_moment": "m2", "mlce": "Lambda", "abs_mlce": "|Lambda|"}


def law_series(merged: xr.Dataset, name: str) -> xr.DataArray:
    """The series ``name`` of :data:`LAW_SERIES` from a merged study."""
    return abs(merged["mlce"]) if name == "abs_mlce" else merged[name]


def log_grid(t: np.ndarray, settings) -> np.ndarray:
    """Which samples ``t`` lie on the log-spaced grid of ``settings`` (``sample_steps``)."""
    steps = np.rint(np.asarray(t) / settings.dt).astype(np.int64)
    return np.isin(steps, settings.sample_steps())


def fit_window(log_t: np.ndarray, slope: np.ndarray, *, min_decades: float, band: float,
               t_min: float) -> tuple[int, int, bool]:
    """(first, last) sample indices of the fit window (module docstring, step 2) and whether it
    is settled: longer than the last ``min_decades`` decades. ``slope``: the running slope at
    each sample of ``log_t`` (NaN where undefined)."""
    finite = np.flatnonzero(np.isfinite(slope) & np.isfinite(log_t))
    require(finite.size >= 3, "running slope", f"{finite.size} finite samples", "at least 3")
    last = int(finite[-1])
    tail = finite[log_t[finite] >= log_t[last] - min_decades - 1e-9]  # a sample on the edge is in
    reference = float(np.median(slope[tail]))
    first = last
    for i in finite[::-1]:
        if log_t[i] < log10(np.array([t_min]))[0] or abs(slope[i] - reference) > band:
            break
        first = int(i)
    minimal = int(tail[0])
    return min(first, minimal), last, first < minimal


def walls_time(t: np.ndarray, mean_log10: np.ndarray, bound: float | None) -> float:
    """The first time ``t`` at which a realization mean of log10 exceeds log10 ``bound``
    (module docstring, step 5); infinity when it never does or there is no bound."""
    if bound is None:
        return float("inf")
    above = np.nan_to_num(mean_log10, nan=-np.inf) > log10(np.array([bound]))[0]
    over = np.flatnonzero(above & (np.asarray(t) > 0))  # the initial state is not a wall
    return float(t[over[0]]) if over.size else float("inf")


def _slope(log_t, y) -> float:
    use = np.isfinite(y)
    return exactmath.line_slope(log_t[use], y[use]) if use.sum() >= 3 else float("nan")


def fit_law(t: np.ndarray, x: np.ndarray, *, window_decades: float, min_decades: float, band: float, t_min: float,
            bootstrap: int, seed: int, t_walls: float = float("inf")) -> dict:
    """The exponent of <log10 x> against log10 t over the realizations ``x`` (realization, time;
    NaN where a realization is left out), its window and bootstrap interval (module docstring),
    on the samples before ``t_walls`` (step 5)."""
    before = np.asarray(t) < t_walls
    t, x = np.asarray(t)[before], np.asarray(x)[:, before]
    log_t = log10(t)  # NaN at t = 0
    start = max(np.nanmin(log_t, initial=np.inf), log10(np.array([t_min]))[0])
    if not t.size or np.nanmax(log_t, initial=-np.inf) - start < min_decades - 1e-9:
        return {"exponent": np.nan, "lower": np.nan, "upper": np.nan, "t_start": np.nan,
                "t_end": float(t[-1]) if t.size else np.nan, "settled": False, "realizations": 0, "t_walls": t_walls}
    logs = log10(x)
    logs = logs[np.isfinite(logs).any(axis=1)]  # resample the realizations that enter, not those left out
    mean, count = ordered_mean(logs, axis=0)
    slope_t = running_slope(log_t, mean, window_decades)
    first, last, settled = fit_window(log_t, slope_t, min_decades=min_decades, band=band, t_min=t_min)
    window = slice(first, last + 1)
    exponent = _slope(log_t[window], mean[window])
    rng = np.random.default_rng(seed)
    R = logs.shape[0]
    draws = np.empty(bootstrap)
    for b in range(bootstrap):
        pick = rng.integers(0, R, R)
        draws[b] = _slope(log_t[window], ordered_mean(logs[pick, window], axis=0)[0])
    lower, upper = np.quantile(draws, [0.025, 0.975]) if R >= 2 else (np.nan, np.nan)
    return {"exponent": exponent, "lower": float(lower), "upper": float(upper), "t_start": float(t[first]),
            "t_end": float(t[last]), "settled": bool(settled), "realizations": int(count[window].min()),
            "t_walls": t_walls}


def local_derivative(t: np.ndarray, x: np.ndarray, *, window_decades: float, t_min: float, bootstrap: int,
                     seed: int, t_walls: float = float("inf")) -> dict:
    """The local derivative of <log10 x> against log10 t over the realizations ``x`` (realization,
    time; NaN where one is left out), with its bootstrap band, and its largest value after
    ``t_min`` (module docstring); samples from ``t_walls`` on are NaN.

    Parameters
    ----------
    t : numpy.ndarray of shape (S,)
        Sample times (the log-spaced grid).
    x : numpy.ndarray of shape (R, S)
        The series of every realization.
    window_decades : float
        Width of the running least-squares slope, in decades.
    t_min : float
        The largest value is sought from this time on.
    bootstrap : int
        Resamples of the realizations, with replacement.
    seed : int
        Seed of ``numpy.random.default_rng`` drawing them.
    t_walls : float, optional
        The first time the chain's ends are felt (default: never).

    Returns
    -------
    dict
        ``slope``, ``lower``, ``upper`` (S,): the derivative of the mean and the 2.5 / 97.5 %
        quantiles of the resampled ones; ``max``, ``t_max``, ``max_lower``, ``max_upper``: its
        largest value after t_min, when, and the band there (NaN without one); ``realizations``.
    """
    t = np.asarray(t, dtype=np.float64)
    log_t = log10(t)
    logs = log10(np.asarray(x, dtype=np.float64))
    logs = logs[np.isfinite(logs).any(axis=1)]
    cut = t >= t_walls
    logs[:, cut] = np.nan
    R = logs.shape[0]
    slope = running_slope(log_t, ordered_mean(logs, axis=0)[0], window_decades)
    rng = np.random.default_rng(seed)
    draws = np.stack([running_slope(log_t, ordered_mean(logs[rng.integers(0, R, R)], axis=0)[0], window_decades)
                      for _ in range(bootstrap)]) if R >= 2 else np.full((1, t.size), np.nan)
    with warnings.catch_warnings():  # a sample without a finite resample (before t_min, after the walls): NaN
        warnings.simplefilter("ignore", RuntimeWarning)
        lower, upper = (np.nanquantile(draws, q, axis=0) for q in (0.025, 0.975))
    slope[cut], lower[cut], upper[cut] = np.nan, np.nan, np.nan  # a running slope there reads samples before
    after = np.flatnonzero((t >= t_min) & np.isfinite(slope))
    k = int(after[np.argmax(slope[after])]) if after.size else -1
    pick = (lambda a: float(a[k]) if k >= 0 else float("nan"))
    return {"slope": slope, "lower": lower, "upper": upper, "max": pick(slope), "t_max": pick(t),
            "max_lower": pick(lower), "max_upper": pick(upper), "realizations": R}


FIELDS = {
    "exponent": ("f8", "least-squares slope of the realization mean of log10 {x} against log10 t over the fit window"),
    "lower": ("f8", "2.5% quantile of the exponent over bootstrap resamples of the realizations"),
    "upper": ("f8", "97.5% quantile of the exponent over bootstrap resamples of the realizations"),
    "t_start": ("f8", "start of the fit window (chosen by the rule of chainchaos.studies.study.laws)"),
    "t_end": ("f8", "end of the fit window"),
    "settled": ("i1", "1 if the running slope stays within the band longer than the minimum window"),
    "realizations": ("i4", "valid realizations that enter every sample of the window"),
    "t_walls": ("f8", "first sample at which the chain's ends are felt (laws.walls); the run is cut there; inf: never"),
}


#: The local derivative's band of a crossover (``local_derivative``), per sample of the grid.
CROSSOVER_BANDS = {
    "slope": "local derivative d<log10 x>/d log10 t of the realization mean (running least-squares slope)",
    "lower": "2.5% quantile of the local derivative over bootstrap resamples of the realizations",
    "upper": "97.5% quantile of the local derivative over bootstrap resamples of the realizations",
}
#: Its largest value after laws.t_min, when, and the band there.
CROSSOVER_PEAKS = {
    "crossover_max": "largest local derivative after laws.t_min",
    "crossover_t_max": "the time it is reached",
    "crossover_max_lower": "2.5% quantile of the resampled derivatives at that time",
    "crossover_max_upper": "97.5% quantile of the resampled derivatives at that time",
}


def _strings(values: list[str]) -> np.ndarray:
    """Text along the law dimension; str, not object, when empty: an empty object array has no
    type that netCDF can store as text."""
    return np.array(values, dtype=object if values else str)


def laws(merged: xr.Dataset, spec: dict, settings, N: int) -> xr.Dataset:
    """Every law of ``spec['laws']`` fitted on every (model, energy) of a merged study (its
    ``study.runs.merge_groups``) of chains of ``N`` sites: dims model, energy, law (empty when
    the study names no law); ``expected`` the published exponent."""
    block = spec["laws"]
    fits = block["fits"]  # none: a Dataset with an empty law dimension
    keys = {"window_decades": float(spec["criteria"]["slope_window_decades"]),
            "min_decades": float(block["min_decades"]), "band": float(block["band"]), "t_min": float(block["t_min"]),
            "bootstrap": int(block["bootstrap"]), "seed": int(block["seed"])}
    walls = block["walls"]  # Study.check: an edge_energy bound only with edge_energy observed
    grid = log_grid(merged["time"].values, settings)
    t = merged["time"].values[grid]
    M, E, L = merged.sizes["model"], merged.sizes["energy"], len(fits)
    out = {key: np.zeros((M, E, L), dtype=dtype) for key, (dtype, _) in FIELDS.items()}
    valid = merged["valid"].isel(lane=0) == 1

    def realizations(series, m, e):
        """(realization, sample) of a series at (model m, energy e), NaN where not valid."""
        return series.isel(model=m, energy=e, lane=0).where(valid.isel(model=m, energy=e)).values[:, grid]

    def wall(name, bound, m, e):
        if bound is None:  # no bound: its series need not be among the observables
            return float("inf")
        values = realizations(merged[name], m, e)
        mean = ordered_mean(log10(values), axis=0)[0]
        return walls_time(t, np.where((values == 0).any(axis=0), -np.inf, mean), bound)  # log10 0 = -inf

    fraction = walls["participation_fraction"]
    crossovers = block.get("crossovers", [])
    trapping = "largest_share" in merged
    trapped = np.full((M, E, L), np.nan)
    C = len(crossovers)
    band = {key: np.full((M, E, C, t.size), np.nan) for key in CROSSOVER_BANDS}
    peak = {key: np.full((M, E, C), np.nan) for key in CROSSOVER_PEAKS}
    for m in range(M):
        for e in range(E):
            filled = wall("participation", None if fraction is None else fraction * N, m, e)
            tail = wall("edge_energy", walls["edge_energy"], m, e)
            for k, fit in enumerate(fits):
                cut = min(filled, tail) if fit["series"] == "second_moment" else filled
                found = fit_law(t, realizations(law_series(merged, fit["series"]), m, e), **keys, t_walls=cut)
                for key in FIELDS:
                    out[key][m, e, k] = found[key]
                if trapping and fit["series"] in ("second_moment", "participation") and np.isfinite(found["t_start"]):
                    share = realizations(merged["largest_share"], m, e)
                    window = (t >= found["t_start"]) & (t <= found["t_end"])
                    kept = np.isfinite(share[:, window]).all(axis=1)
                    trapped[m, e, k] = np.mean(np.mean(share[kept][:, window], axis=1) > SELF_TRAPPED_SHARE) \
                        if kept.any() else np.nan
            for c, crossover in enumerate(crossovers):
                cut = min(filled, tail) if crossover["series"] == "second_moment" else filled
                found = local_derivative(t, realizations(merged[crossover["series"]], m, e), t_walls=cut,
                                         **{k: keys[k] for k in ("window_decades", "t_min", "bootstrap", "seed")})
                for key in CROSSOVER_BANDS:
                    band[key][m, e, c] = found[key]
                for key in CROSSOVER_PEAKS:
                    peak[key][m, e, c] = found[key.removeprefix("crossover_")]
    data = {key: (("model", "energy", "law"), out[key], {"units": "1", "long_name": text.format(x="x")})
            for key, (_, text) in FIELDS.items()}
    data["expected"] = ("law", np.array([float(f["expected"]) for f in fits]),
                        {"units": "1", "long_name": "the published exponent"})
    if trapping:
        data["self_trapped"] = (("model", "energy", "law"), trapped,
                                {"units": "1", "long_name": "fraction of the realizations self-trapped over the fit "
                                 f"window (largest share on one site > {SELF_TRAPPED_SHARE}; NaN: not a law of m2 or P)"})
    if any("uncertainty" in f for f in fits):  # where a publication gives one
        data["uncertainty"] = ("law", np.array([float(f.get("uncertainty", np.nan)) for f in fits]),
                               {"units": "1", "long_name": "the published uncertainty (+-) of the exponent"})
    data["reference"] = ("law", _strings([str(f["reference"]) for f in fits]),
                         {"long_name": "where the published exponent is from"})
    data["series"] = ("law", _strings([f["series"] for f in fits]),
                      {"long_name": "the series whose realization mean of log10 the law is about"})
    error = merged["energy_error_max"].where(merged["valid"] == 1).max(dim=("realization", "lane"))
    data["energy_error_max"] = (("model", "energy"), error.values,
                                {"units": "1", "long_name": "largest relative energy error of the valid orbits"})
    if "norm_error" in merged:  # a split model's second conserved quantity, reported as the energy
        norm = merged["norm_error"].max(dim="time").where(merged["valid"] == 1).max(dim=("realization", "lane"))
        data["norm_error_max"] = (("model", "energy"), norm.values,
                                  {"units": "1", "long_name": "largest relative norm error of the valid orbits"})
    if crossovers:
        for key, text in CROSSOVER_BANDS.items():
            data[f"crossover_{key}"] = (("model", "energy", "crossover", "grid_time"), band[key],
                                        {"units": "1", "long_name": text})
        for key, text in CROSSOVER_PEAKS.items():
            data[key] = (("model", "energy", "crossover"), peak[key], {"units": "1", "long_name": text})
        data["crossover_lines"] = (("crossover", "line"), np.array([c["lines"] for c in crossovers], dtype=float),
                                   {"units": "1", "long_name": "the published slopes the derivative is drawn against"})
        data["crossover_reference"] = ("crossover", _strings([str(c["reference"]) for c in crossovers]),
                                       {"long_name": "where the crossover is published"})
    coords = {"model": merged["model"], "energy": merged["energy"],
              "law": ("law", _strings([LAW_SERIES[f["series"]] for f in fits]), {"long_name": "the law, by the series it fits"})}
    if crossovers:
        coords["crossover"] = ("crossover", _strings([c["series"] for c in crossovers]),
                               {"long_name": "the series whose local derivative is read"})
        coords["grid_time"] = ("grid_time", t, {"long_name": "the sample times of the log-spaced grid"})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(fit_rule=" ".join(__doc__.split("\n\n", 2)[2].split("\n\nSums")[0].split()),
                    **{f"fit_{k}": v for k, v in keys.items()},
                    **{f"walls_{k}": "none" if v is None else v for k, v in walls.items()})
    return ds
