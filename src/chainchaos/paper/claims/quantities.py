"""The quantities a claim is about, each computed from one stored product of the pipeline.

* a scene file (``results/scenes/<name>.nc``, the data contract, docs/conventions.md#scene-file): final and
  windowed averages of a time series, onsets of spreading and of chaos, the chaos criterion on
  Lambda(t), gap statistics, where the DVD peaks, the equipartition value of eta;
* the chain file: the energy profile of a linear mode and where it peaks, and the largest energy a
  single-bead excitation can carry with the Taylor sign of K4;
* the ensemble file of Fig. 1(a): counts and levels of the <P>(rank) curves;
* a scene or an energy scan: its largest relative energy error.

Every choice (windows, thresholds, smoothing) is an argument; :mod:`chainchaos.paper.claims.measures`
fills them from :class:`chainchaos.paper.criteria.Criteria`. Times are in units of 1/omega_max.
"""

import numpy as np
import xarray as xr

from chainchaos.observe import reductions
from chainchaos.paper.criteria import Criteria

# --------------------------------------------------------------------------------------------
# A scene's time series
# --------------------------------------------------------------------------------------------


def _positive_times(ds: xr.Dataset, var: str) -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(ds["time"].values, dtype=float)
    y = np.asarray(ds[var].values, dtype=float)
    keep = t > 0
    return t[keep], y[keep]


