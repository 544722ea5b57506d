"""The integration driver: a problem's lanes advanced through a sampling schedule, with monitors.

:func:`sample` starts the engine of a :class:`~chainchaos.engine.problem.Problem` (the batch engine for
several lanes, the single-trajectory one for one) from given states, advances it from sample to
sample of a schedule of step indices, and records at every sample each lane's state and deviation
vector, ln|v| (renormalised in the engine every ``check_every`` steps), the gap counts of the
interval (reset at every sample) and the relative energy error. After every sample it calls its
monitors, ``monitor(samples, i)``: the energy guard of the scenes (:class:`EnergyGuard`), a
progress report (:func:`progress`). Scenes (``chainchaos.run.scenes``) and orbit sets
(``chainchaos.run.orbits``: scans, realization search, ensemble verdicts) are short loops on it; lane
j of the record, as a ``registry.SampledRun``, feeds the observable registry.
"""

import math
from dataclasses import dataclass

import numpy as np

from chainchaos.errors import SimulationError, require
from chainchaos.kernels import exactmath
from chainchaos.observe.formulas import log_volume, sali
from chainchaos.observe.registry import SampledRun
from chainchaos.system.models import open_bonds


def sample_steps(t_final: float, dt: float, per_decade: int, t_first: float) -> np.ndarray:
    """Step indices of the samples: 0, then log-spaced times from t_first to t_final with
    ``per_decade`` per decade, which include every power of ten, rounded to the step grid.

    The times are t_j = 10^(e_0 + j / per_decade) with e_0 = floor(log10(max(t_first, dt))), up
    to the first t_j >= t_final, from the C library's scalar log10 and pow (chainchaos.kernels.exactmath),
    not NumPy's vectorised ones, whose last bits depend on the CPU.

    Parameters
    ----------
    t_final : float
        The run's length (> 0), in the model's time unit.
    dt : float
        The time step (> 0), in the same unit.
    per_decade : int
        Samples per decade of time (>= 1).
    t_first : float
        Time of the first sample after 0 (raised to dt if smaller).

    Returns
    -------
    numpy.ndarray of int64
        The step indices, increasing and unique, from 0 to round(t_final / dt): sample i is at
        time ``steps[i] * dt``.
    """
    first = math.floor(math.log10(max(t_first, dt)))
    count = math.ceil((math.log10(t_final) - first) * per_decade) + 1
    exponents = first + np.arange(count) / per_decade
    steps = np.rint(exactmath.exp10(exponents) / dt).astype(np.int64)
    n_final = int(np.rint(t_final / dt))
    steps = np.unique(np.concatenate(([0], steps[(steps >= 1) & (steps < n_final)], [n_final])))
    return steps


