"""The paper's quantitative statements, measured on the pipeline's results, each with a verdict.

Two layers:

* measurement functions, one quantity each, computed from the NetCDF Datasets of the data contract
  (DESIGN section 7): final participation number, onset time of spreading, whether an orbit is
  chaotic, gap statistics, entropy plateaus, ensemble statistics of Fig. 1(a). Every choice a
  measurement makes (windows, thresholds, smoothing) is a field of :class:`Criteria`, which the
  pipeline fills from the config block ``claims:``;
* :func:`evaluate_claims`, the table of claims: for each statement of the paper its value, the
  measured value with its unit, the criterion, the numerical error of the scenes it rests on, and a
  verdict computed from stated tolerances.

Verdicts (:data:`VERDICTS`):

``reproduced``
    the measured value satisfies the criterion;
``differs``
    it does not; the row carries the reason (a known one, e.g. a convention, when there is one);
``not testable at this scale``
    the run ends before the time the claim needs (quick scale stops at t = 1e3 while most of the
    paper's statements concern t = 1e4..1e5). A claim that holds "for the whole run" (an orbit
    stays regular, a packet stays localized, at most one gap is open) is refuted by a short run
    that already violates it, so such a claim can still be ``differs`` at a small scale.

No number of the pipeline is typed here: the only literals are the paper's values and the
criteria, and the paper's values are the ones printed in its text.
"""

from __future__ import annotations

import csv
import math
from dataclasses import asdict, dataclass, field, fields

import numpy as np
import xarray as xr

from chainchaos import scan as _scan

VERDICTS = ("reproduced", "differs", "not testable at this scale")
REPRODUCED, DIFFERS, UNTESTABLE = VERDICTS

REALIZATION = ("realization: the energies at which a packet starts to spread or its orbit turns chaotic are "
               "properties of the disorder realization (the paper itself finds FPUT alternating between "
               "localized and delocalized states with energy); our chain matches the paper's mode 34 and "
               "overlaps, not its unpublished radii")


# --------------------------------------------------------------------------------------------
# Criteria: every choice a measurement makes, with its default (config block `claims:`).
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Tolerances:
    """How far a measured value may lie from the paper's and still count as reproduced.

    displacement
        absolute, for u_21(0) and the overlaps delta_21, delta_22: exact properties of the chain
        and the initial state, which the paper quotes to 0.01.
    mode_participation
        absolute, for participation numbers of linear modes (mode 34, the Fig. 1(a) levels): exact
        linear algebra, quoted to 0.1.
    participation_relative
        relative, for participation numbers read from the paper's (smoothed) time series and from
        the Fig. 1(a) curve: P ~ 1.8, P ~ 26, P_D ~ 20.
    count
        absolute, for "about 10 modes".
    time_factor
        multiplicative, for times read off the paper's logarithmic time axes (t ~ 2e2, 4e3):
        reproduced when measured/paper lies in [1/f, f].
    mlce_factor
        multiplicative, for the order-of-magnitude statement Lambda ~ 1e-3.
    eta_plateau
        absolute, for entropy plateaus read from the paper's eta(t) plots (0.5, 0.7, 0.8, 0.82).
    eta_equipartition
        absolute, for "close to <eta>" at the end of a run.
    limiting_curve_relative
        relative, for "<P> reaches a limiting curve for alpha >= 4": largest rank-wise relative
        difference between the alpha >= 4 curves.
    threshold_factor
        multiplicative, for the threshold energies of Sec. III (H ~ 1.8, 2.8, 2.9): the paper ran a
        handful of energies, so its thresholds are bracketed by neighbouring runs (Hertz: between
        0.5 and 1.8), not measured; reproduced when the scan's threshold / paper's lies in [1/f, f].
    """

    displacement: float = 0.01
    mode_participation: float = 0.1
    participation_relative: float = 0.1
    count: int = 3
    time_factor: float = 2.0
    mlce_factor: float = 3.0
    eta_plateau: float = 0.1
    eta_equipartition: float = 0.05
    limiting_curve_relative: float = 0.25
    threshold_factor: float = 1.5


@dataclass(frozen=True)
class Criteria:
    """The choices of the measurements (config block ``claims:``; times in units of 1/omega_max).

    final_window_decades
        a scene's "final" value of P, P_D or any series is its mean over the samples of the last
        ``final_window_decades`` decades of the run, t >= t_final 10^-w (samples are log-spaced,
        so this is a mean over log time).
    eta_final_window_decades
        the same for the final eta, narrower because the paper's eta keeps falling to the end.
    smoothing_decades
        before a threshold is applied to P(t) it is smoothed by a running mean over a window of
        this width in log10 t (the paper plots LOWESS-smoothed P; the raw P of a single-mode
        state oscillates between about 1.2 and 2.8 with the mode's period).
    localized_p_max, delocalized_p_min
        a packet is localized when its final P <= localized_p_max and delocalized when its final
        P >= delocalized_p_min (N = 40; between the two it is "partly spread").
    spreading_p_threshold
        the level of a localized phase: its mean P over [plateau_start, plateau_end[scene]] must
        stay below this (the paper: "P < 3 up to t ~ 2e2").
    spreading_factor
        the onset of spreading is the first time t >= plateau_start at which the smoothed P
        exceeds this factor times its value at t = plateau_start (the end of the initial
        transient): the time the paper's P "starts to increase".
    saturation_fraction
        saturation time: the first time the smoothed P reaches this fraction of its final value.
    chaos_margin
        an orbit is chaotic when, at the end of the run, ln(|v(t)|/|v(0)|) - ln(1 + t) = t Lambda(t)
        - ln(1 + t) exceeds this: the deviation vector of a regular orbit grows at most linearly in
        t, that of a chaotic one exponentially (the same test as the energy scan's ``chaos_margin``).
    chaos_slope, chaos_window_decades
        the onset of chaos is dated by the least-squares slope of log10 Lambda against log10 t in
        windows of ``chaos_window_decades`` decades: Lambda of a regular orbit falls like
        ln(t)/t (slope -0.5 to -0.9 for the short logarithms of these runs), that of a chaotic one
        levels off (slope 0); the onset is where the slope rises above ``chaos_slope`` for good.
    localized_mode_p_max
        Fig. 1(a): a mode (rank) counts as strongly localized when its mean P is at most this.
    n_localized_modes
        Fig. 1(a): the level of the localized part of the curve is the mean <P> of this many most
        localized ranks (the paper's "about 10").
    gap_spread_distance
        a gap has left the excited bead when it opens on a bond at least this many bonds away
        from the two bonds of that bead (bonds s and s+1 are at distance 0).
    gap_coverage
        gaps "cover the whole lattice" when at least this fraction of the N+1 bonds has opened.
    dvd_site_halfwidth, dvd_site_fraction
        the DVD is localized at the excited site when its maximum lies within this many sites of
        it in at least this fraction of the final-window samples.
    eta_near_one
        eta "stays close to 1" when its final value is at least this.
    plateau_start, plateau_end
        an entropy plateau is the median of eta(t) over [plateau_start, plateau_end[scene]]: from
        the end of the initial transient to half the time at which the paper says eta leaves the
        plateau (FPUT 2.9: falls at 5e3; FPUT 8.7381: at 1e4; FPUT 4: "for the last two decades",
        i.e. 1e3; Hertz 1.8: spreads from 2e2; Hertz 3: no time given, the same as 1.8).
    """

    final_window_decades: float = 1.0
    eta_final_window_decades: float = 0.25
    smoothing_decades: float = 0.5
    localized_p_max: float = 5.0
    delocalized_p_min: float = 10.0
    spreading_p_threshold: float = 3.0
    spreading_factor: float = 2.0
    saturation_fraction: float = 0.9
    chaos_margin: float = 5.0
    chaos_slope: float = -0.5
    chaos_window_decades: float = 1.0
    localized_mode_p_max: float = 3.0
    n_localized_modes: int = 10
    gap_spread_distance: int = 2
    gap_coverage: float = 0.9
    dvd_site_halfwidth: int = 1
    dvd_site_fraction: float = 0.8
    eta_near_one: float = 0.9
    plateau_start: float = 10.0
    plateau_end: dict = field(default_factory=lambda: {
        "hertz_H1.8": 100.0, "hertz_H3": 100.0, "fput_H2.9": 2500.0, "fput_H4": 500.0,
        "fput_H8.7381": 5000.0})
    tolerance: Tolerances = field(default_factory=Tolerances)

    @classmethod
    def from_config(cls, block: dict | None) -> "Criteria":
        """Criteria from the config block ``claims:`` (missing keys keep their defaults)."""
        block = dict(block or {})
        unknown = set(block) - {f.name for f in fields(cls)}
        if unknown:
            raise ValueError(f"config block claims: unknown key(s) {sorted(unknown)}")
        tol = block.pop("tolerance", {}) or {}
        unknown = set(tol) - {f.name for f in fields(Tolerances)}
        if unknown:
            raise ValueError(f"config block claims.tolerance: unknown key(s) {sorted(unknown)}")
        defaults = cls()
        if "plateau_end" in block:
            block["plateau_end"] = {**defaults.plateau_end, **block["plateau_end"]}
        return cls(**block, tolerance=Tolerances(**tol))


