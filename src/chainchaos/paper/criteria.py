"""Every choice a measurement or a verdict makes, with its default (config block ``claims:``).

:class:`Criteria` holds the windows and thresholds that turn a time series into a number or a
yes/no (``chainchaos.paper.claims``, ``chainchaos.paper.verdicts``); :class:`Tolerances` how far a measured
value may lie from the paper's. Times are in units of 1/omega_max.
"""

from dataclasses import dataclass, field, fields


@dataclass(frozen=True, kw_only=True)
class Tolerances:
    """How far a measured value may lie from the paper's and still count as reproduced.

    Each follows from how the paper gives the number it is applied to; a bound of the paper
    ("for H > 1.8 always", "P < 3") and a range ("0.5 <~ H <~ 1.8") take none: they are checked as
    the bound or range they are (``chainchaos.paper.claims.catalogue``).

    displacement
        absolute, for u_21(0) = 1.01 and delta_{21,22} ~ 1.06: exact properties of the chain and the
        initial state that the paper prints to 0.01; one unit of that digit rather than the half
        unit of rounding, because the paper writes one approximate value for two different
        overlaps, and u_21(0) depends only on them (docs/conventions.md, Units).
    mode_participation
        absolute, for P ~ 2.5 of mode 34: exact linear algebra printed to 0.1, one unit of that digit.
    participation_relative
        relative, for participation numbers read off curves: P ~ 1.8 and P ~ 26 off the (LOWESS-
        smoothed, unstated settings) P(t) of Figs. 2(c), 4(c), <P> ~ 2 and P ~ 26 off Fig. 1(a),
        P_D ~ 20 off Fig. 3(e,f). The paper prints them with one or two significant digits; 10 %
        is about two units of the second digit, the precision of reading a curve. Also what
        "almost overlap" (two P curves) and a "drop" of P_D (beyond it) mean.
    count
        absolute, for "about 10 modes": a round count of the tail of the Fig. 1(a) curves, whose
        edge ("strongly localized") the paper does not define; 7 to 13 is "about 10" and neither
        "about 5" nor "about 15".
    time_factor
        multiplicative, for times the paper reads off logarithmic time axes and prints with one
        significant digit (t ~ 2e2, 3e2, 4e3): reproduced when measured/paper lies in [1/f, f]. A
        time marks where a curve changes behaviour (P starts to increase, Lambda leaves the t^-1
        line), which the eye places on such an axis to a fraction of a decade, not to the printed
        digit; the paper itself gives the Hertz H = 1.8 onset as 2e2 and as 3e2, a factor 1.5 apart.
    mlce_factor
        multiplicative, for "Lambda(t) ~ 10^-3", a bare power of ten read off a logarithmic axis,
        i.e. the nearest decade: 3 is just under half a decade (sqrt(10) ~ 3.16), where a value
        would round to the neighbouring power of ten.
    eta_plateau
        absolute, for the levels of a fluctuating eta(t) (normalised to [0, 1]) read off plots and
        printed with one digit (0.5, 0.7, 0.8) and once with two (0.82): one unit of the one-digit
        values, wider than the rounding of 0.82.
    eta_equipartition
        absolute, for "close to <eta>" (and, beyond it, "not yet at equipartition") at the end of
        a run: the paper gives no number.
    limiting_curve_relative
        relative, for "<P> reaches a limiting curve for alpha >= 4" (no number): largest rank-wise
        relative difference between the alpha >= 4 curves.
    threshold_factor
        multiplicative, for "the first energy at which the FPUT model's wave-packet is
        delocalized [...] is around H = 2.9": a value among the few energies the paper ran, whose
        nearest runs on either side are 1.8 and 4 (factors 1.6 and 1.4 from 2.9); reproduced when
        the scan's first delocalized energy / 2.9 lies in [1/f, f].
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


@dataclass(frozen=True, kw_only=True)
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
    chaos_slope, chaos_growth_margin, chaos_window_decades
        an orbit is chaotic over a window of ``chaos_window_decades`` decades
        (``reductions.is_chaotic``) when the least-squares slope of log10 Lambda against log10 t
        exceeds ``chaos_slope`` (Lambda of a regular orbit falls like ln(t)/t, slope near -1;
        that of a chaotic one levels off, slope near 0) and ln|v| grew by more than
        ln(10^decades) + ``chaos_growth_margin`` (more than the linear growth a regular orbit
        allows). Chaotic at the end: over the last such window; the onset of chaos is where this
        starts to hold for good.
    gali_threshold
        the second chaos indicator of the verdicts: an orbit is chaotic by GALI_k (k the
        ``gali_order`` of the orbits' settings) once GALI_k falls below this before the window's
        end (``reductions.gali_crossing``; 1e-8, the usual threshold of SALI and GALI, far below
        the order-one values of GALI_k, k <= N, on an N-torus).
    localized_mode_p_max
        Fig. 1(a): a mode (rank) counts as strongly localized when its mean P is at most this.
    n_localized_modes
        Fig. 1(a): the level of the localized part of the curve is the mean <P> of this many most
        localized ranks (the paper's "about 10").
    gap_spread_distance
        a gap has left the excited bead when it opens on a bond at least this many bonds away
        from the two bonds of that bead (bonds s and s+1 are at distance 0).
    dvd_site_halfwidth, dvd_site_fraction
        the DVD is localized at the excited site when its maximum lies within this many sites of
        it in at least this fraction of the final-window samples.
    eta_near_one
        eta "stays close to 1" when its final value is at least this.
    onset_hold_decades
        an onset (of spreading, of delocalization) is a sustained crossing: the series must stay
        above its threshold for this many decades of time after it (or to the end of the run).
    agreement
        an ensemble verdict (``chainchaos.paper.verdicts``): a statement holds (fails) for a scene when
        at least this fraction of its perturbed orbits satisfy (violate) it; otherwise undecided.
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
    chaos_growth_margin: float = 2.0
    chaos_window_decades: float = 1.0
    gali_threshold: float = 1e-8
    localized_mode_p_max: float = 3.0
    n_localized_modes: int = 10
    gap_spread_distance: int = 2
    dvd_site_halfwidth: int = 1
    dvd_site_fraction: float = 0.8
    eta_near_one: float = 0.9
    plateau_start: float = 10.0
    onset_hold_decades: float = 0.5
    agreement: float = 0.875
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
