"""Reductions of a sampled time series to the numbers a verdict is made of.

The samples are log-spaced in time (``driver.sample_steps``), optionally with a dense uniform
tail over the last decade (``orbits.sample_schedule``), so every reduction here weights by time,
not by sample:

- :func:`time_average`: (1/(t1 - t0)) int_{t0}^{t1} y dt, trapezoidal on the samples. A plain mean of
  log-spaced samples is a mean over log t, which over-weights early times;
- :func:`loglog_slope`: d log10 y / d log10 t fitted over a window, and :func:`is_chaotic`, the
  paper's reading of Lambda(t): a regular orbit follows Lambda ~ ln(t)/t (slope near -1), a
  chaotic one levels off (slope near 0) while its deviation vector grows faster than linearly;
- :func:`sustained_onset`: the first time from which a series stays above a threshold for a given
  span of log time, so that one oscillation peak cannot set an onset;
- :func:`gali_crossing`: the time at which GALI_k first falls below its threshold, the second
  indicator's "chaotic" (on an N-torus GALI_k with k <= N stays of order one; on a chaotic orbit it
  decays exponentially).

All times are in units of 1/omega_max; every function takes 1-d arrays of sample times ``t`` and
values ``y`` and ignores t <= 0 where a logarithm is taken.
"""

import numpy as np

from chainchaos.errors import require
from chainchaos.kernels import exactmath
from chainchaos.observe.formulas import finite_time_mlce