# --------------------------------------------------------------------------------------------
# Measurements on time series
# --------------------------------------------------------------------------------------------


def _positive_times(ds: xr.Dataset, var: str) -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(ds["time"].values, dtype=float)
    y = np.asarray(ds[var].values, dtype=float)
    keep = t > 0
    return t[keep], y[keep]


def final_window(t: np.ndarray, decades: float) -> np.ndarray:
    """Mask of the samples in the last ``decades`` decades: t >= t[-1] 10^-decades, t > 0."""
    t = np.asarray(t, dtype=float)
    return (t > 0) & (t >= t[-1] * 10.0 ** (-decades))


def final_mean(ds: xr.Dataset, var: str, decades: float = 1.0) -> float:
    """Mean of ``var(time)`` over the samples of the last ``decades`` decades of the run."""
    t, y = _positive_times(ds, var)
    return float(np.mean(y[final_window(t, decades)]))


def window_mean(ds: xr.Dataset, var: str, t0: float, t1: float) -> float:
    """Mean of ``var(time)`` over the samples with t0 <= t <= t1 (NaN when there is none)."""
    t, y = _positive_times(ds, var)
    sel = (t >= t0) & (t <= t1)
    return float(np.mean(y[sel])) if sel.any() else float("nan")


def window_median(ds: xr.Dataset, var: str, t0: float, t1: float) -> float:
    """Median of ``var(time)`` over the samples with t0 <= t <= t1 (NaN when there is none)."""
    t, y = _positive_times(ds, var)
    sel = (t >= t0) & (t <= t1)
    return float(np.median(y[sel])) if sel.any() else float("nan")


def log_time_smooth(t: np.ndarray, y: np.ndarray, decades: float) -> np.ndarray:
    """Running mean of y over a window of ``decades`` in log10 t centred on each sample (t > 0)."""
    x = np.log10(np.asarray(t, dtype=float))
    y = np.asarray(y, dtype=float)
    inside = np.abs(x[:, None] - x[None, :]) <= decades / 2.0
    return (inside * y[None, :]).sum(axis=1) / inside.sum(axis=1)


def first_time_above(t: np.ndarray, y: np.ndarray, threshold: float) -> float | None:
    """First sample time with y > threshold, or None."""
    above = np.flatnonzero(np.asarray(y) > threshold)
    return float(t[above[0]]) if above.size else None


def spreading_onset(ds: xr.Dataset, factor: float = 2.0, smoothing_decades: float = 0.5,
                    t_ref: float = 10.0) -> float | None:
    """Onset of spreading: the first time t >= t_ref at which the log-time running mean of P
    exceeds ``factor`` times its value at t_ref (None when it never does)."""
    t, P = _positive_times(ds, "participation")
    smooth = log_time_smooth(t, P, smoothing_decades)
    after = t >= t_ref
    if not after.any():
        return None
    reference = smooth[np.flatnonzero(after)[0]]
    return first_time_above(t[after], smooth[after], factor * reference)


def saturation_time(ds: xr.Dataset, fraction: float = 0.9, smoothing_decades: float = 0.5,
                    final_decades: float = 1.0) -> float | None:
    """First time the smoothed P reaches ``fraction`` of its final value (final_mean)."""
    t, P = _positive_times(ds, "participation")
    target = fraction * final_mean(ds, "participation", final_decades)
    reached = np.flatnonzero(log_time_smooth(t, P, smoothing_decades) >= target)
    return float(t[reached[0]]) if reached.size else None


def mlce_slope(ds: xr.Dataset, decades: float = 1.0, t_end: float | None = None) -> float:
    """Least-squares slope of log10 Lambda(t) against log10 t over the last ``decades`` decades
    before ``t_end`` (default: the end of the run). About -1 for a regular orbit (Lambda ~ ln t / t),
    about 0 for a chaotic one (Lambda -> const > 0)."""
    t, L = _positive_times(ds, "mlce")
    end = t[-1] if t_end is None else t_end
    sel = (t <= end) & (t >= end * 10.0 ** (-decades)) & (L > 0) & np.isfinite(L)
    if sel.sum() < 3:
        return float("nan")
    return float(np.polyfit(np.log10(t[sel]), np.log10(L[sel]), 1)[0])


def excess_growth(ds: xr.Dataset) -> float:
    """ln|v(t)|/|v(0)| - ln(1 + t) at the end of the run, from Lambda: t Lambda(t) - ln(1 + t).

    The deviation vector of a regular orbit grows at most linearly, so this stays of order 1 (or
    negative); on a chaotic orbit it grows like lambda t."""
    t, L = _positive_times(ds, "mlce")
    return float(t[-1] * L[-1] - np.log1p(t[-1]))


def is_chaotic(ds: xr.Dataset, margin: float = 5.0) -> bool:
    """Chaotic when the deviation vector has grown e^margin times more than linearly by the end."""
    return bool(excess_growth(ds) > margin)


def chaos_onset(ds: xr.Dataset, slope_threshold: float = -0.5, decades: float = 1.0,
                t_min: float = 10.0) -> float | None:
    """Onset of chaos: the earliest sample time t >= t_min from which on the local slope of
    log Lambda (fitted over the ``decades`` decades ending at each later sample) stays above
    ``slope_threshold`` up to the end of the run; None when the orbit is not chaotic at the end.
    The time returned is the geometric centre of the first chaotic fit window, t_end 10^(-decades/2):
    the departure from the t^-1 law lies inside that window."""
    t, _ = _positive_times(ds, "mlce")
    ends = t[t >= t_min * 10.0 ** decades]
    if ends.size == 0:
        return None
    chaotic = np.array([mlce_slope(ds, decades, end) > slope_threshold for end in ends])
    if not chaotic[-1]:
        return None
    regular = np.flatnonzero(~chaotic)
    first = 0 if regular.size == 0 else regular[-1] + 1
    return float(ends[first] * 10.0 ** (-decades / 2))


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
    from chainchaos.observables import equipartition_eta as value

    return float(value(float(ds["spectral_entropy"].values[0]), ds.sizes["mode"]))


# --------------------------------------------------------------------------------------------
# Measurements on the chain and the ensemble
# --------------------------------------------------------------------------------------------


def mode_energy_profile(chain: xr.Dataset, mode: int) -> np.ndarray:
    """Normalised energy density of linear mode ``mode`` (u = mode shape, p = 0, bond energies
    split half-half, DESIGN section 3), from the chain file's K2 and mode_shape."""
    U = np.asarray(chain["mode_shape"].values)[:, mode - 1]
    y = np.diff(np.concatenate([[0.0], U, [0.0]]))
    bond = 0.5 * np.asarray(chain["K2"].values) * y**2
    h = 0.5 * (bond[:-1] + bond[1:])
    return h / h.sum()


def mode_peak_site(chain: xr.Dataset, mode: int) -> int:
    """Bead of the energy maximum of linear mode ``mode``."""
    return int(np.asarray(chain["site"].values)[np.argmax(mode_energy_profile(chain, mode))])


def chain_from_dataset(chain: xr.Dataset, k4_sign: float = 1.0):
    """The :class:`chainchaos.chain.Chain` of a chain file's Dataset."""
    from chainchaos.chain import Chain

    seed = int(chain.attrs.get("seed", -1))
    return Chain(np.asarray(chain["radius"].values), float(chain.attrs["alpha"]), None if seed < 0 else seed,
                 float(chain.attrs.get("wall_radius", 1.0)), float(k4_sign))