def _none_if_nan(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def final_window(t: np.ndarray, decades: float) -> np.ndarray:
    """Mask of the samples in the last ``decades`` decades: t >= t[-1] 10^-decades, t > 0."""
    t = np.asarray(t, dtype=float)
    return (t > 0) & (t >= t[-1] * 10.0 ** (-decades))


def final_mean(ds: xr.Dataset, var: str, decades: float = 1.0) -> float:
    """Time average of ``var(time)`` over the last ``decades`` decades of the run
    (``reductions.final_average``: trapezoidal in t, not a mean over the log-spaced samples)."""
    t, y = _positive_times(ds, var)
    return reductions.final_average(t, y, decades)


def window_mean(ds: xr.Dataset, var: str, t0: float, t1: float) -> float:
    """Time average of ``var(time)`` over t0 <= t <= t1 (NaN when the run does not cover it)."""
    t, y = _positive_times(ds, var)
    return reductions.time_average(t, y, t0, min(t1, t[-1]))


def window_median(ds: xr.Dataset, var: str, t0: float, t1: float) -> float:
    """Median of ``var(time)`` over the samples with t0 <= t <= t1 (NaN when there is none)."""
    t, y = _positive_times(ds, var)
    sel = (t >= t0) & (t <= t1)
    return float(np.median(y[sel])) if sel.any() else float("nan")


def window_largest(ds: xr.Dataset, var: str, t0: float, t1: float, smoothing_decades: float) -> float:
    """Largest value of ``var(time)`` smoothed over ``smoothing_decades`` of log t (as the paper
    plots P), over the samples with t0 <= t <= t1, smoothed from the samples up to t1 only (NaN
    when there is none)."""
    t, y = _positive_times(ds, var)
    upto = t <= t1
    smooth = reductions.log_time_smooth(t[upto], y[upto], smoothing_decades)
    sel = t[upto] >= t0
    return float(np.max(smooth[sel])) if sel.any() else float("nan")


def spreading_onset(ds: xr.Dataset, factor: float = 2.0, smoothing_decades: float = 0.5,
                    t_ref: float = 10.0, hold_decades: float = 0.5) -> float | None:
    """Onset of spreading: the first time t >= t_ref from which the log-time running mean of P
    stays above ``factor`` times its value at t_ref for ``hold_decades`` (None when never)."""
    t, P = _positive_times(ds, "participation")
    return _none_if_nan(reductions.spreading_onset(t, P, factor, smoothing_decades, t_ref, hold_decades))


def saturation_time(ds: xr.Dataset, fraction: float = 0.9, smoothing_decades: float = 0.5,
                    final_decades: float = 1.0, hold_decades: float = 0.5) -> float | None:
    """First time from which the smoothed P stays above ``fraction`` of its final time average
    for ``hold_decades`` (None when never)."""
    t, P = _positive_times(ds, "participation")
    return _none_if_nan(reductions.saturation_time(t, P, fraction, smoothing_decades, final_decades, hold_decades))


def mlce_slope(ds: xr.Dataset, decades: float = 1.0, t_end: float | None = None) -> float:
    """Least-squares slope of log10 Lambda(t) against log10 t over the last ``decades`` decades
    before ``t_end`` (default: the end of the run): about -1 for a regular orbit, 0 for a chaotic one."""
    t, L = _positive_times(ds, "mlce")
    end = t[-1] if t_end is None else t_end
    return reductions.loglog_slope(t, L, end * 10.0 ** (-decades), end)


def growth_excess(ds: xr.Dataset, decades: float = 1.0) -> float:
    """ln(|v(t_end)|/|v(t_end 10^-decades)|) - ln(10^decades) from Lambda: how much faster than
    linearly the deviation vector grew over the last ``decades`` decades."""
    t, L = _positive_times(ds, "mlce")
    return reductions.excess_growth(t, t * L, t[-1] * 10.0 ** (-decades), t[-1])


def scene_chaotic(ds: xr.Dataset, c: Criteria) -> bool:
    """The chaos criterion (``reductions.is_chaotic``) on a scene's single orbit."""
    t, L = _positive_times(ds, "mlce")
    return reductions.is_chaotic(t, t * L, c.chaos_slope, c.chaos_growth_margin, c.chaos_window_decades)


def chaos_onset(ds: xr.Dataset, c: Criteria) -> float | None:
    """Onset of chaos of a scene's single orbit (``reductions.chaos_onset``), None if not chaotic."""
    t, L = _positive_times(ds, "mlce")
    return _none_if_nan(reductions.chaos_onset(t, t * L, c.chaos_slope, c.chaos_growth_margin,
                                               c.chaos_window_decades))


def final_mlce(ds: xr.Dataset) -> float:
    """Lambda at the end of the run."""
    t, L = _positive_times(ds, "mlce")
    return float(L[-1])


def max_simultaneous_gaps(ds: xr.Dataset) -> int:
    """Largest number of simultaneously open gaps over the run: ``n_gaps_max`` (checked at every
    step) when present, else the sampled ``n_gaps``."""
    var = "n_gaps_max" if "n_gaps_max" in ds else "n_gaps"
    return int(np.max(ds[var].values))


def bonds_ever_open(ds: xr.Dataset) -> np.ndarray:
    """Bonds (1..N+1) open at some sample or during some interval between samples."""
    opened = np.zeros(ds.sizes["bond"], dtype=bool)
    if "gap_fraction" in ds:
        opened |= (np.asarray(ds["gap_fraction"].values) > 0).any(axis=0)
    if "gap_open" in ds:
        opened |= (np.asarray(ds["gap_open"].values) > 0).any(axis=0)
    return np.asarray(ds["bond"].values)[opened]


def open_time_fraction(ds: xr.Dataset, bonds) -> np.ndarray:
    """Fraction of the run (from the first sample to the last) during which each of ``bonds`` was
    open: ``gap_fraction`` (the fraction of the steps since the previous sample at whose end the
    bond was open) weighted by the length of each interval between samples."""
    t = np.asarray(ds["time"].values, dtype=float)
    frac = np.asarray(ds["gap_fraction"].sel(bond=list(bonds)).values, dtype=float)
    span = t[-1] - t[0]
    return (np.diff(t) @ frac[1:]) / span if span > 0 else np.zeros(len(bonds))


def bond_distance(bond: np.ndarray, site: int) -> np.ndarray:
    """Distance of bond b (joining beads b-1 and b) from bead ``site``: 0 for its own two bonds
    (site and site+1), then 1, 2, ... outwards."""
    bond = np.asarray(bond)
    return np.where(bond < site, site - bond, np.where(bond > site + 1, bond - site - 1, 0))


def gap_spread_time(ds: xr.Dataset, site: int, distance: int = 2) -> float | None:
    """First sample time by which a gap has opened on a bond at least ``distance`` bonds away from
    bead ``site`` (from ``gap_fraction``, which counts every step since the previous sample)."""
    frac = np.asarray(ds["gap_fraction"].values)
    far = bond_distance(ds["bond"].values, site) >= distance
    hit = np.flatnonzero((frac[:, far] > 0).any(axis=1))
    return float(ds["time"].values[hit[0]]) if hit.size else None


def dvd_site_fraction(ds: xr.Dataset, site: int, halfwidth: int = 1, decades: float = 1.0) -> float:
    """Fraction of the final-window samples whose DVD maximum lies within ``halfwidth`` of ``site``."""
    t = np.asarray(ds["time"].values, dtype=float)
    w = np.asarray(ds["dvd"].values)[final_window(t, decades)]
    peak = np.asarray(ds["site"].values)[np.argmax(w, axis=1)]
    return float(np.mean(np.abs(peak - site) <= halfwidth))


def equipartition_eta(ds: xr.Dataset) -> float:
    """<eta> = (1 - C)/(ln N - S(0)) as stored with eta (recomputed from S(0) if absent)."""
    if "equipartition_value" in ds["eta"].attrs:
        return float(ds["eta"].attrs["equipartition_value"])
    from chainchaos.observe.formulas import equipartition_eta as value

    return float(value(float(ds["spectral_entropy"].values[0]), ds.sizes["mode"]))


def max_energy_error(ds: xr.Dataset) -> float | None:
    """A scene's largest relative energy error (attribute), or the largest over the valid runs of
    an energy scan (variable ``energy_error_max``); None when the product records none."""
    if "energy_error_max" in ds:
        err = np.where(ds["valid"].values == 1, ds["energy_error_max"].values, np.nan)
        return float(np.nanmax(err)) if np.isfinite(err).any() else None
    return float(ds.attrs["max_energy_error"]) if "max_energy_error" in ds.attrs else None


# --------------------------------------------------------------------------------------------
# The chain file and the ensemble of Fig. 1(a)
# --------------------------------------------------------------------------------------------


def mode_energy_profile(chain: xr.Dataset, mode: int) -> np.ndarray:
    """Normalised energy density of linear mode ``mode`` (u = mode shape, p = 0, bond energies
    split half-half, docs/conventions.md#mode-energy-density), from the chain file's K2 and mode_shape."""
    U = np.asarray(chain["mode_shape"].values)[:, mode - 1]
    y = np.diff(np.concatenate([[0.0], U, [0.0]]))
    bond = 0.5 * np.asarray(chain["K2"].values) * y**2
    h = 0.5 * (bond[:-1] + bond[1:])
    return h / h.sum()


def mode_peak_site(chain: xr.Dataset, mode: int) -> int:
    """Bead of the energy maximum of linear mode ``mode``."""
    return int(np.asarray(chain["site"].values)[np.argmax(mode_energy_profile(chain, mode))])


def taylor_sign_barrier(chain, site: int = 21) -> float:
    """Largest energy a single-bead displacement of bead ``site`` reaches in the FPUT chain with the
    Taylor sign of K4 (``chain``: a :class:`chainchaos.system.chain.Chain` with K4 < 0): the maximum over
    u0 > 0 of the potential energy along that excitation. Above it no single-bead initial state of
    the paper's kind exists."""
    from scipy.optimize import minimize_scalar

    from chainchaos.system.initial import excitation_energy

    fput = "fput"
    upper = 1.0
    while excitation_energy(fput, chain, site, 2 * upper) > excitation_energy(fput, chain, site, upper):
        upper *= 2
        if upper > 1e6:
            return float("inf")
    best = minimize_scalar(lambda u: -excitation_energy(fput, chain, site, u), bounds=(0.0, 2 * upper),
                           method="bounded", options={"xatol": 1e-10})
    return float(-best.fun)


def _curve(ensemble: xr.Dataset, alpha: float) -> np.ndarray:
    return np.asarray(ensemble["mean_participation"].sel(alpha=alpha, method="nearest").values)


def localized_mode_count(ensemble: xr.Dataset, alpha: float, p_max: float = 3.0) -> int:
    """Number of ranks whose mean participation number is at most ``p_max``."""
    return int(np.sum(_curve(ensemble, alpha) <= p_max))


def localized_level(ensemble: xr.Dataset, alpha: float, n: int = 10) -> float:
    """Mean <P> of the ``n`` most localized ranks (the tail of the sorted curve)."""
    return float(np.mean(np.sort(_curve(ensemble, alpha))[:n]))


def most_extended(ensemble: xr.Dataset, alpha: float) -> float:
    """<P> of the most extended rank (rank 1)."""
    return float(np.max(_curve(ensemble, alpha)))


def limiting_curve_deviation(ensemble: xr.Dataset, alpha_min: float = 4.0) -> float:
    """Largest rank-wise relative difference between the <P> curves of the alphas >= alpha_min
    (relative to their rank-wise mean); 0 when they coincide."""
    alphas = [a for a in ensemble["alpha"].values if a >= alpha_min - 1e-9]
    if len(alphas) < 2:
        return float("nan")
    curves = np.array([_curve(ensemble, a) for a in alphas])
    return float(np.max((curves.max(axis=0) - curves.min(axis=0)) / curves.mean(axis=0)))
