"""A study's ensemble statistics, in the form the disordered-lattice literature plots them.

Over the realizations of every (model, energy), lane 0 (the unperturbed orbit), valid runs only:

- ``mean_log10_<x>``: <log10 x>(t) for x = P, m2 and Lambda (the average of the logarithm, as in
  Flach, Krimer & Skokos, PRL 102, 024101 (2009) and Skokos, Gkolias & Flach, PRL 111, 064101
  (2013)), with ``count_<x>`` the realizations that enter each time; ``mean_log10_abs_mlce`` and
  ``count_abs_mlce`` the same of |Lambda| (a regular orbit's Lambda may be <= 0);
- ``quantile_log10_<x>``: its quantiles over the realizations (0.1, 0.25, the median, 0.75, 0.9);
- ``slope_log10_<x>``: the running slope d<log10 x>/d log10 t, the least-squares slope over a
  window of ``criteria.slope_window_decades`` decades centred on each sample (its rule: every
  sample within half a window on either side, at least three of them; NaN elsewhere);
- per realization, a verdict from its lanes (``verdict_<flag>``: 1 when every valid lane says
  delocalized / chaotic, 0 when none does, -1 undecided when they split), and over the decided
  realizations the fraction with Wilson 95% bands (``fraction_<flag>``, ``_lower``, ``_upper``)
  and the counts (``count_<flag>``, ``count_decided_<flag>``, ``count_undecided_<flag>``).

Every sum is taken in index order and every logarithm is fdlibm's (``kernels.exactmath``), so
the statistics are the same bits on every CPU.
"""

import warnings

import numpy as np
import xarray as xr

from chainchaos.kernels import exactmath

QUANTILES = np.array([0.1, 0.25, 0.5, 0.75, 0.9])
#: The series averaged as logarithms over realizations, and how they read.
LOG_SERIES = {"participation": "P", "second_moment": "m2", "mlce": "Lambda"}
#: The verdicts counted over realizations.
FLAGS = ("delocalized", "chaotic", "chaotic_gali")
LN10 = exactmath.ln(10.0)


def log10(x) -> np.ndarray:
    """log10 x elementwise, NaN where x <= 0 or not finite (fdlibm's ln / ln 10)."""
    x = np.asarray(x, dtype=np.float64)
    positive = np.isfinite(x) & (x > 0)
    return np.where(positive, exactmath.log(np.where(positive, x, 1.0)) / LN10, np.nan)


def ordered_mean(x: np.ndarray, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """(mean over ``axis`` of the finite values, their count), the terms added in index order."""
    x = np.moveaxis(np.asarray(x, dtype=np.float64), axis, 0)
    finite = np.isfinite(x)
    # a running sum from zero: add.accumulate adds term after term (never pairwise, as sum may)
    terms = np.concatenate([np.zeros((1, *x.shape[1:])), np.where(finite, x, 0.0)])
    total, count = np.add.accumulate(terms, axis=0)[-1], finite.sum(axis=0, dtype=np.int32)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / np.maximum(count, 1), np.nan), count


def running_slope(log_t: np.ndarray, y: np.ndarray, window: float) -> np.ndarray:
    """d y / d log t by least squares over the samples within ``window`` / 2 of each sample
    (at least three finite ones, else NaN); ``y`` (..., S) against ``log_t`` (S,)."""
    y = np.asarray(y, dtype=np.float64)
    out = np.full(y.shape, np.nan)
    for i in range(log_t.size):
        near = np.isfinite(log_t) & (np.abs(log_t - log_t[i]) <= window / 2)
        for index in np.ndindex(y.shape[:-1]):
            use = near & np.isfinite(y[index])
            if np.isfinite(log_t[i]) and use.sum() >= 3:
                out[index + (i,)] = exactmath.line_slope(log_t[use], y[index][use])
    return out


def realization_verdicts(flag: xr.DataArray, valid: xr.DataArray) -> np.ndarray:
    """Per (model, energy, realization): 1 if every valid lane has the flag, 0 if none, -1 if
    they split, -2 without a valid lane."""
    ok = valid.values == 1
    yes = ((flag.values == 1) & ok).sum(axis=-1)
    n = ok.sum(axis=-1)
    return np.where(n == 0, -2, np.where(yes == n, 1, np.where(yes == 0, 0, -1))).astype(np.int8)


