"""Many orbits integrated together on the batch engine and sampled on one schedule.

The driver of everything that runs more than one trajectory and reduces each to a few series:
the energy scan and the disorder statistics (``chainchaos.studies.scan.runs``), the realization search
(``chainchaos.studies.search.stages``) and the ensemble verdicts (``chainchaos.paper.verdicts``). An :class:`Orbit` is a
model, an energy, a chain, the excited bead and a lane number: lane 0 is the scene's own orbit
(bead ``site`` displaced by u0 with H = energy, deviation vector from ``deviation_seed``), lane
j >= 1 the same with u0 (1 + perturbation xi_j), xi_j uniform in [-1, 1] from
``default_rng([perturbation_seed, j])``, and the deviation vector from ``deviation_seed + j``. An
ensemble of lanes asks whether a verdict survives changes at the level of the last bits of the
initial state, which is what separates a property of the scene from one of a single orbit.

Orbits of one model share a batch (``chainchaos.engine.batch``, any mix of chains, energies and lanes)
or run one after the other on ``integrators.advance`` (``engine: single``); both give identical
numbers. At every sample the series of :data:`SERIES` are recorded per orbit; with ``alignment``,
also ln GALI_k and SALI (:data:`ALIGNMENT_SERIES`) of the mLCE vector and ``gali_order`` - 1 more
vectors, the second chaos indicator of the verdicts; with ``spectrum``, the Lyapunov spectrum of
``exponents`` vectors and h_KS (:data:`SPECTRUM_SERIES`). Lane j's extra vectors come from
``deviation_seed + j`` (``RunSettings.extra_deviations``; docs/conventions.md#chaos-indicators).
"""

import math
from dataclasses import dataclass, field, fields

import numpy as np

from chainchaos.errors import ParameterError, require
from chainchaos.observe.registry import REGISTRY
from chainchaos.run import driver
from chainchaos.run.settings import RunSettings
from chainchaos.run.window import Window, restricted_deviation
from chainchaos.system.initial import Excitation, initial_deviation
from chainchaos.system.models import MODELS, get_model

#: Per-orbit series on the sample times, observables of the registry (``observe.registry``), with
#: their value at samples where the state is not measured (no initial state, or non-finite);
#: None: kept as the engine recorded it.
SERIES = {"participation": np.nan, "log_growth": None, "eta": np.nan, "energy_error": np.inf}
#: The series of runs with ``alignment`` (SALI of the mLCE vector and the first GALI vector): NaN
#: after a stop (``driver.sample``'s ``gali_stop``).
ALIGNMENT_SERIES = {"log_gali": None, "sali": None}
#: The series of runs with ``spectrum``: lambda_i(t) (time, exponent) and h_KS(t).
SPECTRUM_SERIES = {"lyapunov_spectrum": None, "ks_entropy": None}


@dataclass(frozen=True, kw_only=True)
class Orbit:
    """One trajectory: a model, an energy, a chain, the excited bead (1-based) and a lane; with an
    ``excitation`` (``initial.Excitation``: a site, a mode or a block, in displacement or momentum)
    that state instead of bead ``site`` displaced, lane j scaling the whole state by the same
    1 + perturbation xi_j."""

    model: str
    energy: float
    chain: object = field(repr=False)
    site: int
    lane: int = 0
    excitation: object = None


@dataclass(kw_only=True)
class OrbitSettings(RunSettings):
    """Integration and sampling of a set of orbits (:class:`RunSettings`), their perturbations
    and the engine they run on.

    Samples: those of :meth:`RunSettings.sample_steps` plus ``final_samples`` evenly spaced over
    the last decade, so that time averages over it see the fast oscillations of a packet evenly.
    ``alignment``: evolve GALI_``gali_order``'s vectors too and record ln GALI_k; ``spectrum``:
    the Lyapunov spectrum's ``exponents`` vectors (0: all 2N)."""

    samples_per_decade: int = 10
    t_first_sample: float = 1.0
    final_samples: int = 0
    perturbation: float = 1e-9
    perturbation_seed: int = 0
    batch_size: int = 32
    engine: str = "batch"
    alignment: bool = False
    spectrum: bool = False

    def __post_init__(self):
        super().__post_init__()
        for key in ("alignment", "spectrum"):
            value = getattr(self, key)
            require(isinstance(value, bool) and not (value and self.engine == "single"), key, value,
                    "true or false; true only with engine 'batch' (extra deviation vectors run in SIMD blocks)")
        require(self.engine in ("batch", "single"), "engine", self.engine, "'batch' or 'single'")
        require(int(self.batch_size) >= 1, "batch_size", self.batch_size, ">= 1")
        require(int(self.final_samples) >= 0, "final_samples", self.final_samples, "an integer >= 0")
        require(np.isfinite(self.perturbation) and 0 <= self.perturbation < 1e-3, "perturbation",
                self.perturbation, "0 <= perturbation < 1e-3 (a relative change of u0)")

    @property
    def judged_gali_order(self) -> int:
        """k of the GALI_k that judges chaos beside Λ, as result files state it (0: Λ alone)."""
        return int(self.gali_order) if self.alignment else 0

    @classmethod
    def from_config(cls, block: dict):
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in block.items() if k in names})