def taylor_sign_barrier(chain: xr.Dataset, site: int = 21) -> float:
    """Largest energy a single-bead displacement of bead ``site`` reaches in the FPUT chain with the
    Taylor sign of K4 (K4 < 0): the maximum over u0 > 0 of the potential energy along that
    excitation. Above it no single-bead initial state of the paper's kind exists."""
    from scipy.optimize import minimize_scalar

    from chainchaos.initial import excitation_energy
    from chainchaos.models import model_id

    fput = model_id("fput")
    c = chain_from_dataset(chain, -1.0)
    upper = 1.0
    while excitation_energy(fput, c, site, 2 * upper) > excitation_energy(fput, c, site, upper):
        upper *= 2
        if upper > 1e6:
            return float("inf")
    best = minimize_scalar(lambda u: -excitation_energy(fput, c, site, u), bounds=(0.0, 2 * upper),
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


# --------------------------------------------------------------------------------------------
# The table of claims
# --------------------------------------------------------------------------------------------


@dataclass
class Claim:
    """One statement of the paper and what the pipeline measured for it."""

    id: str
    where: str                      # place in the paper, e.g. "Fig. 4(c), Sec. III B"
    statement: str                  # the paper's statement in this project's words (LaTeX)
    paper: str                      # the paper's value (LaTeX)
    measured: float | None          # the headline measured number (None: nothing measurable)
    measured_text: str              # everything measured for the claim (LaTeX)
    unit: str                       # unit of `measured` ("1": dimensionless; time: 1/omega_max)
    criterion: str                  # how the verdict follows from the measurement (LaTeX)
    verdict: str
    reason: str = ""                # why it differs or cannot be tested
    scenes: tuple = ()
    max_energy_error: float | None = None
    t_final: float | None = None
    t_required: float | None = None

    def row(self) -> dict:
        d = asdict(self)
        d["scenes"] = " ".join(self.scenes)
        return d


def decide(passed: bool | None, t_final: float | None = None, t_required: float | None = None,
           refutable_early: bool = False) -> str:
    """Verdict: ``reproduced`` when passed; ``differs`` when not; ``not testable at this scale``
    when the run ends before ``t_required`` (unless the claim holds for the whole run and a
    shorter run already violates it: then ``differs``), or when nothing could be measured."""
    short = t_final is not None and t_required is not None and t_final < t_required * (1 - 1e-9)
    if passed is None:
        return UNTESTABLE
    if short:
        return DIFFERS if (refutable_early and not passed) else UNTESTABLE
    return REPRODUCED if passed else DIFFERS


def fmt(x, digits: int = 3) -> str:
    """A number for LaTeX (math mode content): 3 significant digits, powers of ten as 10^{k}."""
    if x is None:
        return "--"
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    x = float(x)
    if not math.isfinite(x):
        return "--"
    if x == 0:
        return "0"
    exponent = int(math.floor(math.log10(abs(x))))
    if -2 <= exponent <= 3:
        text = f"{x:.{max(digits - 1 - exponent, 0)}f}"
        return text
    mantissa = x / 10**exponent
    m = f"{mantissa:.{digits - 1}f}"
    if float(m) == 10.0:
        m, exponent = f"{1:.{digits - 1}f}", exponent + 1
    if float(m) == 1.0:
        return f"10^{{{exponent}}}"
    return f"{m}\\times 10^{{{exponent}}}"


def g(x) -> str:
    """A parameter (threshold, energy, tolerance) as one would type it: 3, 0.25, 8.7381, 10^{5}."""
    x = float(x)
    if x != 0 and (abs(x) >= 1e5 or abs(x) < 1e-3):
        exponent = int(math.floor(math.log10(abs(x))))
        mantissa = f"{x / 10**exponent:.4g}"
        return f"10^{{{exponent}}}" if mantissa == "1" else f"{mantissa}\\times 10^{{{exponent}}}"
    return f"{x:.6g}"


def m(x, digits: int = 3) -> str:
    """``fmt`` wrapped in $...$."""
    return f"${fmt(x, digits)}$"


def _within_factor(measured: float | None, paper: float, factor: float) -> bool:
    return measured is not None and measured > 0 and 1 / factor <= measured / paper <= factor


@dataclass
class _Context:
    scenes: dict
    chain: xr.Dataset
    ensemble: xr.Dataset
    c: Criteria
    site: int
    claims: list = field(default_factory=list)

    def scene(self, name):
        return self.scenes.get(name)

    def err(self, names) -> float | None:
        errs = [_max_energy_error(self.scenes[n]) for n in names if n in self.scenes]
        errs = [e for e in errs if e is not None]
        return max(errs) if errs else None

    def t_final(self, names) -> float | None:
        ts = [float(self.scenes[n]["time"].values[-1]) for n in names if n in self.scenes]
        return min(ts) if ts else None

    def has(self, names, *variables) -> bool:
        return all(n in self.scenes and all(v in self.scenes[n] for v in variables) for n in names)

    def add(self, id, where, statement, paper, measured, measured_text, unit, criterion, passed,
            scenes=(), t_required=None, refutable_early=False, reason_differs="", variables=()):
        scenes = tuple(scenes)
        if scenes and not self.has(scenes, *variables):
            missing = [n for n in scenes if n not in self.scenes]
            what = (f"scene(s) {', '.join(missing)} missing" if missing
                    else f"the scenes lack {', '.join(variables)}")
            self.claims.append(Claim(id, where, statement, paper, None, "--", unit, criterion, UNTESTABLE,
                                     what, scenes, self.err(scenes), self.t_final(scenes), t_required))
            return
        t_final = self.t_final(scenes) if scenes else None
        verdict = decide(passed() if callable(passed) else passed, t_final, t_required, refutable_early)
        reason = ""
        if verdict == UNTESTABLE:
            reason = (f"needs the run to reach $t = {g(t_required)}$; it ends at $t = {fmt(t_final)}$"
                      if t_final is not None and t_required is not None and t_final < t_required
                      else "nothing to measure")
        elif verdict == DIFFERS:
            reason = reason_differs or "the measured value lies outside the tolerance"
        self.claims.append(Claim(id, where, statement, paper, measured, measured_text, unit, criterion,
                                 verdict, reason, scenes, self.err(scenes), t_final, t_required))


def _max_energy_error(ds: xr.Dataset) -> float | None:
    """A scene's largest relative energy error (attribute), or the largest over the valid runs of
    an energy scan (variable ``energy_error_max``)."""
    if "energy_error_max" in ds:
        err = np.where(ds["valid"].values == 1, ds["energy_error_max"].values, np.nan)
        return float(np.nanmax(err)) if np.isfinite(err).any() else None
    return float(ds.attrs["max_energy_error"]) if "max_energy_error" in ds.attrs else None


def _lazy(fn):
    """Call fn() only when the claim's scenes and variables are there."""
    class Lazy:
        def __init__(self):
            self._value, self._done = None, False

        def __call__(self):
            if not self._done:
                self._value, self._done = fn(), True
            return self._value
    return Lazy()


#: The name under which the energy scan (results/scan/energy_scan.nc) joins the scenes of a claim.
ENERGY_SCAN = "energy_scan"


def evaluate_claims(scenes: dict, chain: xr.Dataset, ensemble: xr.Dataset,
                    criteria: Criteria | None = None, excited_site: int = 21,
                    energy_scan: xr.Dataset | None = None) -> list[Claim]:
    """Every claim of the paper, measured on ``scenes`` (scene name -> Dataset), the chain file,
    the ensemble file and the energy scan (the threshold statements; without it they are not
    testable); see the module docstring for the verdicts."""
    c = criteria or Criteria()
    tol = c.tolerance
    if energy_scan is not None:
        scenes = {**scenes, ENERGY_SCAN: energy_scan}
    ctx = _Context(scenes, chain, ensemble, c, excited_site)
    s = excited_site
    add = ctx.add
    fw = c.final_window_decades

    # ---------------- Fig. 1 and the chosen realization ----------------
    alphas_hi = [float(a) for a in ensemble["alpha"].values if a >= 4.0 - 1e-9]
    counts = [localized_mode_count(ensemble, a, c.localized_mode_p_max) for a in alphas_hi]
    add("fig1-count", "Fig. 1(a), Sec. II A",
        r"For $\alpha \ge 4$ about 10 modes are strongly localized",
        "about 10",
        min(counts) if counts else None,
        (f"{min(counts)}--{max(counts)} modes with $\\langle P\\rangle \\le {g(c.localized_mode_p_max)}$ "
         f"($\\alpha = {g(min(alphas_hi))}$--${g(max(alphas_hi))}$)") if counts else "--",
        "modes",
        f"every $\\alpha \\ge 4$ has $10 \\pm {tol.count}$ ranks with "
        f"$\\langle P\\rangle \\le {g(c.localized_mode_p_max)}$",
        all(abs(n - 10) <= tol.count for n in counts) if counts else None)

    levels = [localized_level(ensemble, a, c.n_localized_modes) for a in alphas_hi]
    chain_pa = np.sort(np.asarray(chain["mode_participation_period_averaged"].values))[:c.n_localized_modes] \
        if "mode_participation_period_averaged" in chain else None
    add("fig1-level", "Fig. 1(a), Sec. II A",
        r"Those modes have $\langle P\rangle \approx 2$",
        "$2$",
        min(levels) if levels else None,
        (f"${fmt(min(levels))}$--${fmt(max(levels))}$ (mean of the {c.n_localized_modes} most localized "
         f"ranks); chosen chain, period-averaged: {m(np.mean(chain_pa)) if chain_pa is not None else '--'}")
        if levels else "--",
        "1",
        f"$|\\langle P\\rangle - 2| \\le {g(tol.mode_participation)}$ for every $\\alpha \\ge 4$",
        all(abs(v - 2.0) <= tol.mode_participation for v in levels) if levels else None,
        reason_differs=("convention: with the potential energy density of DESIGN section 3 no bead holds "
                        "more than half of an interior mode's energy, so $P \\ge 2$ and a mode on one bead "
                        "has $2 \\le P \\le 8/3$; a mean of exactly 2 is out of reach. The paper does not "
                        "define its energy density of a mode."))

    dev = limiting_curve_deviation(ensemble, 4.0)
    add("fig1-limit", "Fig. 1(a), Sec. II A",
        r"For $\alpha \ge 4$ the curve $\langle P\rangle(k)$ reaches a limiting curve",
        "limiting curve",
        dev, f"largest rank-wise spread of the $\\alpha \\ge 4$ curves: {m(100 * dev, 2)}\\,\\%", "1",
        f"spread $\\le {g(100 * tol.limiting_curve_relative)}\\,\\%$",
        bool(dev <= tol.limiting_curve_relative) if np.isfinite(dev) else None)

    alpha_dyn = float(chain.attrs.get("alpha", 5.0))
    ext = most_extended(ensemble, alpha_dyn)
    add("fig1-extended", "Sec. III B, Fig. 1(a)",
        r"The most extended mode of a disordered chain has $P \approx 26$",
        "$26$", ext,
        (f"rank-1 $\\langle P\\rangle = {fmt(ext)}$ ($\\alpha = {g(alpha_dyn)}$); chosen chain's most "
         f"extended mode {m(float(np.max(chain['mode_participation'].values)))}"),
        "1", f"within ${g(100 * tol.participation_relative)}\\,\\%$ of 26",
        abs(ext / 26.0 - 1) <= tol.participation_relative)

    mode = 34
    P34 = float(chain["mode_participation"].values[mode - 1])
    P34pa = (float(chain["mode_participation_period_averaged"].values[mode - 1])
             if "mode_participation_period_averaged" in chain else float("nan"))
    add("mode34-P", "Fig. 1(b), Sec. II A",
        r"Mode 34 of the chosen chain is strongly localized, $P \approx 2.5$",
        "$2.5$", P34, f"{m(P34)} (potential); {m(P34pa)} (period-averaged)", "1",
        f"$|P - 2.5| \\le {g(tol.mode_participation)}$ (potential convention)",
        abs(P34 - 2.5) <= tol.mode_participation,
        reason_differs=("convention: the paper's realization and its energy density of a mode are "
                        "unpublished; under the potential convention of DESIGN section 3 a mode whose "
                        "neighbours move has $P \\gtrsim 8/3$, and the selection window is "
                        "$2.2 \\le P \\le 2.8$; the period-averaged convention gives the other value shown"))

    peak = mode_peak_site(chain, mode)
    add("mode34-site", "Fig. 1(b), Sec. II A", r"Mode 34 is centred on site $n = 21$", "$21$", peak,
        f"energy maximum at site ${peak}$", "site", "the mode's energy maximum is on site 21 "
        "(a selection requirement, DESIGN section 4)", peak == 21)

    d = np.asarray(chain["delta"].values)[s - 1:s + 1]
    add("overlaps", "Sec. III A", r"The static overlaps next to site 21 are $\delta_{21,22} \approx 1.06$",
        "$1.06$", float(np.max(np.abs(d - 1.06))), f"$\\delta_{{21}} = {fmt(d[0])}$, $\\delta_{{22}} = {fmt(d[1])}$",
        "length unit", f"both within ${g(tol.displacement)}$ of 1.06 (the selection prefers them near 1.06)",
        bool(np.all(np.abs(d - 1.06) <= tol.displacement)))

    hz25, fp25 = "hertz_H0.25", "fput_H0.25"
    u0 = float(scenes[hz25].attrs["u0"]) if hz25 in scenes else None
    add("u0", "Sec. III A", r"At $H = 0.25$ the Hertz initial displacement is $u_{21}(0) \approx 1.01$",
        "$1.01$", u0, m(u0, 4) if u0 is not None else "--", "length unit",
        f"$|u_{{21}}(0) - 1.01| \\le {g(tol.displacement)}$",
        (abs(u0 - 1.01) <= tol.displacement) if u0 is not None else None, scenes=(hz25,),
        reason_differs=("units: in these units $u_{21}(0)$ depends only on the two overlaps next to "
                        "bead 21, and overlaps of 1.06 give $u_{21}(0) \\approx 1.04$; 1.01 would need "
                        "overlaps near 1.0 (DESIGN section 1). The units are not tuned to hide this"))

    # ---------------- H = 0.25 ----------------
    for name, label in ((hz25, "Hertz"), (fp25, "FPUT")):
        val = _lazy(lambda name=name: final_mean(scenes[name], "participation", fw))
        add(f"P-H0.25-{label.lower()}", "Fig. 2(c), Sec. III A",
            f"At $H = 0.25$ the {label} packet keeps a constant $P \\approx 1.8$", "$1.8$",
            val() if ctx.has((name,), "participation") else None,
            m(val()) if ctx.has((name,), "participation") else "--", "1",
            f"final $P$ within ${g(100 * tol.participation_relative)}\\,\\%$ of 1.8",
            lambda: abs(val() / 1.8 - 1) <= tol.participation_relative, scenes=(name,), t_required=1e2,
            variables=("participation",),
            reason_differs=("the paper plots a LOWESS-smoothed $P$ under an unstated energy density; the "
                            "mean of the raw $P$, which oscillates with the mode between about 1.2 and "
                            "2.8, is larger"))

    if ctx.has((hz25, fp25), "participation"):
        ph, pf = (final_mean(scenes[n], "participation", fw) for n in (hz25, fp25))
        add("P-H0.25-overlap", "Fig. 2(c), Sec. III A",
            r"At $H = 0.25$ the $P(t)$ curves of the two models almost overlap", "overlap",
            abs(ph - pf) / (0.5 * (ph + pf)), f"final $P$: Hertz {m(ph)}, FPUT {m(pf)}", "1",
            f"relative difference $\\le {g(100 * tol.participation_relative)}\\,\\%$",
            abs(ph - pf) / (0.5 * (ph + pf)) <= tol.participation_relative, scenes=(hz25, fp25),
            t_required=1e2, variables=("participation",))
    else:
        add("P-H0.25-overlap", "Fig. 2(c), Sec. III A",
            r"At $H = 0.25$ the $P(t)$ curves of the two models almost overlap", "overlap", None, "--", "1",
            "relative difference of the final $P$", None, scenes=(hz25, fp25), variables=("participation",))

    def chaos_claim(id, where, name, label, H, chaotic=True, t_required=1e5, extra="", reason=""):
        ok = ctx.has((name,), "mlce")
        growth = _lazy(lambda: excess_growth(scenes[name]))
        relation = ">" if chaotic else r"\le"
        add(id, where, f"At $H = {g(H)}$ the {label} orbit is {'chaotic' if chaotic else 'regular'}{extra}",
            "chaotic" if chaotic else "regular", growth() if ok else None,
            (f"$\\ln|v| - \\ln t = {fmt(growth(), 2)}$, $\\Lambda(t_\\mathrm{{end}}) = {fmt(final_mlce(scenes[name]))}$"
             if ok else "--"),
            "1", f"$\\ln(|v(t)|/|v(0)|) - \\ln(1+t) {relation} {g(c.chaos_margin)}$ at the end",
            (lambda: growth() > c.chaos_margin) if chaotic else (lambda: growth() <= c.chaos_margin),
            scenes=(name,), t_required=t_required, refutable_early=not chaotic, variables=("mlce",),
            reason_differs=reason)

    for name, label in ((hz25, "Hertz"), (fp25, "FPUT")):
        chaos_claim(f"regular-H0.25-{label.lower()}", "Fig. 2(d), Sec. III A", name, label, 0.25, False,
                    extra=", $\\Lambda \\propto t^{-1}$")

    for name, label in ((hz25, "Hertz"), (fp25, "FPUT")):
        pd = _lazy(lambda name=name: window_mean(scenes[name], "dvd_participation", 1e2, 1e3))
        add(f"PD-H0.25-{label.lower()}", "Fig. 3(e,f), Sec. III A",
            f"At $H = 0.25$ the {label} DVD has $P_D \\approx 20$ up to $t \\approx 10^3$", "$20$",
            pd() if ctx.has((name,), "dvd_participation") else None,
            f"mean $P_D$ over $10^2 \\le t \\le 10^3$: {m(pd())}" if ctx.has((name,), "dvd_participation") else "--",
            "1", f"within ${g(100 * tol.participation_relative)}\\,\\%$ of 20",
            lambda: abs(pd() / 20 - 1) <= tol.participation_relative, scenes=(name,), t_required=1e3,
            variables=("dvd_participation",),
            reason_differs="$P_D$ fluctuates strongly from sample to sample; its mean over the decade is lower")

    if ctx.has((hz25, fp25), "dvd_participation"):
        ratios = {n: final_mean(scenes[n], "dvd_participation", fw) / window_mean(scenes[n], "dvd_participation", 1e2, 1e3)
                  for n in (hz25, fp25)}
        add("PD-H0.25-drop", "Fig. 3(e,f), Sec. III A",
            r"After $t \approx 10^3$ the Hertz $P_D$ drops, the FPUT one does not", "drop (Hertz only)",
            ratios[hz25],
            f"final/early $P_D$: Hertz {m(ratios[hz25], 2)}, FPUT {m(ratios[fp25], 2)}", "1",
            f"Hertz ratio $< 1 - {g(tol.participation_relative)}$ and FPUT ratio $\\ge$ that",
            ratios[hz25] < 1 - tol.participation_relative and ratios[fp25] >= 1 - tol.participation_relative,
            scenes=(hz25, fp25), t_required=1e5, variables=("dvd_participation",))

    for name, label in ((hz25, "Hertz"), (fp25, "FPUT")):
        eta = _lazy(lambda name=name: final_mean(scenes[name], "eta", c.eta_final_window_decades))
        add(f"eta-H0.25-{label.lower()}", "Fig. 8(a)/9(a), Sec. III C",
            f"At $H = 0.25$ the {label} $\\eta$ stays close to 1", "close to 1",
            eta() if ctx.has((name,), "eta") else None, m(eta()) if ctx.has((name,), "eta") else "--", "1",
            f"final $\\eta \\ge {g(c.eta_near_one)}$", lambda: eta() >= c.eta_near_one, scenes=(name,),
            t_required=1e5, refutable_early=True, variables=("eta",))

    # ---------------- H = 0.5 ----------------
    hz05, fp05 = "hertz_H0.5", "fput_H0.5"

    def localized_claim(id, where, name, label, H, t_required=1e5, reason=""):
        val = _lazy(lambda: final_mean(scenes[name], "participation", fw))
        add(id, where, f"At $H = {g(H)}$ the {label} packet stays localized", "localized",
            val() if ctx.has((name,), "participation") else None,
            f"final $P = {fmt(val())}$" if ctx.has((name,), "participation") else "--", "1",
            f"final $P \\le {g(c.localized_p_max)}$", lambda: val() <= c.localized_p_max, scenes=(name,),
            t_required=t_required, refutable_early=True, variables=("participation",), reason_differs=reason)

    localized_claim("loc-H0.5-hertz", "Fig. 4(a,c), Sec. III B", hz05, "Hertz", 0.5, reason=REALIZATION)
    chaos_claim("chaos-H0.5-hertz", "Fig. 4(d), Sec. III B", hz05, "Hertz", 0.5, True,
                extra=" (localized chaos, in the last decade)")
    localized_claim("loc-H0.5-fput", "Fig. 4(c), Sec. III B", fp05, "FPUT", 0.5, reason=REALIZATION)
    chaos_claim("regular-H0.5-fput", "Fig. 4(d), Sec. III B", fp05, "FPUT", 0.5, False, reason=REALIZATION)

    frac = _lazy(lambda: dvd_site_fraction(scenes[hz05], s, c.dvd_site_halfwidth, fw))
    add("dvd-H0.5-site21", "Fig. 5(a,b), Sec. III B",
        r"At $H = 0.5$ the Hertz DVD stays attached to site 21 in the last decade", "site 21",
        frac() if ctx.has((hz05,), "dvd") else None,
        f"DVD maximum within {c.dvd_site_halfwidth} site of 21 in {m(100 * frac(), 2)}\\,\\% of the final samples"
        if ctx.has((hz05,), "dvd") else "--", "1",
        f"fraction $\\ge {g(100 * c.dvd_site_fraction)}\\,\\%$", lambda: frac() >= c.dvd_site_fraction,
        scenes=(hz05,), t_required=1e5, variables=("dvd",))

    ng = _lazy(lambda: max_simultaneous_gaps(scenes[hz05]))
    add("gaps-H0.5-one", "Fig. 7(a,c), Sec. III C", r"At $H = 0.5$ at most one gap is open at any instant",
        r"$\le 1$", ng() if ctx.has((hz05,), "n_gaps") else None,
        f"at most {ng()} open at once (checked every step)" if ctx.has((hz05,), "n_gaps") else "--",
        "gaps", "largest number of simultaneously open gaps $\\le 1$", lambda: ng() <= 1, scenes=(hz05,),
        t_required=1e5, refutable_early=True, variables=("n_gaps",), reason_differs=REALIZATION)

    near = _lazy(lambda: bonds_ever_open(scenes[hz05]))
    add("gaps-H0.5-site21", "Fig. 7(a), Sec. III C",
        r"At $H = 0.5$ gaps open only beside site 21", "bonds 21, 22",
        float(np.max(bond_distance(near(), s))) if ctx.has((hz05,), "gap_fraction") and near().size else None,
        ("bonds ever open: " + (", ".join(str(int(b)) for b in near()) or "none"))
        if ctx.has((hz05,), "gap_fraction") else "--", "bonds",
        "every bond that opens is one of the two bonds of bead 21",
        lambda: bool(near().size) and bool(np.all(bond_distance(near(), s) == 0)), scenes=(hz05,),
        t_required=1e5, refutable_early=True, variables=("gap_fraction",), reason_differs=REALIZATION)

    # ---------------- H = 1.8 ----------------
    hz18, fp18 = "hertz_H1.8", "fput_H1.8"
    onset = _lazy(lambda: spreading_onset(scenes[hz18], c.spreading_factor, c.smoothing_decades, c.plateau_start))
    has18 = ctx.has((hz18,), "participation")
    t_loc = float(c.plateau_end.get(hz18, 100.0))
    level = _lazy(lambda: window_mean(scenes[hz18], "participation", c.plateau_start, t_loc))
    add("spread-H1.8-level", "Fig. 4(b,c), Sec. III B",
        r"At $H = 1.8$ the Hertz packet is first localized with $P < 3$", r"$< 3$", level() if has18 else None,
        f"mean $P$ over ${g(c.plateau_start)} \\le t \\le {g(t_loc)}$: {m(level())}" if has18 else "--", "1",
        f"mean $P < {g(c.spreading_p_threshold)}$ over that window (before the paper's onset)",
        lambda: level() < c.spreading_p_threshold, scenes=(hz18,), t_required=t_loc, variables=("participation",),
        reason_differs=("the packet's early participation number is larger than the paper's; the paper's "
                        "energy density and smoothing are not stated (see the $H = 0.25$ claims)"))
    add("spread-H1.8-onset", "Fig. 4(b,c), Sec. III B",
        r"At $H = 1.8$ the Hertz packet starts to spread at $t \approx 2\times 10^2$",
        r"$2\times 10^{2}$", onset() if has18 else None,
        (f"smoothed $P$ first exceeds {g(c.spreading_factor)} times its value at $t = {g(c.plateau_start)}$ "
         f"at $t = {fmt(onset())}$" if onset() is not None else "the smoothed $P$ never doubles") if has18 else "--",
        "time", f"onset within a factor {g(tol.time_factor)} of $2\\times 10^2$",
        lambda: _within_factor(onset(), 2e2, tol.time_factor), scenes=(hz18,), t_required=2e2 * tol.time_factor,
        refutable_early=True, variables=("participation",))

    Psat = _lazy(lambda: final_mean(scenes[hz18], "participation", fw))
    add("spread-H1.8-saturation", "Fig. 4(c), Sec. III B",
        r"At $H = 1.8$ the Hertz $P$ saturates near 26", "$26$", Psat() if has18 else None,
        f"final $P = {fmt(Psat())}$" if has18 else "--", "1",
        f"within ${g(100 * tol.participation_relative)}\\,\\%$ of 26",
        lambda: abs(Psat() / 26 - 1) <= tol.participation_relative, scenes=(hz18,), t_required=4e4,
        variables=("participation",))

    tsat = _lazy(lambda: saturation_time(scenes[hz18], c.saturation_fraction, c.smoothing_decades, fw))
    add("spread-H1.8-until", "Fig. 4(c), Sec. III B",
        r"At $H = 1.8$ the spreading goes on until $t \approx 4\times 10^3$", r"$4\times 10^{3}$",
        tsat() if has18 else None,
        (f"smoothed $P$ reaches {g(100 * c.saturation_fraction)}\\,\\% of its final value at "
         f"$t = {fmt(tsat())}$") if has18 else "--", "time",
        f"within a factor {g(tol.time_factor)} of $4\\times 10^3$",
        lambda: _within_factor(tsat(), 4e3, tol.time_factor), scenes=(hz18,), t_required=4e4,
        variables=("participation",))

    lam = _lazy(lambda: final_mlce(scenes[hz18]))
    add("mlce-H1.8", "Fig. 4(d), Sec. III B",
        r"At $H = 1.8$ the Hertz $\Lambda$ levels off at $\Lambda \approx 10^{-3}$", r"$10^{-3}$",
        lam() if ctx.has((hz18,), "mlce") else None,
        f"$\\Lambda(t_\\mathrm{{end}}) = {fmt(lam())}$" if ctx.has((hz18,), "mlce") else "--", "1/time",
        f"within a factor {g(tol.mlce_factor)} of $10^{{-3}}$",
        lambda: _within_factor(lam(), 1e-3, tol.mlce_factor), scenes=(hz18,), t_required=1e4,
        variables=("mlce",))

    def chaos_onset_claim(id, where, name, statement, paper_t, paper_tex, t_required):
        ok = ctx.has((name,), "mlce")
        con = _lazy(lambda: chaos_onset(scenes[name], c.chaos_slope, c.chaos_window_decades))
        add(id, where, statement, f"${paper_tex}$", con() if ok else None,
            (f"chaotic from $t = {fmt(con())}$ on" if con() is not None else "not chaotic at the end")
            if ok else "--", "time", f"onset of chaos within a factor {g(tol.time_factor)} of ${paper_tex}$",
            lambda: _within_factor(con(), paper_t, tol.time_factor), scenes=(name,), t_required=t_required,
            variables=("mlce",))

    chaos_onset_claim("chaos-H1.8-onset", "Fig. 4(d), Sec. III B", hz18,
                      r"At $H = 1.8$ the Hertz orbit is chaotic from $t \approx 2\times 10^2$ on",
                      2e2, r"2\times 10^{2}", 2e3)

    tg = _lazy(lambda: gap_spread_time(scenes[hz18], s, c.gap_spread_distance))
    add("gaps-H1.8-spread", "Fig. 7(b), Sec. III C",
        r"At $H = 1.8$ gaps leave site 21 at $t \approx 3\times 10^2$, when $P$ starts to grow",
        r"$3\times 10^{2}$", tg() if ctx.has((hz18,), "gap_fraction") else None,
        (f"first gap {c.gap_spread_distance} or more bonds from bead 21 by $t = {fmt(tg())}$"
         + (f"; spreading onset $t = {fmt(onset())}$" if has18 and onset() is not None else "")
         if tg() is not None else "no gap leaves bead 21") if ctx.has((hz18,), "gap_fraction") else "--",
        "time", f"within a factor {g(tol.time_factor)} of $3\\times 10^2$",
        lambda: _within_factor(tg(), 3e2, tol.time_factor), scenes=(hz18,), t_required=3e2 * tol.time_factor,
        refutable_early=True, variables=("gap_fraction",))

    cover = _lazy(lambda: bonds_ever_open(scenes[hz18]).size / scenes[hz18].sizes["bond"])
    add("gaps-H1.8-cover", "Fig. 7(b), Sec. III C",
        r"At $H = 1.8$ gaps eventually cover the whole lattice", "whole lattice",
        cover() if ctx.has((hz18,), "gap_fraction") else None,
        f"{m(100 * cover(), 2)}\\,\\% of the bonds have opened" if ctx.has((hz18,), "gap_fraction") else "--",
        "1", f"at least ${g(100 * c.gap_coverage)}\\,\\%$ of the bonds open at some time",
        lambda: cover() >= c.gap_coverage, scenes=(hz18,), t_required=1e5, variables=("gap_fraction",))

    # ---------------- FPUT: regular up to 1.8, then alternation ----------------
    low = (fp25, fp05, fp18)
    if ctx.has(low, "participation", "mlce"):
        Ps = [final_mean(scenes[n], "participation", fw) for n in low]
        sl = [excess_growth(scenes[n]) for n in low]
        passed = all(p <= c.localized_p_max for p in Ps) and all(x <= c.chaos_margin for x in sl)
        text = "; ".join(f"$H = {g(scenes[n].attrs['energy'])}$: $P = {fmt(p)}$, $\\ln|v| - \\ln t = {fmt(x, 2)}$"
                         for n, p, x in zip(low, Ps, sl))
        measured = max(Ps)
    else:
        passed, text, measured = None, "--", None
    add("fput-regular-to-1.8", "Fig. 4(c,d), Sec. III B",
        r"The FPUT packet stays localized and regular up to $H = 1.8$", "localized, regular", measured, text, "1",
        f"final $P \\le {g(c.localized_p_max)}$ and $\\ln|v| - \\ln(1+t) \\le {g(c.chaos_margin)}$ at $H = 0.25, 0.5, 1.8$",
        passed, scenes=low, t_required=1e5, refutable_early=True, variables=("participation", "mlce"),
        reason_differs=REALIZATION)

    def deloc_chaos(id, where, name, H, extra=""):
        ok = ctx.has((name,), "participation", "mlce")
        P = final_mean(scenes[name], "participation", fw) if ok else None
        sl = excess_growth(scenes[name]) if ok else None
        add(id, where, f"At $H = {g(H)}$ the FPUT packet is delocalized and chaotic{extra}",
            "delocalized, chaotic", P,
            f"final $P = {fmt(P)}$, $\\ln|v| - \\ln t = {fmt(sl, 2)}$" if ok else "--", "1",
            f"final $P \\ge {g(c.delocalized_p_min)}$ and $\\ln|v| - \\ln(1+t) > {g(c.chaos_margin)}$",
            (P >= c.delocalized_p_min and sl > c.chaos_margin) if ok else None, scenes=(name,),
            t_required=1e5, variables=("participation", "mlce"), reason_differs=REALIZATION)

    fp29, fp4, fp87 = "fput_H2.9", "fput_H4", "fput_H8.7381"
    deloc_chaos("fput-H2.9", "Fig. 6(a--d), Sec. III B", fp29, 2.9, " (the first such energy)")
    chaos_onset_claim("chaos-H2.9-onset", "Fig. 6(d), Sec. III B", fp29,
                      r"At $H = 2.9$ the FPUT orbit is chaotic for $t \gtrsim 4\times 10^3$",
                      4e3, r"4\times 10^{3}", 4e4)
    localized_claim("loc-H4-fput", "Fig. 6(e,f), Sec. III B", fp4, "FPUT", 4.0, reason=REALIZATION)
    chaos_claim("chaos-H4-fput", "Sec. III B", fp4, "FPUT", 4.0, True, extra=" (FPUT is chaotic for all $H > 2.8$)")
    deloc_chaos("fput-H8.7381", "Fig. 6(i--l), Sec. III B", fp87, 8.7381)

    # ---------------- entropy ----------------
    for name, H, value, where in (("hertz_H1.8", 1.8, 0.5, "Fig. 8(c)"), ("hertz_H3", 3.0, 0.5, "Fig. 8(d)"),
                                  (fp29, 2.9, 0.7, "Fig. 9(b)"), (fp4, 4.0, 0.82, "Fig. 9(c)"),
                                  (fp87, 8.7381, 0.8, "Fig. 9(d)")):
        label = "Hertz" if name.startswith("hertz") else "FPUT"
        t1 = float(c.plateau_end.get(name, float("nan")))
        pl = _lazy(lambda name=name, t1=t1: window_median(scenes[name], "eta", c.plateau_start, t1))
        ok = ctx.has((name,), "eta")
        add(f"eta-plateau-{name}", f"{where}, Sec. III C",
            f"At $H = {g(H)}$ the {label} $\\eta$ has a plateau near {g(value)}", f"${g(value)}$",
            pl() if ok else None,
            f"median $\\eta$ over ${g(c.plateau_start)} \\le t \\le {g(t1)}$: {m(pl())}" if ok else "--", "1",
            f"$|\\eta_\\mathrm{{plateau}} - {g(value)}| \\le {g(tol.eta_plateau)}$",
            lambda pl=pl, value=value: abs(pl() - value) <= tol.eta_plateau, scenes=(name,), t_required=t1,
            variables=("eta",))

    for name, H, where in (("hertz_H1.8", 1.8, "Fig. 8(c)"), ("hertz_H3", 3.0, "Fig. 8(d)"),
                           (fp29, 2.9, "Fig. 9(b)"), (fp87, 8.7381, "Fig. 9(d)")):
        label = "Hertz" if name.startswith("hertz") else "FPUT"
        ok = ctx.has((name,), "eta")
        ef = final_mean(scenes[name], "eta", c.eta_final_window_decades) if ok else None
        eq = equipartition_eta(scenes[name]) if ok else None
        add(f"eta-final-{name}", f"{where}, Sec. III C",
            f"At $H = {g(H)}$ the {label} $\\eta$ ends close to the equipartition value $\\langle\\eta\\rangle$",
            r"$\approx\langle\eta\rangle$", ef, f"final $\\eta = {fmt(ef)}$, $\\langle\\eta\\rangle = {fmt(eq)}$" if ok else "--",
            "1", f"$|\\eta_\\mathrm{{final}} - \\langle\\eta\\rangle| \\le {g(tol.eta_equipartition)}$",
            (abs(ef - eq) <= tol.eta_equipartition) if ok else None, scenes=(name,), t_required=1e5,
            variables=("eta",))

    ok = ctx.has((fp4,), "eta")
    ef = final_mean(scenes[fp4], "eta", c.eta_final_window_decades) if ok else None
    eq = equipartition_eta(scenes[fp4]) if ok else None
    add("eta-final-fput_H4", "Fig. 9(c,g), Sec. III C",
        r"At $H = 4$ the FPUT $\eta$ is still far from equipartition at the end", r"$\gg\langle\eta\rangle$",
        ef, f"final $\\eta = {fmt(ef)}$, $\\langle\\eta\\rangle = {fmt(eq)}$" if ok else "--", "1",
        f"$\\eta_\\mathrm{{final}} - \\langle\\eta\\rangle > {g(tol.eta_plateau)}$",
        (ef - eq > tol.eta_plateau) if ok else None, scenes=(fp4,), t_required=1e5, refutable_early=True,
        variables=("eta",), reason_differs=REALIZATION)

    _threshold_claims(ctx)
    return ctx.claims


def _threshold_claims(ctx: _Context) -> None:
    """The threshold statements of Sec. III and IV, judged on the energy scan: a grid of energies
    on the chosen chain, each run classified delocalized / chaotic by the scan's own criteria
    (written in the scan file), invalid runs (energy error above the scan's bound) counting as
    neither."""
    tol = ctx.c.tolerance
    f = tol.threshold_factor
    ds = ctx.scene(ENERGY_SCAN)
    ok = ds is not None and all(v in ds for v in ("delocalized", "chaotic", "valid"))
    E = ds.energy.values if ok else np.array([])

    def criterion_text(key):
        if not ok:
            return key
        if key == "delocalized":
            return f"final $P > {g(ds.attrs['p_delocalized'])}$"
        return f"$\\ln(|v(t)|/|v(0)|) - \\ln(1+t) > {g(ds.attrs['chaos_margin'])}$ at the end"

    def energies_text(values):
        return ", ".join(f"${g(float(f'{x:.3g}'))}$" for x in values) or "none"

    def always_claim(id, where, model, label, key, H):
        flag = _scan.criterion_holds(ds, model, key) if ok else None
        above = E >= H * (1 - 1e-9)
        star = _scan.always_above(E, flag) if ok else None
        holds_above = bool(flag[above].all()) if ok and above.any() else None
        failing = E[above & ~flag] if ok else []
        measured_text = "--"
        if ok:
            tail = f"at every scanned $H \\ge H^* = {fmt(star)}$" if np.isfinite(star) else "not at the highest"
            measured_text = (f"{key} at {int(flag[above].sum())} of the {int(above.sum())} scanned "
                             f"$H \\ge {g(H)}$; {tail}")
        reason = REALIZATION if holds_above else f"not {key} at the scanned $H = $ {energies_text(failing)}"
        ctx.add(id, where, f"Above $H \\approx {g(H)}$ the {label} packet is always {key}",
                f"$H^* \\approx {g(H)}$", star if ok and np.isfinite(star) else None, measured_text, "energy",
                (f"{criterion_text(key)} at every scanned $H \\ge {g(H)}$, and the lowest $H^*$ above which "
                 f"this holds at every scanned energy within a factor {g(f)} of {g(H)}"),
                (lambda: holds_above and _within_factor(star, H, f)) if holds_above is not None else None,
                scenes=(ENERGY_SCAN,), t_required=1e5, variables=("delocalized", "chaotic", "valid"),
                reason_differs=reason)

    always_claim("scan-hertz-deloc", "Sec. III B, IV", "hertz", "Hertz", "delocalized", 1.8)
    always_claim("scan-hertz-chaos", "Sec. III B, IV", "hertz", "Hertz", "chaotic", 1.8)
    always_claim("scan-fput-chaos", "Sec. III B, IV", "fput", "FPUT", "chaotic", 2.8)

    H = 2.9
    flag = _scan.criterion_holds(ds, "fput", "delocalized") if ok else None
    first = _scan.first_energy(E, flag) if ok else None
    beyond = (E >= first) if ok and np.isfinite(first) else None
    n_switch = _scan.switches(flag[beyond]) if beyond is not None else 0
    localized_above = E[beyond & ~flag] if beyond is not None else []
    if not ok:
        measured_text = "--"
    elif beyond is None:
        measured_text = "never delocalized"
    else:
        measured_text = (f"first delocalized at $H = {fmt(first)}$; above it localized at $H = $ "
                         f"{energies_text(localized_above)} ({n_switch} changes)")
    ctx.add("scan-fput-alternation", "Sec. III B, IV",
            f"Above $H \\approx {g(H)}$ the FPUT packet alternates between localized and delocalized states",
            f"from $H \\approx {g(H)}$", first if beyond is not None else None, measured_text, "energy",
            (f"the lowest scanned $H$ with {criterion_text('delocalized')} lies within a factor {g(f)} of {g(H)}, "
             f"and above it the state changes at least twice (delocalized, localized, delocalized)"),
            (lambda: _within_factor(first, H, f) and n_switch >= 2) if ok else None,
            scenes=(ENERGY_SCAN,), t_required=1e5, variables=("delocalized", "chaotic", "valid"),
            reason_differs=REALIZATION)


# --------------------------------------------------------------------------------------------
# Output: CSV, LaTeX table, macros
# --------------------------------------------------------------------------------------------

CSV_FIELDS = [f.name for f in fields(Claim)]


def write_csv(claims: list[Claim], path) -> None:
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=CSV_FIELDS)
        writer.writeheader()
        for claim in claims:
            row = claim.row()
            writer.writerow({k: ("" if v is None else v) for k, v in row.items()})


