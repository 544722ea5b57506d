"""The paper's qualitative statements (``statements.STATEMENTS``) decided on ensembles of orbits.

A statement is decided per orbit by the function of its kind in :data:`STATEMENT_KINDS`, which
reduces the orbit's sampled series (``orbits.SERIES``) to one measured value and a yes/no, with the
windows and thresholds of :class:`chainchaos.paper.criteria.Criteria`. Over an ensemble of perturbed
orbits of one scene (``orbits.Orbit.lane``) the outcome is the fraction of the decided orbits that
satisfy it, and the scene's verdict is

- ``holds`` when at least ``criteria.agreement`` of them do,
- ``fails`` when at most 1 - ``agreement`` do,
- ``undecided`` otherwise (the answer depends on the orbit, not only on the scene),
- ``not testable`` when no orbit reached the time the statement needs. A run shorter than that can
  still break a statement marked ``early`` (a packet already spread is not localized at the end).

Chaos is judged by two indicators where the orbits carry GALI_k (``orbits.OrbitSettings.alignment``):
a statement of a kind in :data:`GALI_KINDS` is decided by Λ (its slope criterion) and by GALI_k
(below ``criteria.gali_threshold``) separately, each with its own fraction and verdict; the
scene's verdict is theirs where they agree and ``undecided`` where they do not, and its fraction is
that of the orbits on which both indicators say the statement holds. The onset of chaos is read
from both (GALI_k's crossing time is reported, not judged: it depends on the threshold).

Times in units of 1/omega_max. ``t_paper`` is the paper's integration time, 1e5.
"""

import numpy as np
import xarray as xr

from chainchaos.observe.formulas import finite_time_mlce
from chainchaos.observe.reductions import (
    chaos_onset,
    final_average,
    gali_crossing,
    is_chaotic,
    log_time_median,
    log_time_smooth,
    saturation_time,
    spreading_onset,
    within_factor,
)
from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria

T_PAPER = 1e5

HOLDS, FAILS, UNDECIDED, UNTESTABLE, NOT_READ = 1, 0, -1, -2, -3
VERDICT_NAMES = {HOLDS: "holds", FAILS: "fails", UNDECIDED: "undecided", UNTESTABLE: "not testable",
                 NOT_READ: "not read"}
#: flag attributes of a verdict variable (NOT_READ: the indicator does not decide the statement)
VERDICT_FLAGS = {"flag_values": np.array([-3, -2, -1, 0, 1], dtype=np.int8),
                 "flag_meanings": "not_read not_testable undecided fails holds"}

#: attributes of the coordinates of an ensemble (chainchaos.run.orbits: lane 0 is the scene's own orbit)
LANE = {"units": "1", "long_name": "lane j: orbit of the ensemble, 0 the scene's own, j >= 1 perturbed"}
STATEMENT = {"long_name": "id of the paper's statement (chainchaos.paper.statements.STATEMENTS)"}


def _final_p(t, s, st, c):
    return final_average(t, s["participation"], c.final_window_decades)


def _end(t, st) -> float:
    """The end of the run, or of the window ending at the statement's ``until``."""
    return float(t[-1]) if st.until is None else min(float(st.until), float(t[-1]))


def _chaotic(t, s, st, c):
    """1.0 if the orbit is chaotic by Λ at the end of the run (or of the window ending at ``until``)."""
    return float(is_chaotic(t, s["log_growth"], c.chaos_slope, c.chaos_growth_margin,
                            c.chaos_window_decades, _end(t, st)))


def _gali_chaotic(t, s, st, c):
    """1.0 if GALI_k fell below its threshold by the end of the run (or by ``until``)."""
    return float(np.isfinite(gali_crossing(t, s["log_gali"], c.gali_threshold, _end(t, st))))


def _gali_onset(t, s, st, c):
    return gali_crossing(t, s["log_gali"], c.gali_threshold)


def _p_until(t, s, st, c):
    """The largest smoothed P from ``plateau_start`` to the statement's end time ("P < 3 up to
    t ~ 2e2"): P smoothed as the paper plots it, from the samples up to that time only."""
    end = min(float(st.until), float(t[-1]))
    upto = t <= end
    smooth = log_time_smooth(t[upto], s["participation"][upto], c.smoothing_decades)
    window = t[upto] >= c.plateau_start
    return float(np.max(smooth[window])) if window.any() else float("nan")


def _saturation(t, s, st, c):
    return saturation_time(t, s["participation"], c.saturation_fraction, c.smoothing_decades,
                           c.final_window_decades, c.onset_hold_decades)


def _spreading_onset(t, s, st, c):
    return spreading_onset(t, s["participation"], c.spreading_factor, c.smoothing_decades, c.plateau_start,
                           c.onset_hold_decades)


def _final_mlce(t, s, st, c):
    return float(finite_time_mlce(s["log_growth"], t)[-1])


