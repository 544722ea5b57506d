"""The measures of the claims: each reads stored results and returns a :class:`Measurement`.

A measure is called as ``MEASURES[row.measure](inputs, *row.scenes, **row.args)``: ``inputs`` holds
the scene files, the chain file, the ensemble of Fig. 1(a), the energy scan (as the scene
``ENERGY_SCAN``), the ensemble verdicts and the criteria; the scene arguments are names. It returns
the headline number and the named numbers the row's checks and texts use, or None when there is
nothing to measure. The arithmetic is in :mod:`chainchaos.paper.claims.quantities`; a measure chooses
what to compute and with which of the criteria.
"""

import numpy as np

from chainchaos.paper.claims import quantities as q
from chainchaos.paper.claims.framework import Inputs, Measurement
from chainchaos.records.formatting import tex_number, tex_parameter
from chainchaos.paper.thresholds import (
    always_above,
    criterion_holds,
    first_energy,
    reads_gali,
    switches,
)


def _alphas_from(inputs: Inputs, alpha_min: float) -> list[float]:
    return [float(a) for a in inputs.ensemble["alpha"].values if a >= alpha_min - 1e-9]


# ---- the ensemble of Fig. 1(a) and the chain file ---------------------------------------------


def localized_mode_counts(inputs: Inputs, alpha_min: float = 4.0) -> Measurement | None:
    """Number of strongly localized ranks (<P> <= localized_mode_p_max) at each alpha >= alpha_min;
    headline: the smallest count."""
    alphas = _alphas_from(inputs, alpha_min)
    counts = [q.localized_mode_count(inputs.ensemble, a, inputs.criteria.localized_mode_p_max) for a in alphas]
    if not counts:
        return None
    return Measurement(min(counts), {"counts": np.array(counts), "lowest": min(counts), "highest": max(counts),
                                     "alpha_low": min(alphas), "alpha_high": max(alphas)})


def localized_levels(inputs: Inputs, alpha_min: float = 4.0) -> Measurement | None:
    """Mean <P> of the n_localized_modes most localized ranks at each alpha >= alpha_min, and the
    chosen chain's period-averaged level (``period_averaged``, None if the chain file lacks it);
    headline: the lowest level."""
    n = inputs.criteria.n_localized_modes
    levels = [q.localized_level(inputs.ensemble, a, n) for a in _alphas_from(inputs, alpha_min)]
    if not levels:
        return None
    chain = inputs.chain
    averaged = None
    if "mode_participation_period_averaged" in chain:
        averaged = np.mean(np.sort(np.asarray(chain["mode_participation_period_averaged"].values))[:n])
    return Measurement(min(levels), {"levels": np.array(levels), "lowest": min(levels), "highest": max(levels),
                                     "period_averaged": averaged})


def limiting_curve(inputs: Inputs, alpha_min: float = 4.0) -> Measurement:
    """Largest rank-wise relative spread of the <P> curves of the alphas >= alpha_min
    (undecided with fewer than two such curves)."""
    spread = q.limiting_curve_deviation(inputs.ensemble, alpha_min)
    return Measurement(spread, decided=bool(np.isfinite(spread)))


def most_extended_mode(inputs: Inputs) -> Measurement:
    """<P> of rank 1 at the chosen chain's alpha, and the chosen chain's largest mode participation."""
    alpha = float(inputs.chain.attrs.get("alpha", 5.0))
    return Measurement(q.most_extended(inputs.ensemble, alpha),
                       {"alpha": alpha, "chain_largest": float(np.max(inputs.chain["mode_participation"].values))})


def mode_participation(inputs: Inputs, mode: int) -> Measurement:
    """Participation number of linear mode ``mode`` of the chosen chain (potential convention), and
    the period-averaged one (NaN if the chain file lacks it)."""
    chain = inputs.chain
    averaged = (float(chain["mode_participation_period_averaged"].values[mode - 1])
                if "mode_participation_period_averaged" in chain else float("nan"))
    return Measurement(float(chain["mode_participation"].values[mode - 1]), {"period_averaged": averaged})


def mode_peak(inputs: Inputs, mode: int) -> Measurement:
    """Bead of the energy maximum of linear mode ``mode``."""
    return Measurement(q.mode_peak_site(inputs.chain, mode))


def excited_overlaps(inputs: Inputs, around: float) -> Measurement:
    """The static overlaps of the two bonds of the excited bead; headline: their largest distance
    from ``around``."""
    s = inputs.site
    overlaps = np.asarray(inputs.chain["delta"].values)[s - 1:s + 1]
    return Measurement(float(np.max(np.abs(overlaps - around))),
                       {"overlaps": overlaps, "left": overlaps[0], "right": overlaps[1]})