@dataclass(kw_only=True)
class Samples:
    """The record of a problem's lanes on the sample steps, lane first: states (B, S, N), ln|v|,
    energy error and largest number of open gaps (B, S), gap counts (B, S, N+1); ``bad`` (B,) is
    the step at which a lane turned non-finite (-1: never), ``H0`` (B,) the initial energies.
    With the problem's several deviation vectors: ``extra_growth`` (B, S, spectrum - 1), the
    accumulated ln of the norms of the orthonormalised vectors beyond the mLCE vector (with
    ``log_growth``, the ``spectrum_growth``), and ``log_gali`` and ``sali`` (B, S) of the mLCE
    vector with the GALI vectors (NaN without).

    Made by :func:`sample`; lane j as the observable registry reads it is ``run(j)``. B is the
    number of lanes, S of samples, N of sites; units of docs/conventions.md#units.

    Parameters
    ----------
    problem : Problem
        The problem the lanes ran.
    steps : numpy.ndarray of shape (S,)
        The sample steps (sample time = step dt).
    Q, P : numpy.ndarray of shape (B, S, N)
        Displacements and momenta at every sample.
    DQ, DP : numpy.ndarray of shape (B, S, N)
        The mLCE deviation vector at every sample (unit norm after each renormalisation).
    log_growth : numpy.ndarray of shape (B, S)
        ln(|v(t)| / |v(0)|) of the mLCE vector (dimensionless).
    gap_steps : numpy.ndarray of shape (B, S, N + 1), dtype int
        Steps each bond was open since the previous sample.
    max_gaps : numpy.ndarray of shape (B, S), dtype int
        Largest number of simultaneously open bonds since the previous sample.
    energy_error : numpy.ndarray of shape (B, S)
        Relative energy error abs(H(t) - H0) / abs(H0) (dimensionless).
    H0 : numpy.ndarray of shape (B,)
        Initial total energies, in the model's energy unit.
    bad : numpy.ndarray of shape (B,), dtype int
        The step at which a lane's state turned non-finite (-1: never).
    extra_growth : numpy.ndarray of shape (B, S, spectrum - 1)
        Accumulated ln of the norms of the spectrum's vectors beyond the mLCE vector.
    log_gali, sali : numpy.ndarray of shape (B, S)
        ln GALI_k and SALI of the mLCE vector with the GALI vectors (NaN without them).
    norm_error : numpy.ndarray of shape (B, S) or None
        Relative norm error abs(S(t) - S0) / S0 of a split model (DNLS), None for a bond model.
    """

    problem: object
    steps: np.ndarray
    Q: np.ndarray
    P: np.ndarray
    DQ: np.ndarray
    DP: np.ndarray
    log_growth: np.ndarray
    gap_steps: np.ndarray
    max_gaps: np.ndarray
    energy_error: np.ndarray
    H0: np.ndarray
    bad: np.ndarray
    extra_growth: np.ndarray
    log_gali: np.ndarray
    sali: np.ndarray
    norm_error: np.ndarray | None = None

    @property
    def times(self) -> np.ndarray:
        """(S,) sample times ``steps * dt``, in the model's time unit."""
        return self.steps * self.problem.dt

    @property
    def spectrum_growth(self) -> np.ndarray:
        """(B, S, spectrum): the accumulated ln of the norms of the spectrum's vectors, the mLCE
        vector's first."""
        return np.concatenate([self.log_growth[:, :, None], self.extra_growth], axis=2)

    def run(self, j: int, deviation0=None) -> SampledRun:
        """Lane j as the sampled run the observable registry reads.

        Parameters
        ----------
        j : int
            The lane, 0-based.
        deviation0 : numpy.ndarray of shape (2 N,), optional
            The lane's initial deviation vector (du, dp), recorded by the ``initial_deviation``
            observable.

        Returns
        -------
        chainchaos.observe.registry.SampledRun
            Lane j's samples and its lattice, on the sample times.
        """
        return SampledRun(self.problem.model, self.problem.chains[j], self.times, self.steps, self.Q[j], self.P[j],
                          self.DQ[j], self.DP[j], self.log_growth[j], self.gap_steps[j], self.max_gaps[j],
                          self.energy_error[j], deviation0,
                          np.column_stack([self.log_growth[j], self.extra_growth[j]]), self.log_gali[j], self.sali[j],
                          self.problem.gali, None if self.norm_error is None else self.norm_error[j])


def _alignment(engine, samples: Samples, i: int, lanes) -> None:
    """ln GALI_k and SALI of the mLCE vector and GALI vectors (unit vectors after every call of the
    engine) of ``lanes`` at sample i."""
    first = engine.problem.spectrum - 1
    for j in lanes:
        W = np.concatenate([np.concatenate([engine.dq[:, j], engine.dp[:, j]])[None, :],
                            np.concatenate([engine.xq[first:, :, j], engine.xp[first:, :, j]], axis=1)])
        samples.log_gali[j, i] = log_volume(W)
        samples.sali[j, i] = sali(W[0], W[1])