def _chaos_onset(t, s, st, c):
    return chaos_onset(t, s["log_growth"], c.chaos_slope, c.chaos_growth_margin, c.chaos_window_decades)


def _eta_median(t, s, st, c):
    """The median of eta over log time from ``plateau_start`` to the end ("for most of the
    evolution", on the paper's logarithmic time axis): the run's densely sampled last decade
    weighs one decade."""
    return log_time_median(t, s["eta"], c.plateau_start)


#: kind -> (measure(t, series, statement, criteria), passed(value, statement, criteria),
#: time required(statement), unit, description of the criterion).
STATEMENT_KINDS = {
    "localized": (_final_p, lambda v, st, c: v <= c.localized_p_max, lambda st: T_PAPER, "1",
                  "time-averaged $P$ over the last decade $\\le \\cc{crit.localizedpmax}$"),
    "delocalized": (_final_p, lambda v, st, c: v >= c.delocalized_p_min, lambda st: T_PAPER, "1",
                    "time-averaged $P$ over the last decade $\\ge \\cc{crit.delocalizedpmin}$"),
    "chaotic": (_chaotic, lambda v, st, c: v == 1.0, lambda st: T_PAPER, "1",
                "chaotic over the last decade (slope and growth criterion)"),
    "regular": (_chaotic, lambda v, st, c: v == 0.0, lambda st: T_PAPER, "1",
                "not chaotic over the last decade (slope and growth criterion)"),
    "regular_until": (_chaotic, lambda v, st, c: v == 0.0, lambda st: st.until, "1",
                      "not chaotic over the decade before the statement's end time"),
    "participation_below_until": (_p_until, lambda v, st, c: v < st.value, lambda st: st.until, "1",
                                  "smoothed $P$ below the paper's level at every sample from $t = \\cc{crit.plateaustart}$ to the statement's end time"),
    "saturation_near": (_saturation, lambda v, st, c: within_factor(v, st.value, c.tolerance.time_factor),
                        lambda st: T_PAPER, "time",
                        "smoothed $P$ stays above \\cc{crit.saturationfraction} of its final average from a "
                        "time within a factor \\cc{tol.timefactor} of the paper's"),
    "spreading_onset_near": (_spreading_onset,
                             lambda v, st, c: within_factor(v, st.value, c.tolerance.time_factor),
                             lambda st: T_PAPER, "time",
                             "smoothed $P$ stays above \\cc{crit.spreadingfactor} times its value at "
                             "$t = \\cc{crit.plateaustart}$ from a time within a factor \\cc{tol.timefactor} of the paper's"),
    "mlce_near": (_final_mlce, lambda v, st, c: within_factor(v, st.value, c.tolerance.mlce_factor),
                  lambda st: T_PAPER, "1/time",
                  "$\\Lambda(t_\\mathrm{end})$ within a factor \\cc{tol.mlcefactor} of the paper's"),
    "chaos_onset_near": (_chaos_onset, lambda v, st, c: within_factor(v, st.value, c.tolerance.time_factor),
                         lambda st: T_PAPER, "time",
                         "onset of chaos (the criterion holding to the end) within a factor "
                         "\\cc{tol.timefactor} of the paper's time"),
    "eta_near": (_eta_median, lambda v, st, c: abs(v - st.value) <= c.tolerance.eta_plateau, lambda st: T_PAPER,
                 "1", "median over $\\log t$ of $\\eta$ from $t = \\cc{crit.plateaustart}$ to the end within \\cc{tol.etaplateau} of "
                 "the paper's level"),
}


#: kind -> (measure by GALI_k, passed(value, statement, criteria) or None where the value is
#: reported only), for the statements that GALI_k decides beside Λ.
GALI_KINDS = {
    "chaotic": (_gali_chaotic, lambda v, st, c: v == 1.0),
    "regular": (_gali_chaotic, lambda v, st, c: v == 0.0),
    "regular_until": (_gali_chaotic, lambda v, st, c: v == 0.0),
    "chaos_onset_near": (_gali_onset, None),
}


def outcome(statement: statements.Statement, t, series: dict, criteria: Criteria, valid: bool = True) -> tuple[float, float]:
    """(measured value, outcome) of one orbit by Λ and the other series: outcome 1.0 satisfied, 0.0
    violated, NaN undecidable (an invalid run, or a run shorter than the statement needs that does
    not already break it)."""
    measure, passed, required, *_ = STATEMENT_KINDS[statement.kind]
    return _decide(measure, passed, required, statement, t, series, criteria, valid)