def statistics(merged: xr.Dataset, window_decades: float) -> xr.Dataset:
    """The ensemble statistics (module docstring) of a merged study, on (model, energy[, time])."""
    valid0 = merged["valid"].isel(lane=0) == 1
    log_t = log10(merged["time"].values)
    data = {}
    for name, short in LOG_SERIES.items():
        if name not in merged:
            continue
        x = log10(merged[name].isel(lane=0).where(valid0).values)  # (model, energy, realization, time)
        mean, count = ordered_mean(x, axis=2)
        data[f"mean_log10_{name}"] = (("model", "energy", "time"), mean, {
            "units": "1", "long_name": f"mean over the valid realizations of log10 {short}"})
        data[f"count_{name}"] = (("model", "energy", "time"), count, {
            "units": "1", "long_name": f"valid realizations with a finite log10 {short}"})
        with warnings.catch_warnings():  # an all-NaN slice has a NaN quantile, as wanted
            warnings.simplefilter("ignore", RuntimeWarning)
            q = np.nanquantile(x, QUANTILES, axis=2)  # (quantile, model, energy, time)
        data[f"quantile_log10_{name}"] = (("model", "energy", "quantile", "time"), np.moveaxis(q, 0, 2), {
            "units": "1", "long_name": f"quantiles over the valid realizations of log10 {short}"})
        data[f"slope_log10_{name}"] = (("model", "energy", "time"), running_slope(log_t, mean, window_decades), {
            "units": "1", "long_name": f"running slope d<log10 {short}>/d log10 t over {window_decades:g} decades"})
    if "mlce" in merged:  # a regular orbit's Lambda may be <= 0: its log10 |Lambda| still decays as t^-1
        x = log10(abs(merged["mlce"].isel(lane=0).where(valid0).values))
        mean, count = ordered_mean(x, axis=2)
        data["mean_log10_abs_mlce"] = (("model", "energy", "time"), mean, {
            "units": "1", "long_name": "mean over the valid realizations of log10 |Lambda|"})
        data["count_abs_mlce"] = (("model", "energy", "time"), count, {
            "units": "1", "long_name": "valid realizations with a finite log10 |Lambda|"})
    for flag in FLAGS:
        if flag == "chaotic_gali" and not (merged[flag] >= 0).any():
            continue
        verdict = realization_verdicts(merged[flag], merged["valid"])
        k, n = (verdict == 1).sum(axis=-1), (verdict >= 0).sum(axis=-1)
        lo, hi = wilson_interval(k, n)
        with np.errstate(invalid="ignore", divide="ignore"):
            fraction = np.where(n > 0, k / np.maximum(n, 1), np.nan)
        data[f"verdict_{flag}"] = (("model", "energy", "realization"), verdict, {
            "units": "1", "long_name": f"{flag} by every valid lane (1), by none (0), lanes split (-1), no valid lane (-2)",
            "flag_values": np.array([-2, -1, 0, 1], dtype=np.int8),
            "flag_meanings": "no_valid_lane undecided no yes"})
        data[f"fraction_{flag}"] = (("model", "energy"), fraction, {
            "units": "1", "long_name": f"fraction of the decided realizations {flag}"})
        data[f"fraction_{flag}_lower"] = (("model", "energy"), lo, {"units": "1", "long_name": "Wilson 95% interval, lower bound"})
        data[f"fraction_{flag}_upper"] = (("model", "energy"), hi, {"units": "1", "long_name": "Wilson 95% interval, upper bound"})
        data[f"count_{flag}"] = (("model", "energy"), k.astype(np.int32), {"units": "1", "long_name": f"realizations {flag}"})
        data[f"count_decided_{flag}"] = (("model", "energy"), n.astype(np.int32), {
            "units": "1", "long_name": "realizations whose valid lanes agree"})
        data[f"count_undecided_{flag}"] = (("model", "energy"), (verdict == -1).sum(axis=-1).astype(np.int32), {
            "units": "1", "long_name": "realizations whose valid lanes split"})
    if "density_map" in merged:  # the maps of one orbit for the figure maps: the first valid realization's lane 0
        first = np.argmax(valid0.values, axis=-1)  # (model, energy); 0 where none is valid
        maps = merged["density_map"].isel(lane=0).values
        shown = np.stack([[maps[m, e, first[m, e]] for e in range(first.shape[1])] for m in range(first.shape[0])])
        data["shown_density_map"] = (("model", "energy", "map_time", "site"), shown, {
            **merged["density_map"].attrs, "comment": "the orbit of realization shown_realization, lane 0"})
        data["shown_realization"] = (("model", "energy"), first.astype(np.int32), {
            "units": "1", "long_name": "the realization whose maps shown_density_map holds: the first valid one"})
    out = xr.Dataset(data, coords={k: merged[k] for k in ("model", "energy", "realization", "time", "map_time")
                                   if k in merged.coords})
    out = out.assign_coords(quantile=("quantile", QUANTILES, {"units": "1", "long_name": "probability of the quantile"}))
    out.attrs.update(slope_window_decades=float(window_decades), confidence_interval="Wilson score interval, 95%",
                     statistics_rule=("over the valid realizations, lane 0; running slopes by least squares over "
                                      f"{window_decades:g} decades centred on each sample, at least 3 samples"))
    return out


def wilson_interval(k, n, z: float = 1.959963984540054):
    """Wilson score interval of a binomial proportion k/n (95% by default); NaN where n = 0."""
    k, n = np.asarray(k, float), np.asarray(n, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        phat = k / n
        denom = 1 + z**2 / n
        centre = (phat + z**2 / (2 * n)) / denom
        half = z * np.sqrt(phat * (1 - phat) / n + z**2 / (4 * n**2)) / denom
    return np.clip(centre - half, 0, 1), np.clip(centre + half, 0, 1)