# ---- one scene ---------------------------------------------------------------------------------


def initial_displacement(inputs: Inputs, scene: str) -> Measurement:
    """u_site(0) of a scene (its attribute ``u0``)."""
    return Measurement(float(inputs.scenes[scene].attrs["u0"]))


def final_value(inputs: Inputs, scene: str, variable: str) -> Measurement:
    """Time average of ``variable`` over the final window: the last final_window_decades, or
    eta_final_window_decades for eta (whose fall the paper follows to the end)."""
    c = inputs.criteria
    decades = c.eta_final_window_decades if variable == "eta" else c.final_window_decades
    return Measurement(q.final_mean(inputs.scenes[scene], variable, decades))


def window_average(inputs: Inputs, scene: str, variable: str, start: float, end: float) -> Measurement:
    """Time average of ``variable`` over start <= t <= end."""
    return Measurement(q.window_mean(inputs.scenes[scene], variable, start, end))


def _plateau(inputs: Inputs, scene: str) -> tuple[float, float]:
    c = inputs.criteria
    return c.plateau_start, float(c.plateau_end.get(scene, float("nan")))


def plateau_median(inputs: Inputs, scene: str, variable: str) -> Measurement:
    """Median of ``variable`` over the scene's plateau, plateau_start <= t <= plateau_end[scene]."""
    start, end = _plateau(inputs, scene)
    return Measurement(q.window_median(inputs.scenes[scene], variable, start, end), {"start": start, "end": end})


def plateau_largest(inputs: Inputs, scene: str, variable: str) -> Measurement:
    """Largest smoothed ``variable`` over the scene's plateau, plateau_start <= t <= plateau_end[scene]
    ("P < 3 up to t ~ 2e2": below at every sample, as the search's statement judges it)."""
    start, end = _plateau(inputs, scene)
    value = q.window_largest(inputs.scenes[scene], variable, start, end, inputs.criteria.smoothing_decades)
    return Measurement(value, {"start": start, "end": end})


def _spreading_onset(inputs: Inputs, scene: str) -> float | None:
    c = inputs.criteria
    return q.spreading_onset(inputs.scenes[scene], c.spreading_factor, c.smoothing_decades, c.plateau_start,
                             c.onset_hold_decades)


def spreading_onset(inputs: Inputs, scene: str) -> Measurement:
    """When the smoothed P starts to grow for good (case ``never``: it does not)."""
    onset = _spreading_onset(inputs, scene)
    return Measurement(onset, case="never" if onset is None else "")


def saturation_time(inputs: Inputs, scene: str) -> Measurement:
    """When the smoothed P reaches saturation_fraction of its final value for good."""
    c = inputs.criteria
    return Measurement(q.saturation_time(inputs.scenes[scene], c.saturation_fraction, c.smoothing_decades,
                                         c.final_window_decades, c.onset_hold_decades))


def final_mlce(inputs: Inputs, scene: str) -> Measurement:
    """Lambda at the end of the run."""
    return Measurement(q.final_mlce(inputs.scenes[scene]))


def _chaos_details(inputs: Inputs, scene: str) -> dict:
    ds, c = inputs.scenes[scene], inputs.criteria
    return {"slope": q.mlce_slope(ds, c.chaos_window_decades), "growth": q.growth_excess(ds, c.chaos_window_decades),
            "mlce": q.final_mlce(ds), "chaotic": q.scene_chaotic(ds, c)}


def chaos(inputs: Inputs, scene: str) -> Measurement:
    """The chaos criterion at the end of the run; headline: the log-log slope of Lambda."""
    details = _chaos_details(inputs, scene)
    return Measurement(details["slope"], details)


def participation_and_chaos(inputs: Inputs, scene: str) -> Measurement:
    """Final P (headline) and the chaos criterion at the end of the run."""
    return Measurement(final_value(inputs, scene, "participation").value, _chaos_details(inputs, scene))


def localized_and_regular(inputs: Inputs, *scenes: str) -> Measurement:
    """Final P and the chaos criterion of each scene; headline: the largest final P."""
    P = [final_value(inputs, name, "participation").value for name in scenes]
    chaotic = [q.scene_chaotic(inputs.scenes[name], inputs.criteria) for name in scenes]
    energies = [inputs.scenes[name].attrs["energy"] for name in scenes]
    return Measurement(max(P), {"P": np.array(P), "chaotic": np.array(chaotic),
                                "states": list(zip(energies, P, chaotic))})


def chaos_onset(inputs: Inputs, scene: str) -> Measurement:
    """When the orbit turns chaotic for good (case ``never``: not chaotic at the end)."""
    onset = q.chaos_onset(inputs.scenes[scene], inputs.criteria)
    return Measurement(onset, case="never" if onset is None else "")