def map_samples(times: np.ndarray, wanted) -> np.ndarray:
    """Indices of the samples (at ``times``) nearest in log t to each of the ``wanted`` times
    (t = 0 excluded): where a study keeps its density maps (``integration.map_times``)."""
    log_t = np.log10(np.where(times > 0, times, np.nan))
    return np.array([int(np.nanargmin(np.abs(log_t - np.log10(t)))) for t in wanted], dtype=np.int64)


def sample_schedule(settings: OrbitSettings) -> np.ndarray:
    """Step indices of the samples: the log-spaced ones of :meth:`RunSettings.sample_steps` and
    ``final_samples`` evenly spaced ones over the last decade."""
    steps = settings.sample_steps()
    if settings.final_samples:
        n_final = steps[-1]
        dense = np.rint(np.linspace(0.1, 1.0, int(settings.final_samples) + 1) * n_final).astype(np.int64)
        steps = np.union1d(steps, dense)
    return steps


def lane_factor(lane: int, settings: OrbitSettings) -> float:
    """1 + perturbation xi_lane, the factor on u0 of a lane (exactly 1 for lane 0)."""
    if lane == 0:
        return 1.0
    xi = np.random.default_rng([int(settings.perturbation_seed), int(lane)]).uniform(-1.0, 1.0)
    return 1.0 + settings.perturbation * xi


def integrate(orbits: list[Orbit], settings: OrbitSettings, progress=None, gali_stop: float | None = None,
              series: dict | None = None, window=None, deviation_start: str = "all") -> tuple[np.ndarray, list[dict]]:
    """Integrate every orbit with its tangent map (and gap counting where bonds open) and sample it.

    Returns the sample times and, per orbit in input order, a dict with the :data:`SERIES` arrays
    (and :data:`ALIGNMENT_SERIES` with ``settings.alignment``) and ``u0``, ``max_gaps`` (-1 for a
    model without gaps) and ``valid`` (the initial state exists, the run stayed finite and its
    energy error stayed <= ``max_energy_error``). ``gali_stop``: an orbit's GALI vectors stop once
    its ln GALI_k is below it (``driver.sample``); results do not depend on which orbits share a
    batch. ``progress(done, total)`` is called at every decade of time and at the end of each
    batch of orbits, ``done`` counting the orbits of the running batch by the fraction of its
    steps made (so it may be fractional). ``series``: the per-orbit series to record instead of
    :data:`SERIES` (name -> fill, as
    there; ``energy_error`` is always recorded, since validity reads it). ``window``: integrate
    only where the packets are (``run.window.Window``; None: the whole chain). ``deviation_start``:
    the mLCE vector random on every site ("all") or that vector on the excited sites only, scaled
    back to its norm ("excited", as a window starts it: on a large lattice integrated whole, a
    vector spread over every site is mostly on sites at rest, whose regular part Lambda takes long
    to outgrow)."""
    require(deviation_start in ("all", "excited"), "deviation_start", deviation_start, "'all' or 'excited'")
    require(window is None or not (settings.alignment or settings.spectrum), "window", window,
            "None with GALI or Lyapunov spectrum vectors (only the mLCE vector runs on a window)")
    wanted = SERIES if series is None else {**series, "energy_error": SERIES["energy_error"]}
    results = [None] * len(orbits)
    times = sample_schedule(settings) * settings.dt
    for name in MODELS:
        index = [i for i, o in enumerate(orbits) if o.model == name]
        for start in range(0, len(index), int(settings.batch_size)):
            chunk = index[start:start + int(settings.batch_size)]
            monitors = () if progress is None else (
                _decades(progress, sum(r is not None for r in results), len(chunk), len(orbits)),)
            for i, r in zip(chunk, _integrate_model(name, [orbits[i] for i in chunk], settings, gali_stop, wanted,
                                                        window, monitors, deviation_start)):
                results[i] = r
    unknown = sorted({o.model for o, r in zip(orbits, results) if r is None})
    require(not unknown, "model", unknown, f"one of {sorted(MODELS)}")
    return times, results