def read_csv(path) -> list[dict]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


VERDICT_TEX = {REPRODUCED: r"\verdictok", DIFFERS: r"\verdictdiffers", UNTESTABLE: r"\verdictuntestable"}


def claims_table_tex(claims: list[Claim]) -> str:
    """A longtable of the claims (needs the array and longtable packages; \\verdictok etc. are
    defined in macros.tex)."""
    col = r">{\raggedright\arraybackslash}p"
    head = r"\# & Statement of the paper & Paper & Measured here & Error & Verdict\\ \hline"
    lines = [
        r"\begingroup\footnotesize\setlength{\LTcapwidth}{\linewidth}\setlength{\tabcolsep}{3pt}",
        rf"\begin{{longtable}}{{@{{}}r {col}{{0.32\linewidth}} {col}{{0.085\linewidth}} {col}{{0.30\linewidth}} "
        rf"{col}{{0.085\linewidth}} {col}{{0.095\linewidth}}@{{}}}}",
        r"\caption{\label{tab:claims}The paper's quantitative statements beside the values this build "
        r"measured. ``Error'' is the largest relative energy error $|H(t)-H(0)|/H(0)$ of the scenes "
        r"the claim rests on. Criteria and reasons follow the table.}\\",
        r"\hline\hline",
        head,
        r"\endfirsthead",
        r"\hline " + head,
        r"\endhead",
        r"\hline\hline",
        r"\endlastfoot",
    ]
    for i, claim in enumerate(claims, 1):
        err = m(claim.max_energy_error, 2) if claim.max_energy_error is not None else "--"
        lines.append(f"{i} & {claim.statement}\\newline{{\\scriptsize [{claim.where}]}} & {claim.paper} & "
                     f"{claim.measured_text} & {err} & {VERDICT_TEX[claim.verdict]}\\\\[2pt]")
    lines += [r"\end{longtable}", r"\endgroup", ""]
    return "\n".join(lines)


