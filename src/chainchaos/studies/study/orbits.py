"""What an orbit of a study is reduced to, and the settings and excitation rule that decide it.

Many orbits, each reduced to a handful of numbers (:func:`reduce_orbit`, :data:`SCALARS`):

- ``participation_final``: the time average of the participation number P over the last decade
  (t >= t_final / 10; ``reductions.final_average`` on the log-spaced samples plus
  ``final_samples`` evenly spaced ones);
- ``mlce_final``: the finite-time mLCE Lambda(t_final), and ``log_growth_final`` = Lambda t =
  ln(|v(t)|/|v(0)|) at t_final;
- ``eta_final``: the time average of the normalised spectral entropy eta over the last decade;
- ``max_gaps``: the largest number of simultaneously open Hertz bonds over the run (FPUT: -1);
- ``delocalization_onset``: the first sample time from which P(t) stays above ``p_delocalized``
  for ``onset_hold_decades`` (``reductions.sustained_onset``; NaN if never);
- ``chaos_onset``: the onset of chaos (``reductions.chaos_onset``; NaN if not chaotic at the end);
- with ``alignment``, the second chaos indicator: ``chaotic_gali`` (GALI_k below ``gali_threshold``
  by t_final; -1 without GALI_k) and ``gali_onset``, the time it crosses (NaN: never).

Criteria (:class:`StudySettings`, stated in every output file by :func:`criteria_attrs`):

- delocalized: ``participation_final > p_delocalized`` (default 10: the initial excitation has
  P ~ 1-3, an equipartitioned chain of N = 40 beads P ~ 20-27).
- chaotic: the paper's reading of Lambda(t) over the last decade (``reductions.is_chaotic``): its
  log-log slope exceeds ``chaos_slope`` (a regular orbit's Lambda ~ ln(t)/t has slope near -1, a
  chaotic one levels off) and ln|v| grew by more than ln 10 + ``chaos_growth_margin`` (faster than
  the linear growth a regular orbit allows). A chaotic orbit with mLCE lambda is seen once
  lambda t_final is of order 10, so a short run (t = 1e3) reports only strong chaos. With
  ``alignment`` each run is also judged by GALI_k.

Excitation of a realization (:func:`select_excitation`): among the ``high_frequency_modes``
highest linear modes, those whose energy-density maximum lies within ``centre_window`` sites of the
chain centre (N+1)/2; the one with the smallest participation number is chosen, and its maximum
bead is excited alone (u = u0 at that bead, p = 0), as in the paper. If no high mode peaks near the
centre, the most localized high mode anywhere is taken and ``selection_fallback`` is set.
"""

import math
from dataclasses import asdict, dataclass

import numpy as np

from chainchaos.errors import require, require_finite_positive
from chainchaos.kernels import exactmath
from chainchaos.observe.reductions import (
    chaos_onset,
    final_average,
    gali_crossing,
    is_chaotic,
    sustained_onset,
)
from chainchaos.run.orbits import OrbitSettings
from chainchaos.system.linear import (
    mode_energy_density,
    normal_modes,
    participation_number,
)

SELECTION_RULE = ("among the high_frequency_modes highest linear modes, those whose energy-density maximum "
                  "lies within centre_window sites of the chain centre (N+1)/2; the one with the smallest "
                  "participation number is chosen and its maximum bead alone is displaced (p = 0)")


@dataclass(kw_only=True)
class StudySettings(OrbitSettings):
    """Integration, sampling (``orbits.OrbitSettings``) and classification of a study's orbits."""

    p_delocalized: float = 10.0
    chaos_slope: float = -0.5
    chaos_growth_margin: float = 2.0
    onset_hold_decades: float = 0.5
    gali_threshold: float = 1e-8

    def __post_init__(self):
        super().__post_init__()
        require_finite_positive(self, "p_delocalized")
        require(0 < self.gali_threshold < 1, "gali_threshold", self.gali_threshold, "0 < gali_threshold < 1")
        require(np.isfinite(self.chaos_slope) and self.chaos_slope <= 0, "chaos_slope", self.chaos_slope, "<= 0")
        for key in ("chaos_growth_margin", "onset_hold_decades"):
            require(np.isfinite(getattr(self, key)) and getattr(self, key) >= 0, key, getattr(self, key), ">= 0")