def _decades(progress, before: int, batch: int, total: int):
    """A ``driver.sample`` monitor calling ``progress(done, total)`` when the time passes a power
    of ten and at the last sample, ``done`` = ``before`` + ``batch`` times the fraction of steps made."""

    def monitor(samples, i: int) -> None:
        steps = samples.steps
        last = i == steps.size - 1
        previous, now = samples.times[i - 1] if i else 0.0, samples.times[i]
        if i > 0 and (last or previous <= 0 or math.floor(math.log10(now)) > math.floor(math.log10(previous))):
            progress(before + batch * (1.0 if last else float(steps[i]) / float(steps[-1])), total)

    return monitor


def _integrate_model(name: str, orbits: list[Orbit], settings: OrbitSettings, gali_stop, wanted,
                     window, monitors=(), deviation_start: str = "all") -> list[dict]:
    model = get_model(name)
    if model.is_split:  # its second conserved quantity, recorded and judged as the energy
        wanted = {**wanted, "norm_error": np.inf}
    problem = settings.problem(model, [o.chain for o in orbits], tangent=True, track_gaps=model.has_gaps,
                               spectrum=settings.spectrum, alignment=settings.alignment)
    N, B, K = problem.N, problem.lanes, problem.extra_vectors
    Q0, P0, DQ0, DP0 = (np.zeros((N, B)) for _ in range(4))
    XQ0, XP0 = np.zeros((K, N, B)), np.zeros((K, N, B))
    u0s, ok0 = np.full(B, np.nan), np.zeros(B, dtype=bool)
    for j, (o, c) in enumerate(zip(orbits, problem.chains)):
        try:
            u, p, amplitude = (o.excitation or Excitation(site=int(o.site))).state(model, c, float(o.energy))
            factor = lane_factor(o.lane, settings)
            Q0[:, j], P0[:, j], u0s[j] = u * factor, p * factor, amplitude * factor
            ok0[j] = True
        except ParameterError:
            pass
        DQ0[:, j], DP0[:, j] = initial_deviation(N, settings.deviation_seed + o.lane)
        XQ0[:, :, j], XP0[:, :, j] = settings.extra_deviations(problem, o.lane)
    if deviation_start == "excited" and window is None and ok0.any():  # (a window starts it so itself)
        DQ0, DP0 = restricted_deviation(DQ0, DP0, *Window.excited(Q0, P0, problem.geometry), geometry=problem.geometry)
    samples = driver.sample(problem, Q0, P0, DQ0, DP0, sample_schedule(settings), monitors, kind=settings.engine,
                            xq0=XQ0 if K else None, xp0=XP0 if K else None,
                            gali_stop=gali_stop if settings.alignment else None, window=window)

    out = []
    for j in range(B):
        run = samples.run(j)
        # a sample is measured where the initial state existed and the state is still finite
        measured = ok0[j] & np.all(np.isfinite(run.Q), axis=-1) & np.all(np.isfinite(run.P), axis=-1)
        series = _series(run, measured, {**wanted, **(ALIGNMENT_SERIES if settings.alignment else {}),
                                         **(SPECTRUM_SERIES if settings.spectrum else {})})
        out.append({
            **series,
            "u0": float(u0s[j]),
            "max_gaps": int(run.max_gaps.max()) if model.has_gaps else -1,
            "valid": bool(ok0[j] and samples.bad[j] < 0
                          and np.all(series["energy_error"] <= settings.max_energy_error)
                          and np.all(series.get("norm_error", 0.0) <= settings.max_energy_error)),
        })
    return out


def _series(run, measured: np.ndarray, wanted: dict) -> dict:
    """The ``wanted`` series (name -> fill, as :data:`SERIES`) of one lane's run, each with its fill
    value where ``measured`` is False."""
    out = {}
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for key, fill in wanted.items():
            values = REGISTRY[key].compute(run)
            out[key] = values if fill is None else np.where(measured, values, fill)
    return out