def scenes_table_tex(scenes: dict) -> str:
    """One row per scene: model, H, u_21(0), scheme, dt, t_final, largest relative energy error."""
    lines = [
        r"\begin{table}[htbp]",
        r"\caption{\label{tab:scenes}The simulated scenes as run: initial displacement of bead 21 solved "
        r"from each model's exact potential, scheme, step, final time, and the largest relative energy "
        r"error $\max_t |H(t)-H(0)|/H(0)$ over the samples.}",
        r"\begin{ruledtabular}",
        r"\begin{tabular}{llllllll}",
        r"Scene & Model & $H$ & $u_{21}(0)$ & Scheme & $\Delta t$ & $t_\mathrm{end}$ & max.\ energy error\\ \hline",
    ]
    order = sorted(scenes, key=lambda n: (scenes[n].attrs["model"] != "hertz", float(scenes[n].attrs["energy"])))
    for name in order:
        a = scenes[name].attrs
        model = "Hertz" if a["model"] == "hertz" else "FPUT"
        tex_name = name.replace("_", r"\_")
        scheme = str(a["integrator"]).replace("_", r"\_")
        cells = [rf"\texttt{{{tex_name}}}", model, f"${g(a['energy'])}$",
                 m(float(a["u0"]), 4), scheme, f"${g(a['dt'])}$", f"${g(a['t_final'])}$",
                 m(float(a["max_energy_error"]), 2)]
        lines.append(" & ".join(cells) + r"\\")
    lines += [r"\end{tabular}", r"\end{ruledtabular}", r"\end{table}", ""]
    return "\n".join(lines)