def early_and_late(inputs: Inputs, first: str, second: str, variable: str, start: float, end: float) -> Measurement:
    """Final value of ``variable`` over its average over start <= t <= end, in two scenes
    (``first``, headline, and ``second``)."""
    ratios = [final_value(inputs, name, variable).value / q.window_mean(inputs.scenes[name], variable, start, end)
              for name in (first, second)]
    return Measurement(ratios[0], {"first": ratios[0], "second": ratios[1]})


def relative_difference(inputs: Inputs, first: str, second: str, variable: str) -> Measurement:
    """|a - b| / ((a + b)/2) of the final values a, b of ``variable`` in two scenes."""
    a, b = (final_value(inputs, name, variable).value for name in (first, second))
    return Measurement(abs(a - b) / (0.5 * (a + b)), {"first": a, "second": b})


def eta_final(inputs: Inputs, scene: str) -> Measurement:
    """Final eta (headline), the equipartition value <eta> and ``excess`` = final eta - <eta>."""
    final = final_value(inputs, scene, "eta").value
    equipartition = q.equipartition_eta(inputs.scenes[scene])
    return Measurement(final, {"equipartition": equipartition, "excess": final - equipartition})


def dvd_at_site(inputs: Inputs, scene: str) -> Measurement:
    """Fraction of the final-window samples whose DVD peaks within dvd_site_halfwidth of the excited bead."""
    c = inputs.criteria
    return Measurement(q.dvd_site_fraction(inputs.scenes[scene], inputs.site, c.dvd_site_halfwidth,
                                           c.final_window_decades))


def max_gaps(inputs: Inputs, scene: str) -> Measurement:
    """Largest number of simultaneously open gaps."""
    return Measurement(q.max_simultaneous_gaps(inputs.scenes[scene]))


def gaps_beside_site(inputs: Inputs, scene: str) -> Measurement:
    """The gaps beside the excited bead s: the bonds that ever opened and their distance from s,
    and whether each of the bead's own two bonds opened, ``left`` bond s (between beads s-1 and
    s) and ``right`` bond s+1 (between beads s and s+1), with the fraction of the run each was
    open (``left_time``, ``right_time``); headline: the largest distance (None when no bond opened)."""
    ds, s = inputs.scenes[scene], inputs.site
    bonds = q.bonds_ever_open(ds)
    distances = q.bond_distance(bonds, s)
    left_time, right_time = (float(x) for x in q.open_time_fraction(ds, (s, s + 1)))
    return Measurement(float(np.max(distances)) if bonds.size else None,
                       {"bonds": bonds, "distances": distances, "opened": bonds.size,
                        "left_bond": s, "right_bond": s + 1, "left": bool(np.isin(s, bonds)),
                        "right": bool(np.isin(s + 1, bonds)), "left_time": left_time, "right_time": right_time})


def gap_spread(inputs: Inputs, scene: str) -> Measurement:
    """When a gap first opens gap_spread_distance or more bonds from the excited bead, and the
    scene's spreading onset (case ``never``: no gap gets there; ``with_onset``: both exist)."""
    ds = inputs.scenes[scene]
    reached = q.gap_spread_time(ds, inputs.site, inputs.criteria.gap_spread_distance)
    onset = _spreading_onset(inputs, scene) if "participation" in ds else None
    case = "never" if reached is None else ("with_onset" if onset is not None else "")
    return Measurement(reached, {"onset": onset}, case=case)


def bond_coverage(inputs: Inputs, scene: str) -> Measurement:
    """How much of the chain the gaps covered: the fraction of its bonds, 1 to N+1 with the two wall
    bonds, that opened at some time (headline), the number that ``never`` did and which
    (``never_bonds``)."""
    ds = inputs.scenes[scene]
    all_bonds = np.asarray(ds["bond"].values)
    never = np.setdiff1d(all_bonds, q.bonds_ever_open(ds))
    return Measurement((all_bonds.size - never.size) / all_bonds.size,
                       {"never": int(never.size), "never_bonds": never, "bonds": int(all_bonds.size)})


# ---- the energy scan ---------------------------------------------------------------------------


def _scan_flags(inputs: Inputs, scan: str, model: str, key: str) -> tuple[np.ndarray, np.ndarray]:
    """The energies of the scan's valid runs of ``model`` and where they satisfy ``key``
    (delocalized, chaotic); an invalid run (energy error above the bound) is neither."""
    ds = inputs.scenes[scan]
    valid = ds["valid"].sel(model=model).values == 1
    return ds.energy.values[valid], criterion_holds(ds, model, key)[valid]