def gali_outcome(statement: statements.Statement, t, series: dict, criteria: Criteria,
                 valid: bool = True) -> tuple[float, float]:
    """(measured value, outcome) of one orbit by GALI_k, as :func:`outcome`; (NaN, NaN) for a
    statement GALI_k does not decide (not in :data:`GALI_KINDS`, or no ``log_gali`` series), and
    outcome NaN for one whose value it only reports."""
    if statement.kind not in GALI_KINDS or "log_gali" not in series:
        return float("nan"), float("nan")
    measure, passed = GALI_KINDS[statement.kind]
    required = STATEMENT_KINDS[statement.kind][2]
    value, out = _decide(measure, passed or (lambda v, st, c: True), required, statement, t, series, criteria, valid)
    return value, (out if passed is not None else float("nan"))


def _decide(measure, passed, required, statement, t, series, criteria, valid) -> tuple[float, float]:
    t = np.asarray(t, dtype=float)
    if not valid:
        return float("nan"), float("nan")
    with np.errstate(invalid="ignore", divide="ignore"):
        value = float(measure(t, series, statement, criteria))
    if not np.isfinite(value) and not statement.kind.endswith("_near"):
        return value, float("nan")
    ok = bool(passed(value, statement, criteria))
    if t[-1] < required(statement) * (1 - 1e-9):
        return value, (0.0 if (statement.early and not ok) else float("nan"))
    return value, float(ok)


def verdict_code(fraction: float, agreement: float) -> int:
    """HOLDS when at least ``agreement`` of the orbits satisfy a statement, FAILS when at most
    1 - ``agreement`` do, UNDECIDED between, UNTESTABLE for NaN (no orbit decided it)."""
    if not np.isfinite(fraction):
        return UNTESTABLE
    if fraction >= agreement - 1e-12:
        return HOLDS
    if fraction <= 1.0 - agreement + 1e-12:
        return FAILS
    return UNDECIDED


def ensemble_verdict(outcomes, agreement: float) -> tuple[float, int, int]:
    """(fraction satisfied among the decided orbits, number decided, verdict code)."""
    x = np.asarray(outcomes, dtype=float)
    decided = np.isfinite(x)
    n = int(decided.sum())
    frac = float(x[decided].mean()) if n else float("nan")
    return frac, n, verdict_code(frac, agreement)


def two_indicator_verdict(lam, gali, agreement: float, read: bool = True) -> dict:
    """The ensemble verdict of a statement from the per-orbit outcomes by Λ and by GALI_k (``read``
    False: GALI_k does not decide it, and the verdict is Λ's). Keys: ``fraction``, ``n_decided``,
    ``verdict`` (the two verdicts where they agree, UNDECIDED where not; the fraction over the
    orbits both decide, of those on which both say it holds) and per indicator
    ``fraction_lambda``, ``verdict_lambda``, ``fraction_gali``, ``verdict_gali`` (NOT_READ)."""
    lam, gali = np.asarray(lam, dtype=float), np.asarray(gali, dtype=float)
    f_l, n_l, v_l = ensemble_verdict(lam, agreement)
    out = {"fraction_lambda": f_l, "verdict_lambda": v_l, "fraction_gali": float("nan"), "verdict_gali": NOT_READ,
           "fraction": f_l, "n_decided": n_l, "verdict": v_l}
    if not read:
        return out
    f_g, _, v_g = ensemble_verdict(gali, agreement)
    both = np.isfinite(lam) & np.isfinite(gali)
    n = int(both.sum())
    out.update(fraction_gali=f_g, verdict_gali=v_g, n_decided=n,
               fraction=float(((lam == 1.0) & (gali == 1.0))[both].mean()) if n else float("nan"),
               verdict=v_l if v_l == v_g else UNDECIDED)
    return out


def evaluate(scene_statements, t, runs: list[dict], criteria: Criteria) -> dict[str, np.ndarray]:
    """Outcomes and measured values of ``scene_statements`` (one scene's) over ``runs`` (its orbits, as
    returned by ``orbits.integrate``) by Λ (``value``, ``outcome``) and by GALI_k (``value_gali``,
    ``outcome_gali``, NaN where it does not decide): arrays (statement, lane); ``read_gali``
    (statement,): GALI_k decides the statement."""
    S, L = len(scene_statements), len(runs)
    ev = {key: np.full((S, L), np.nan) for key in ("value", "outcome", "value_gali", "outcome_gali")}
    ev["read_gali"] = np.array([st.kind in GALI_KINDS and GALI_KINDS[st.kind][1] is not None
                                and all("log_gali" in r for r in runs) for st in scene_statements], dtype=bool)
    for i, st in enumerate(scene_statements):
        for j, r in enumerate(runs):
            ev["value"][i, j], ev["outcome"][i, j] = outcome(st, t, r, criteria, r["valid"])
            ev["value_gali"][i, j], ev["outcome_gali"][i, j] = gali_outcome(st, t, r, criteria, r["valid"])
    return ev