def claims_notes_tex(claims: list[Claim]) -> str:
    """Criterion of every claim, and the reason of every verdict other than reproduced."""
    lines = [r"\begin{enumerate}\small"]
    for claim in claims:
        tex_id = claim.id.replace("_", r"\_")
        note = f"\\item \\texttt{{{tex_id}}}: {claim.criterion}."
        if claim.reason:
            note += f" \\emph{{{claim.verdict.capitalize()}}}: {claim.reason.rstrip('.')}."
        lines.append(note)
    lines += [r"\end{enumerate}", ""]
    return "\n".join(lines)


def tex_macro(key: str, value: str) -> str:
    """A \\newcommand for key (any characters but braces and backslashes), read with \\cc{key}."""
    if any(ch in key for ch in "{}\\%#"):
        raise ValueError(f"macro key {key!r} contains a TeX special character")
    return f"\\expandafter\\newcommand\\csname cc@{key}\\endcsname{{{value}}}"


MACRO_PREAMBLE = r"""% Generated by workflow/scripts/evaluate_claims.py: every measured number of the manuscript.
% Use \cc{key}; an unknown key stops the build (no number is typed by hand in ms.tex).
\makeatletter
\providecommand{\cc}[1]{\ifcsname cc@#1\endcsname\csname cc@#1\endcsname\else
  \PackageError{claims}{Unknown measured value '#1'}{macros.tex defines no such key}\fi}
\makeatother
\providecommand{\verdictok}{reproduced}
\providecommand{\verdictdiffers}{\textbf{differs}}
\providecommand{\verdictuntestable}{\emph{not testable}}
"""