#: The keys of a study file's blocks ``integration``, ``ensemble`` and ``criteria`` that give a
#: :class:`StudySettings` (``alignment`` follows from the observables, the engine is the batch one).
SETTINGS_BLOCKS = {
    "integration": ("integrator", "dt", "t_final", "samples_per_decade", "t_first_sample", "final_samples",
                    "check_every", "max_energy_error", "k4_sign", "deviation_seed"),
    "ensemble": ("perturbation", "perturbation_seed"),
    "criteria": ("p_delocalized", "chaos_slope", "chaos_growth_margin", "onset_hold_decades", "gali_order",
                 "gali_threshold"),
}


def settings_blocks(settings: StudySettings) -> dict:
    """The blocks ``integration``, ``ensemble`` and ``criteria`` of a study file whose orbits are
    integrated and judged with ``settings``.

    Parameters
    ----------
    settings : StudySettings
        Integration, sampling, perturbations and criteria of the orbits.

    Returns
    -------
    dict
        ``{block: {key: value}}`` with the keys of :data:`SETTINGS_BLOCKS`.
    """
    values = {**asdict(settings), "k4_sign": int(settings.k4_sign)}
    return {block: {key: values[key] for key in keys} for block, keys in SETTINGS_BLOCKS.items()}


def select_excitation(chain, high_frequency_modes: int = 14, centre_window: int = 5,
                      convention: str = "potential") -> dict:
    """The most localized high-frequency mode near the centre of ``chain`` and its maximum bead.

    Candidates are the ``high_frequency_modes`` highest modes (k > N - high_frequency_modes)
    whose energy-density maximum bead n satisfies |n - (N+1)/2| <= ``centre_window``; the one with
    the smallest participation number wins (P from ``linear.mode_energy_density``, ``convention``).
    Returns mode (1-based), site (1-based bead of the maximum), participation, fallback (True if
    no candidate peaked near the centre and the most localized high mode anywhere was taken).
    """
    N = chain.N
    require(1 <= high_frequency_modes <= N, "high_frequency_modes", high_frequency_modes, f"1..{N}")
    require(centre_window >= 0, "centre_window", centre_window, ">= 0")
    omega, U = normal_modes(chain)
    h = mode_energy_density(chain, omega, U, convention)
    P = participation_number(h)
    peak = np.argmax(h, axis=0) + 1
    high = np.arange(N - high_frequency_modes, N)
    near = high[np.abs(peak[high] - (N + 1) / 2.0) <= centre_window]
    fallback = near.size == 0
    pool = high if fallback else near
    k = int(pool[np.argmin(P[pool])])
    return {"mode": k + 1, "site": int(peak[k]), "participation": float(P[k]), "fallback": bool(fallback),
            "frequency": float(omega[k])}


def reduce_orbit(times: np.ndarray, r: dict, settings: StudySettings) -> dict:
    """The scan observables (module docstring) of one integrated orbit (a result of
    ``orbits.integrate``); ``eta_final`` is NaN where the orbit kept no eta."""
    with np.errstate(invalid="ignore", divide="ignore"):
        P, g = r["participation"], r["log_growth"]
        P_fin = final_average(times, P)
        return {
            "participation_final": P_fin,
            "participation_last": float(P[-1]),
            "mlce_final": float(g[-1] / times[-1]),
            "log_growth_final": float(g[-1]),
            "eta_final": final_average(times, r["eta"]) if "eta" in r else float("nan"),
            "max_gaps": r["max_gaps"],
            "delocalized": bool(P_fin > settings.p_delocalized),
            "chaotic": is_chaotic(times, g, settings.chaos_slope, settings.chaos_growth_margin),
            "delocalization_onset": sustained_onset(times, P, settings.p_delocalized, settings.onset_hold_decades),
            "chaos_onset": chaos_onset(times, g, settings.chaos_slope, settings.chaos_growth_margin),
            **_gali_reading(times, r, settings),
            "energy_error_max": float(np.max(r["energy_error"])),
            "u0": r["u0"],
            "valid": r["valid"],
        }


def _gali_reading(times, run: dict, settings: StudySettings) -> dict:
    """``chaotic_gali`` (1, 0; -1 without GALI_k) and ``gali_onset`` of one run."""
    if "log_gali" not in run:
        return {"chaotic_gali": -1, "gali_onset": float("nan")}
    onset = gali_crossing(times, run["log_gali"], settings.gali_threshold)
    return {"chaotic_gali": int(np.isfinite(onset)), "gali_onset": onset}