def sample(problem, q0, p0, dq0, dp0, steps, monitors=(), kind: str = "auto", xq0=None, xp0=None,
           gali_stop: float | None = None, window=None) -> Samples:
    """Integrate the lanes of ``problem`` and record them at the step indices ``steps``.

    Parameters
    ----------
    problem : Problem
        The model, one lattice per lane (B lanes of N sites), the scheme and step.
    q0, p0 : numpy.ndarray of shape (N, B)
        Initial displacements and momenta, one column per lane.
    dq0, dp0 : numpy.ndarray of shape (N, B)
        Initial deviation vector of each lane (ignored without the problem's tangent map).
    steps : array_like of int
        Step indices of the samples, increasing from 0 (``RunSettings.sample_steps``).
    monitors : sequence of callable, optional
        Each called as ``monitor(samples, i)`` after sample i (``EnergyGuard``, ``progress``).
    kind : {"auto", "batch", "single"}, optional
        The engine (``Problem.engine``): the SIMD batch engine, the single-trajectory one lane by
        lane, or the one that costs less (default).
    xq0, xp0 : numpy.ndarray of shape (K, N, B), optional
        The problem's extra deviation vectors (``Problem.extra_vectors``: the spectrum's, then
        GALI's), unit vectors.
    gali_stop : float, optional
        A lane whose ln GALI_k falls below this value at a sample is decided (chaotic by GALI_k):
        its GALI vectors stop there (``Batch.stop_vectors``; the work is saved once a whole SIMD
        block has stopped) and its later ln GALI_k and SALI are NaN. The orbit, its mLCE vector
        and every lane's record up to its crossing are the same as without the stop.
    window : Window, optional
        Integrate only the sites the packets have reached (``run.window.WindowedEngine``; the
        deviation vectors start inside the first window).

    Returns
    -------
    Samples
        The lanes' states, ln|v|, energy errors and gap counts at every sample, lane first.

    Raises
    ------
    ParameterError
        For ``gali_stop`` without GALI vectors, or with a spectrum's.
    SimulationError
        From a monitor (``EnergyGuard``) that stops the run.

    Examples
    --------
    >>> import numpy as np
    >>> from chainchaos import Problem, random_chain, sample
    >>> problem = Problem("fput", [random_chain(1, 5.0, 16), random_chain(2, 5.0, 16)], dt=0.01)
    >>> q0 = np.zeros((16, 2)); q0[7] = 0.1            # bead 8 displaced in both lanes
    >>> p0, dq0 = np.zeros((16, 2)), np.full((16, 2), 0.25)
    >>> record = sample(problem, q0, p0, dq0, p0, steps=[0, 100, 1000])
    >>> record.times.tolist(), bool(record.energy_error.max() < 1e-8)
    ([0.0, 1.0, 10.0], True)
    """
    if window is None:
        engine = problem.engine(q0, p0, dq0, dp0, kind, xq0, xp0)
    else:
        from chainchaos.run.window import WindowedEngine

        engine = WindowedEngine(problem, window, q0, p0, dq0, dp0, kind)
    N, B, S = problem.N, problem.lanes, len(steps)
    Q, P, DQ, DP = (np.empty((B, S, N)) for _ in range(4))
    samples = Samples(problem=problem, steps=np.asarray(steps), Q=Q, P=P, DQ=DQ, DP=DP, log_growth=np.zeros((B, S)),
                      gap_steps=np.zeros((B, S, N + 1), dtype=np.int64),
                      max_gaps=np.zeros((B, S), dtype=np.int64), energy_error=np.zeros((B, S)),
                      H0=np.zeros(B), bad=engine.bad, extra_growth=np.zeros((B, S, problem.spectrum - 1)),
                      log_gali=np.full((B, S), np.nan), sali=np.full((B, S), np.nan),
                      norm_error=np.zeros((B, S)) if problem.model.is_split else None)
    Q[:, 0], P[:, 0], DQ[:, 0], DP[:, 0] = engine.q.T, engine.p.T, engine.dq.T, engine.dp.T
    aligning = np.full(B, problem.gali > 1)
    if gali_stop is not None:
        require(problem.gali > 1 and problem.spectrum == 1, "gali_stop", gali_stop,
                "None without GALI vectors, or with a spectrum's")

    def alignment(i):
        if aligning.any():
            _alignment(engine, samples, i, np.flatnonzero(aligning))
            if gali_stop is not None:
                decided = aligning & (samples.log_gali[:, i] < gali_stop)
                engine.stop_vectors(np.flatnonzero(decided))
                aligning[decided] = False

    alignment(0)
    samples.H0[:] = problem.energies(Q[:, 0], P[:, 0])
    S0 = problem.norms(Q[:, 0], P[:, 0]) if problem.model.is_split else None
    if problem.track_gaps:
        samples.max_gaps[:, 0] = [open_bonds(problem.model, c, Q[j, 0]).sum() for j, c in enumerate(problem.chains)]
    for monitor in monitors:
        monitor(samples, 0)
    for i in range(1, S):
        engine.new_interval()
        engine.advance(int(steps[i] - steps[i - 1]))
        Q[:, i], P[:, i], DQ[:, i], DP[:, i] = engine.q.T, engine.p.T, engine.dq.T, engine.dp.T
        samples.log_growth[:, i] = engine.log_growth
        samples.extra_growth[:, i] = engine.x_growth[:problem.spectrum - 1].T
        alignment(i)
        samples.gap_steps[:, i] = engine.gap_steps.T
        samples.max_gaps[:, i] = engine.max_gaps
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            samples.energy_error[:, i] = np.abs(problem.energies(Q[:, i], P[:, i]) - samples.H0) / np.abs(samples.H0)
            if S0 is not None:
                samples.norm_error[:, i] = np.abs(problem.norms(Q[:, i], P[:, i]) - S0) / S0
        for monitor in monitors:
            monitor(samples, i)
    return samples