def macros_tex(values: dict[str, str]) -> str:
    return MACRO_PREAMBLE + "\n".join(tex_macro(k, v) for k, v in sorted(values.items())) + "\n"


def claim_macros(claims: list[Claim]) -> dict[str, str]:
    """claim.<id>.measured / .paper / .verdict / .error for every claim, and verdict counts."""
    out = {}
    for number, claim in enumerate(claims, 1):
        out[f"claim.{claim.id}.n"] = str(number)
        out[f"claim.{claim.id}.measured"] = claim.measured_text
        out[f"claim.{claim.id}.value"] = m(claim.measured) if claim.measured is not None else "--"
        out[f"claim.{claim.id}.paper"] = claim.paper
        out[f"claim.{claim.id}.verdict"] = claim.verdict
        out[f"claim.{claim.id}.error"] = m(claim.max_energy_error, 2) if claim.max_energy_error is not None else "--"
    for verdict, key in ((REPRODUCED, "reproduced"), (DIFFERS, "differs"), (UNTESTABLE, "untestable")):
        numbers = [str(i) for i, c in enumerate(claims, 1) if c.verdict == verdict]
        out[f"list.{key}"] = ", ".join(numbers) if numbers else "none"
    out["count.total"] = str(len(claims))
    out["count.reproduced"] = str(sum(c.verdict == REPRODUCED for c in claims))
    out["count.differs"] = str(sum(c.verdict == DIFFERS for c in claims))
    out["count.untestable"] = str(sum(c.verdict == UNTESTABLE for c in claims))
    return out