def time_average(t, y, t0: float, t1: float | None = None) -> float:
    """Time average (1/(t1 - t0)) int_{t0}^{t1} y(t) dt by the trapezoidal rule on the samples,
    y interpolated linearly at t0 and t1 (t1 defaults to the last sample). NaN if the window holds
    no sample interval."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    t1 = float(t[-1]) if t1 is None else float(t1)
    t0 = float(t0)
    if not (t1 > t0 and t0 >= t[0] and t1 <= t[-1]):
        return float("nan")
    inside = (t > t0) & (t < t1)
    tt = np.concatenate(([t0], t[inside], [t1]))
    yy = np.concatenate(([np.interp(t0, t, y)], y[inside], [np.interp(t1, t, y)]))
    # by hand until the NumPy floor (1.26) is 2.0, which has numpy.trapezoid: the same products and
    # pairwise sum, the same bits (tests/observe: equal on random samples)
    return float(np.sum(0.5 * (yy[1:] + yy[:-1]) * np.diff(tt)) / (t1 - t0))


def log_time_median(t, y, t0: float, t1: float | None = None) -> float:
    """Median of y over log time on [t0, t1] (t1 defaults to the last sample): each sample
    weighs the stretch of log10 t it stands for (from the midpoints to its neighbours, clipped to
    the window), so a stretch sampled densely (a run's last decade) counts no more than it lasts
    on a logarithmic time axis. The lower weighted median; NaN if no sample lies in the window."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    t1 = float(t[-1]) if t1 is None else float(t1)
    inside = (t >= t0) & (t <= t1) & np.isfinite(y)
    if not inside.any():
        return float("nan")
    x = exactmath.log10(t[inside])
    edges = np.concatenate(([exactmath.log10(np.array([float(t0)]))[0]], 0.5 * (x[1:] + x[:-1]),
                            [exactmath.log10(np.array([t1]))[0]]))
    weight = np.diff(edges)
    # by hand until the NumPy floor (1.26) is 2.0, which has numpy.quantile(weights=...,
    # method="inverted_cdf"): the same lower weighted median (tests/observe: equal on random samples)
    order = np.argsort(y[inside], kind="stable")
    cumulative = np.cumsum(weight[order])
    return float(y[inside][order][np.searchsorted(cumulative, 0.5 * cumulative[-1])])


def final_average(t, y, decades: float = 1.0) -> float:
    """Time average over the last ``decades`` decades of the run, t_end 10^-decades <= t <= t_end."""
    t = np.asarray(t, dtype=float)
    return time_average(t, y, t[-1] * 10.0 ** (-decades), t[-1])


def loglog_slope(t, y, t0: float, t1: float) -> float:
    """Least-squares slope of log10 y against log10 t over the samples with t0 <= t <= t1 and y > 0
    (NaN with fewer than three such samples)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    sel = (t >= t0) & (t <= t1) & (t > 0) & (y > 0) & np.isfinite(y)
    if sel.sum() < 3:
        return float("nan")
    return exactmath.line_slope(exactmath.log10(t[sel]), exactmath.log10(y[sel]))


def excess_growth(t, log_growth, t0: float, t1: float) -> float:
    """ln(|v(t1)|/|v(t0)|) - ln(t1/t0): how much faster than linearly the deviation vector grew
    over [t0, t1] (log_growth = ln(|v(t)|/|v(0)|) interpolated linearly in t). A regular orbit's
    |v| grows at most linearly, so this stays of order 1 or below; a chaotic one's grows like
    lambda (t1 - t0)."""
    t = np.asarray(t, dtype=float)
    g = np.asarray(log_growth, dtype=float)
    return float(np.interp(t1, t, g) - np.interp(t0, t, g) - exactmath.ln(t1 / t0))


def is_chaotic(t, log_growth, slope_threshold: float = -0.5, growth_margin: float = 2.0,
               decades: float = 1.0, t_end: float | None = None) -> bool:
    """Chaotic by the paper's reading of Lambda(t) = log_growth / t over the ``decades`` decades
    ending at ``t_end`` (default: the end of the run): Lambda has left the t^-1 law of a regular
    orbit and levels off, i.e. its log-log slope exceeds ``slope_threshold``, and the deviation
    vector grew more than a regular orbit can, :func:`excess_growth` > ``growth_margin``.

    The slope alone misreads a regular orbit whose ln|v| is still of order 1: ln|v| rising from
    0.3 to 2.3 over a decade is linear growth of |v|, yet gives Lambda a slope near 0. The growth
    condition rules that out; the slope condition rules out a transient burst on an orbit whose
    Lambda still falls like 1/t.
    """
    t = np.asarray(t, dtype=float)
    g = np.asarray(log_growth, dtype=float)
    end = float(t[-1]) if t_end is None else min(float(t_end), float(t[-1]))
    start = end * 10.0 ** (-decades)
    if start < t[t > 0][0]:
        return False
    slope = loglog_slope(t, finite_time_mlce(g, t), start, end)
    return bool(np.isfinite(slope) and slope > slope_threshold
                and excess_growth(t, g, start, end) > growth_margin)


def sustained_onset(t, y, threshold: float, hold_decades: float = 0.5, t_min: float = 0.0) -> float:
    """First sample time t_i >= t_min with y > threshold at every sample of
    [t_i, min(t_i 10^hold_decades, t_end)]: a crossing that lasts, not a single peak. A crossing
    whose hold window runs past the end must last to the end. NaN if there is none."""
    t = np.asarray(t, dtype=float)
    above = np.asarray(y, dtype=float) > threshold
    # below[i]: index of the first sample at or after i that is not above the threshold
    n = t.size
    next_below = np.full(n + 1, n)
    for i in range(n - 1, -1, -1):
        next_below[i] = i if not above[i] else next_below[i + 1]
    for i in np.flatnonzero(above & (t >= t_min)):
        end = min(t[i] * 10.0 ** hold_decades, t[-1])
        if next_below[i] == n or t[next_below[i]] > end:
            return float(t[i])
    return float("nan")


def log_time_smooth(t, y, decades: float) -> np.ndarray:
    """Running mean of y over a window of ``decades`` in log10 t centred on each sample (t > 0)."""
    x = exactmath.log10(np.asarray(t, dtype=float))
    y = np.asarray(y, dtype=float)
    inside = np.abs(x[:, None] - x[None, :]) <= decades / 2.0
    return (inside * y[None, :]).sum(axis=1) / inside.sum(axis=1)


def chaos_onset(t, log_growth, slope_threshold: float = -0.5, growth_margin: float = 2.0,
                decades: float = 1.0, t_min: float = 10.0) -> float:
    """Onset of chaos: the earliest window end from which on :func:`is_chaotic` holds for the
    ``decades``-wide window ending at every later sample, to the end of the run (a sustained
    crossing); returned as that window's geometric centre t_end 10^(-decades/2), where the
    departure from the t^-1 law lies. NaN when the orbit is not chaotic at the end."""
    t = np.asarray(t, dtype=float)
    require(decades > 0, "decades", decades, "> 0")
    ends = t[t >= t_min * 10.0 ** decades]
    if ends.size == 0:
        return float("nan")
    chaotic = np.array([is_chaotic(t, log_growth, slope_threshold, growth_margin, decades, end) for end in ends])
    if not chaotic[-1]:
        return float("nan")
    regular = np.flatnonzero(~chaotic)
    first = 0 if regular.size == 0 else regular[-1] + 1
    return float(ends[first] * 10.0 ** (-decades / 2))


def gali_crossing(t, log_gali, threshold: float, end: float | None = None) -> float:
    """The first sample time t_i <= ``end`` (default: the last) at which ln GALI_k < ln(threshold):
    when GALI_k calls the orbit chaotic (Skokos, Bountis & Antonopoulos, Physica D 231, 30 (2007)).
    NaN when it stays at or above the threshold (regular by GALI_k up to ``end``); a sample where
    ln GALI_k is NaN (not recorded) is not below."""
    require(0 < threshold < 1, "threshold", threshold, "0 < threshold < 1 (GALI_k is at most 1)")
    t = np.asarray(t, dtype=float)
    with np.errstate(invalid="ignore"):
        below = np.asarray(log_gali, dtype=float) < np.log(threshold)
    if end is not None:
        below &= t <= end * (1 + 1e-12)
    first = np.flatnonzero(below)
    return float(t[first[0]]) if first.size else float("nan")


def within_factor(x, target: float, factor: float) -> bool:
    """x / target lies in [1/factor, factor] (False for None, NaN or x <= 0)."""
    return x is not None and bool(np.isfinite(x) and x > 0 and 1.0 / factor <= x / target <= factor)


def spreading_onset(t, P, factor: float, smoothing_decades: float, t_ref: float, hold_decades: float) -> float:
    """Onset of spreading: the first time t >= t_ref from which the log-time running mean of P
    (:func:`log_time_smooth`) stays above ``factor`` times its value at t_ref (the end of the
    initial transient) for ``hold_decades``; NaN when never. Samples at t <= 0 are ignored."""
    t, P = _positive(t, P)
    smooth = log_time_smooth(t, P, smoothing_decades)
    after = t >= t_ref
    if not after.any():
        return float("nan")
    reference = smooth[np.flatnonzero(after)[0]]
    return sustained_onset(t, smooth, factor * reference, hold_decades, t_ref)


def saturation_time(t, P, fraction: float, smoothing_decades: float, final_decades: float,
                    hold_decades: float) -> float:
    """First time from which the smoothed P stays above ``fraction`` of its time average over
    the last ``final_decades`` decades for ``hold_decades``; NaN when never."""
    t, P = _positive(t, P)
    target = fraction * final_average(t, P, final_decades)
    return sustained_onset(t, log_time_smooth(t, P, smoothing_decades), target, hold_decades)


def _positive(t, y):
    t = np.asarray(t, dtype=float)
    keep = t > 0
    return t[keep], np.asarray(y, dtype=float)[keep]