class EnergyGuard:
    """A monitor that stops the run with SimulationError, naming the lane, at a non-finite state or
    at a relative energy error above the lane's limit, or a relative norm error above it for a
    split model (docs/conventions.md#guards).

    Called as ``guard(samples, i)`` after sample i (a monitor of :func:`sample`).

    Parameters
    ----------
    names : sequence of str
        Each lane's name (a scene's or orbit's), which the error names.
    limits : sequence of float
        Each lane's bound on the relative energy error (dimensionless).

    Raises
    ------
    SimulationError
        When called on a sample at which a lane has turned non-finite or exceeds its bound.
    """

    def __init__(self, names, limits):
        self.names, self.limits = list(names), list(limits)

    def __call__(self, samples: Samples, i: int) -> None:
        for j, name in enumerate(self.names):
            if samples.bad[j] >= 0:
                raise SimulationError(name, samples.bad[j] * samples.problem.dt,
                                      "non-finite state (the orbit escaped to infinity or the step is unstable)",
                                      float("nan"))
        for j, (name, limit) in enumerate(zip(self.names, self.limits)):
            if not samples.energy_error[j, i] <= limit:
                raise SimulationError(name, samples.times[i], "relative energy error", samples.energy_error[j, i],
                                      f"{limit:g}")
            if samples.norm_error is not None and not samples.norm_error[j, i] <= limit:
                raise SimulationError(name, samples.times[i], "relative norm error", samples.norm_error[j, i],
                                      f"{limit:g}")


def progress(report):
    """A monitor that calls ``report(t, fraction done)`` after every sample but the first.

    Parameters
    ----------
    report : callable
        Called as ``report(t, fraction)``: the sample time (the model's time unit) and the
        fraction of the steps done, from 0 to 1.

    Returns
    -------
    callable
        The monitor, ``monitor(samples, i)``, for :func:`sample`.
    """

    def monitor(samples: Samples, i: int) -> None:
        if i > 0:
            report(samples.times[i], samples.steps[i] / samples.steps[-1])

    return monitor