def scene_macros(name: str, ds: xr.Dataset, criteria: Criteria) -> dict[str, str]:
    """Numbers of one scene: u0, run parameters, energy errors, final P, Lambda, eta."""
    a = ds.attrs
    out = {
        f"scene.{name}.u0": fmt(float(a["u0"]), 4),
        f"scene.{name}.dt": g(float(a["dt"])),
        f"scene.{name}.tfinal": g(float(a["t_final"])),
        f"scene.{name}.integrator": str(a["integrator"]),
        f"scene.{name}.maxerr": fmt(float(a["max_energy_error"]), 2),
        f"scene.{name}.finalerr": fmt(float(a["final_energy_error"]), 2),
    }
    if "participation" in ds:
        out[f"scene.{name}.Pfinal"] = fmt(final_mean(ds, "participation", criteria.final_window_decades))
    if "mlce" in ds:
        out[f"scene.{name}.mlce"] = fmt(final_mlce(ds))
        out[f"scene.{name}.slope"] = fmt(mlce_slope(ds, criteria.chaos_window_decades), 2)
        out[f"scene.{name}.growth"] = fmt(excess_growth(ds), 2)
    if "eta" in ds:
        out[f"scene.{name}.etafinal"] = fmt(final_mean(ds, "eta", criteria.eta_final_window_decades))
        out[f"scene.{name}.etaeq"] = fmt(equipartition_eta(ds))
    return out


def _grid_energy(x: float) -> str:
    """An energy of a scan grid for math mode, or a note that the grid has none."""
    return fmt(x) if np.isfinite(x) else r"\text{(none on the grid)}"


def scan_macros(energy_scan: xr.Dataset, disorder: xr.Dataset) -> dict[str, str]:
    """Numbers of the energy scan (grid, run, thresholds per model and criterion) and of the
    disorder statistics (realizations, grid, and per model and criterion: the probability at the
    highest energy with its 95% band, the lowest energy where at least half of the runs qualify)."""
    out = {}
    for prefix, ds in (("scan", energy_scan), ("disorder", disorder)):
        a = ds.attrs
        E = ds.energy.values
        out.update({f"{prefix}.nenergies": str(E.size), f"{prefix}.emin": g(float(f"{E[0]:.3g}")),
                    f"{prefix}.emax": g(float(f"{E[-1]:.3g}")), f"{prefix}.tfinal": g(a["t_final"]),
                    f"{prefix}.dt": g(a["dt"]), f"{prefix}.integrator": str(a["integrator"]).replace("_", r"\_"),
                    f"{prefix}.pdeloc": g(a["p_delocalized"]), f"{prefix}.chaosmargin": g(a["chaos_margin"])})
        out[f"{prefix}.invalid"] = str(int((ds["valid"].values != 1).sum()))
        out[f"{prefix}.maxerr"] = fmt(_max_energy_error(ds), 2)
    flags = {"delocalization": "delocalized", "chaos": "chaotic"}
    for row in _scan.thresholds_table(energy_scan):
        key = f"scan.{row['model']}.{flags[row['criterion']]}"
        out[f"{key}.first"] = _grid_energy(row["first_energy"])
        out[f"{key}.always"] = _grid_energy(row["always_above"])
    out["disorder.realizations"] = str(disorder.sizes["realization"])
    out["disorder.alpha"] = g(disorder.attrs["alpha"])
    E = disorder.energy.values
    for model in disorder.model.values:
        for key in ("delocalized", "chaotic"):
            p = disorder[f"probability_{key}"].sel(model=model).values
            lo = disorder[f"probability_{key}_lower"].sel(model=model).values
            hi = disorder[f"probability_{key}_upper"].sel(model=model).values
            out[f"disorder.{model}.{key}.top"] = (f"{fmt(100 * p[-1], 2)}\\,\\% "
                                                  f"({fmt(100 * lo[-1], 2)}--{fmt(100 * hi[-1], 2)}\\,\\%)")
            half = E[np.nan_to_num(p) >= 0.5]
            out[f"disorder.{model}.{key}.half"] = _grid_energy(float(half[0]) if half.size else np.nan)
    return out