def scene_verdicts(ev: dict, agreement: float) -> dict[str, np.ndarray]:
    """Per statement of :func:`evaluate`'s arrays, the keys of :func:`two_indicator_verdict` as arrays."""
    rows = [two_indicator_verdict(lam, gali, agreement, read)
            for lam, gali, read in zip(ev["outcome"], ev["outcome_gali"], ev["read_gali"])]
    return {key: np.array([r[key] for r in rows]) for key in rows[0]} if rows else {}


def verdict_variables(ev: dict, sv: dict) -> dict:
    """The per-lane outcomes and measured values (:func:`evaluate`'s ``ev``, arrays (statement,
    lane)) and the ensemble's fractions and verdicts (:func:`scene_verdicts`' ``sv``) as the data
    variables of a verdict or search-score file."""
    one = {"units": "1"}
    fraction = {**one, "long_name": "fraction of the decided lanes that satisfy the statement"}
    return {
        "measured": (("statement", "lane"), ev["value"], {"long_name": "measured value of the statement per lane"}),
        "outcome": (("statement", "lane"), ev["outcome"],
                    {**one, "long_name": "1 satisfied, 0 violated, NaN undecidable (per lane, by Lambda and P)"}),
        "measured_gali": (("statement", "lane"), ev["value_gali"],
                          {"long_name": "measured value of the statement per lane by GALI_k (NaN: not read)"}),
        "outcome_gali": (("statement", "lane"), ev["outcome_gali"],
                         {**one, "long_name": "1 satisfied, 0 violated, NaN undecidable or not read (per lane, by GALI_k)"}),
        "fraction": ("statement", sv["fraction"],
                     {**one, "long_name": "fraction of the lanes decided by every indicator on which all say the "
                                          "statement holds"}),
        "fraction_lambda": ("statement", sv["fraction_lambda"], {**fraction, "comment": "by Lambda"}),
        "fraction_gali": ("statement", sv["fraction_gali"], {**fraction, "comment": "by GALI_k (NaN: not read)"}),
        "n_decided": ("statement", sv["n_decided"].astype(np.int32),
                      {**one, "long_name": "lanes whose run decides the statement"}),
        "verdict": ("statement", sv["verdict"].astype(np.int8),
                    {"long_name": "ensemble verdict (undecided where the indicators disagree)", **VERDICT_FLAGS}),
        "verdict_lambda": ("statement", sv["verdict_lambda"].astype(np.int8),
                           {"long_name": "ensemble verdict by Lambda", **VERDICT_FLAGS}),
        "verdict_gali": ("statement", sv["verdict_gali"].astype(np.int8),
                         {"long_name": "ensemble verdict by GALI_k", **VERDICT_FLAGS}),
    }


def verdict_dataset(scene_name: str, t, runs: list[dict], criteria: Criteria, attrs: dict) -> xr.Dataset:
    """One scene's ensemble: the series of every lane and, per statement, every lane's outcome by
    each indicator, the fractions satisfied and the verdicts."""
    from chainchaos.observe.registry import REGISTRY

    of_scene = statements.statements_of_scene(scene_name)
    ev = evaluate(of_scene, t, runs, criteria)
    sv = scene_verdicts(ev, criteria.agreement)
    one = {"units": "1"}
    series = [key for key in runs[0] if isinstance(runs[0][key], np.ndarray)]
    data = {
        key: (("lane", "time"), np.stack([r[key] for r in runs]), {**one, "long_name": REGISTRY[key].long_name})
        for key in series
    }
    data.update({
        "u0": ("lane", np.array([r["u0"] for r in runs]), {**one, "long_name": "initial displacement of the excited bead"}),
        "valid": ("lane", np.array([r["valid"] for r in runs], dtype=np.int8),
                  {**one, "long_name": "1 if the run stayed finite with energy error <= max_energy_error"}),
        "max_gaps": ("lane", np.array([r["max_gaps"] for r in runs], dtype=np.int32),
                     {**one, "long_name": "largest number of simultaneously open gaps (-1: FPUT)"}),
        **verdict_variables(ev, sv),
        "kind": ("statement", np.array([st.kind for st in of_scene], dtype=object)),
        "text": ("statement", np.array([st.text for st in of_scene], dtype=object)),
    })
    ds = xr.Dataset(data, coords={"statement": ("statement", [st.id for st in of_scene], STATEMENT),
                                  "lane": ("lane", np.arange(len(runs)), LANE), "time": np.asarray(t, dtype=float)})
    ds.time.attrs.update(units="1", long_name="time",
                         comment="nondimensional time, unit 1/omega_max of the homogeneous linear chain")
    ds.attrs.update(attrs)
    ds.attrs.update(scene=scene_name, agreement=float(criteria.agreement),
                    gali_threshold=float(criteria.gali_threshold),
                    title=f"chainchaos ensemble verdicts of scene {scene_name}")
    return ds