def scan_always(inputs: Inputs, scan: str, model: str, key: str, H: float) -> Measurement:
    """The paper's "for H > H_paper it is always ``key``" on the energy scan's valid runs of
    ``model``: ``holds_above``, whether every scanned energy strictly above H satisfies it,
    ``count`` of the ``above`` ones that do and the ``failing`` ones; the lowest scanned H* above
    which it holds at every scanned energy (headline; None, case ``nowhere``, when it fails at the
    highest). Undecided when no valid run lies above H. For "chaotic" on a scan that also judged
    chaos by GALI_k (``chaotic_gali``): the same by GALI_k, and ``split`` when the two answers differ."""
    E, flag = _scan_flags(inputs, scan, model, key)
    above = E > H * (1 + 1e-9)
    star = always_above(E, flag)
    holds_above = bool(flag[above].all()) if above.any() else None
    split = ""
    if key == "chaotic" and reads_gali(inputs.scenes[scan], model):
        _, by_gali = _scan_flags(inputs, scan, model, "chaotic_gali")
        holds_gali = bool(by_gali[above].all()) if above.any() else None
        if holds_gali is not None and holds_gali != holds_above:
            star_gali = always_above(E, by_gali)
            split = (f"by $\\Lambda$ the packet is chaotic at {int(flag[above].sum())} and by GALI$_k$ at "
                     f"{int(by_gali[above].sum())} of the {int(above.sum())} scanned $H > {tex_parameter(H)}$ "
                     f"(always from $H^* = {tex_number(star)}$ and ${tex_number(star_gali)}$): the two "
                     f"indicators answer differently")
    return Measurement(star if np.isfinite(star) else None,
                       {"star": star, "holds_above": holds_above, "count": int(flag[above].sum()),
                        "above": int(above.sum()), "failing": E[above & ~flag]},
                       case="" if np.isfinite(star) else "nowhere", decided=holds_above is not None, split=split)



def scan_onset(inputs: Inputs, scan: str, model: str, key: str, high: float) -> Measurement:
    """Where ``key`` first holds on the energy scan's valid runs of ``model``: the lowest such
    energy ``first`` (headline; None, case ``never``: nowhere) and the scanned energy ``before``
    it (0 when ``first`` is the lowest; case ``lowest``), so that it sets in within (before, first].
    Undecided when it holds nowhere and no valid run lies above ``high`` (the top of the range the
    paper places the onset in)."""
    E, flag = _scan_flags(inputs, scan, model, key)
    first = first_energy(E, flag)
    if not np.isfinite(first):
        return Measurement(None, {"first": first, "before": np.nan}, case="never",
                           decided=bool((E > high * (1 + 1e-9)).any()))
    lower = E[E < first]
    before = float(lower[-1]) if lower.size else 0.0
    return Measurement(first, {"first": first, "before": before}, case="" if lower.size else "lowest")


def scan_alternation(inputs: Inputs, scan: str, model: str) -> Measurement:
    """The lowest scanned energy where ``model`` is delocalized (headline; case ``never``: none),
    how often the state changes above it (``switches``) and where it is localized again."""
    E, flag = _scan_flags(inputs, scan, model, "delocalized")
    first = first_energy(E, flag)
    if not np.isfinite(first):
        return Measurement(None, {"first": first, "switches": 0}, case="never")
    beyond = E >= first
    return Measurement(first, {"first": first, "switches": switches(flag[beyond]),
                               "localized": E[beyond & ~flag]})


# ---- the ensemble verdicts of a scene ----------------------------------------------------------


def ensemble_statement(inputs: Inputs, scene: str, statement: str) -> Measurement:
    """A statement's measured value over the scene's perturbed orbits: the median (headline; None,
    and NaN as ``median``, when no orbit gives a value), and for yes/no statements how many orbits
    are chaotic of how many decided."""
    values = inputs.verdicts[scene]["measured"].sel(statement=statement).values
    finite = values[np.isfinite(values)]
    median = float(np.median(finite)) if finite.size else float("nan")
    return Measurement(median if finite.size else None,
                       {"median": median, "chaotic": int(np.nansum(values)), "orbits": np.isfinite(values).sum()})


MEASURES = {f.__name__: f for f in (
    localized_mode_counts, localized_levels, limiting_curve, most_extended_mode, mode_participation, mode_peak,
    excited_overlaps, initial_displacement, final_value, window_average, plateau_largest, plateau_median,
    spreading_onset, saturation_time, final_mlce, chaos, participation_and_chaos, localized_and_regular,
    chaos_onset, early_and_late, relative_difference, eta_final, dvd_at_site, max_gaps, gaps_beside_site,
    gap_spread, bond_coverage, scan_always, scan_onset, scan_alternation, ensemble_statement)}