def energy_range(block: dict) -> tuple[int, float, float]:
    """(n_energies, energy_min, energy_max) of a scan block, checked (ParameterError names the
    key): what the config check asks of a grid, without computing it."""
    n, lo, hi = int(block["n_energies"]), float(block["energy_min"]), float(block["energy_max"])
    require(n >= 1, "n_energies", n, ">= 1")
    require(0 < lo <= hi, "energy_min", lo, f"0 < energy_min <= energy_max = {hi}")
    return n, lo, hi


def energy_grid(block: dict) -> np.ndarray:
    """Energies of a scan block: ``n_energies`` values from ``energy_min`` to ``energy_max``,
    log-spaced (``spacing: log``, default) or linear; rounded to 6 significant digits so that
    they print and compare cleanly."""
    n, lo, hi = energy_range(block)
    if block.get("spacing", "log") == "log":  # scalar libm logs and powers: the same grid on every CPU
        grid = exactmath.exp10(np.linspace(math.log10(lo), math.log10(hi), n))
        grid[0], grid[-1] = lo, hi
    else:
        grid = np.linspace(lo, hi, n)
    return np.array([float(f"{e:.6g}") for e in grid])


SCALARS = {
    "participation_final": ("time average of the participation number P over the last decade", "f8"),
    "mlce_final": ("finite-time mLCE Lambda(t_final)", "f8"),
    "log_growth_final": ("Lambda(t_final) t_final = ln(|v(t_final)|/|v(0)|)", "f8"),
    "eta_final": ("time average of the normalised spectral entropy eta over the last decade", "f8"),
    "max_gaps": ("largest number of simultaneously open gaps over the run (-1: a model without gaps)", "i4"),
    "delocalized": ("1 if participation_final > p_delocalized", "i1"),
    "chaotic": ("1 if chaotic over the last decade (chaos_criterion)", "i1"),
    "delocalization_onset": ("first time from which P(t) > p_delocalized for onset_hold_decades (NaN: never)", "f8"),
    "chaos_onset": ("onset of chaos: from it on the chaos criterion holds to the end (NaN: never)", "f8"),
    "chaotic_gali": ("1 if GALI_k fell below gali_threshold by t_final, 0 if not, -1 without GALI_k", "i1"),
    "gali_onset": ("first time GALI_k < gali_threshold (NaN: never, or without GALI_k)", "f8"),
    "energy_error_max": ("largest relative energy error |H(t) - H(0)|/H(0) at the samples", "f8"),
    "u0": ("initial displacement of the excited bead", "f8"),
    "valid": ("1 if the run stayed finite with energy error <= max_energy_error", "i1"),
}


#: the excitation select_excitation picks in each realization: variable -> (its key, dtype)


EXCITATION_PICKS = {"excited_mode": ("mode", np.int32), "excited_site": ("site", np.int32),
                    "excited_mode_participation": ("participation", np.float64),
                    "selection_fallback": ("fallback", np.int8)}


EXCITATION = {
    "excited_mode": {"units": "1", "long_name": "excited linear mode k (1-based, by increasing frequency)"},
    "excited_site": {"units": "1", "long_name": "excited bead n: the maximum of the mode's energy density"},
    "excited_mode_participation": {"units": "1", "long_name": "participation number of the excited mode"},
    "selection_fallback": {"units": "1", "long_name": "1 if no candidate mode peaked near the centre and "
                                                      "the most localized high mode anywhere was taken"},
}


def criteria_attrs(settings: StudySettings) -> dict:
    return {
        "p_delocalized": float(settings.p_delocalized),
        "chaos_slope": float(settings.chaos_slope),
        "chaos_growth_margin": float(settings.chaos_growth_margin),
        "onset_hold_decades": float(settings.onset_hold_decades),
        "gali_order": settings.judged_gali_order,
        "gali_threshold": float(settings.gali_threshold),
        "delocalization_criterion": (f"delocalized if the time average of P over the last decade "
                                     f"(t >= t_final/10) exceeds p_delocalized = {settings.p_delocalized:g}"),
        "chaos_criterion": (f"chaotic if over the last decade the log-log slope of Lambda(t) exceeds "
                            f"chaos_slope = {settings.chaos_slope:g} and ln|v| grew by more than ln 10 + "
                            f"chaos_growth_margin = {settings.chaos_growth_margin:g}: Lambda has left the "
                            f"t^-1 law of a regular orbit and levels off"),
    }
