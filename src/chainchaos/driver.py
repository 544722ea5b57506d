"""The integration driver: a problem's lanes advanced through a sampling schedule, with monitors.

:func:`sample` starts the engine of a :class:`~chainchaos.problem.Problem` (the batch engine for
several lanes, the single-trajectory one for one) from given states, advances it from sample to
sample of a schedule of step indices, and records at every sample each lane's state and deviation
vector, ln|v| (renormalised in the engine every ``check_every`` steps), the gap counts of the
interval (reset at every sample) and the relative energy error. After every sample it calls its
monitors, ``monitor(samples, i)``: the energy guard of the scenes (:class:`EnergyGuard`), a
progress report (:func:`progress`). Scenes (``chainchaos.simulate``) and orbit sets
(``chainchaos.orbits``: scans, realization search, ensemble verdicts) are short loops on it; lane
j of the record, as a ``scene_observables.SampledRun``, feeds the observable registry.
"""

import os
from dataclasses import dataclass

import numpy as np

from chainchaos.errors import SimulationError
from chainchaos.models import get_model, open_bonds
from chainchaos.problem import Problem
from chainchaos.scene_observables import SampledRun


@dataclass
class Samples:
    """The record of a problem's lanes on the sample steps, lane first: states (B, S, N), ln|v|,
    energy error and largest number of open gaps (B, S), gap counts (B, S, N+1); ``bad`` (B,) is
    the step at which a lane turned non-finite (-1: never), ``H0`` (B,) the initial energies."""

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

    @property
    def times(self) -> np.ndarray:
        return self.steps * self.problem.dt

    def run(self, j: int, deviation0=None) -> SampledRun:
        """Lane j as the sampled run the observable registry reads."""
        return SampledRun(self.problem.model, self.problem.chains[j], self.times, self.steps, self.Q[j], self.P[j],
                          self.DQ[j], self.DP[j], self.log_growth[j], self.gap_steps[j], self.max_gaps[j],
                          self.energy_error[j], deviation0)


def sample(problem, q0, p0, dq0, dp0, steps, monitors=(), kind: str = "auto") -> Samples:
    """Integrate the lanes of ``problem`` from q0, p0, dq0, dp0 ((N, B) each) on the engine of
    ``kind`` (``Problem.engine``) and record them at the step indices ``steps`` (increasing, from
    0); call every monitor after every sample."""
    engine = problem.engine(q0, p0, dq0, dp0, kind)
    N, B, S = problem.N, problem.lanes, len(steps)
    Q, P, DQ, DP = (np.empty((B, S, N)) for _ in range(4))
    samples = Samples(problem, np.asarray(steps), Q, P, DQ, DP, np.zeros((B, S)),
                      np.zeros((B, S, N + 1), dtype=np.int64), np.zeros((B, S), dtype=np.int64), np.zeros((B, S)),
                      np.zeros(B), engine.bad)
    Q[:, 0], P[:, 0], DQ[:, 0], DP[:, 0] = engine.q.T, engine.p.T, engine.dq.T, engine.dp.T
    samples.H0[:] = problem.energies(Q[:, 0], P[:, 0])
    if problem.track_gaps:
        samples.max_gaps[:, 0] = [open_bonds(problem.model, c, Q[j, 0]).sum() for j, c in enumerate(problem.chains)]
    for monitor in monitors:
        monitor(samples, 0)
    for i in range(1, S):
        engine.gap_steps[:] = 0
        engine.max_gaps[:] = 0
        engine.advance(int(steps[i] - steps[i - 1]))
        Q[:, i], P[:, i], DQ[:, i], DP[:, i] = engine.q.T, engine.p.T, engine.dq.T, engine.dp.T
        samples.log_growth[:, i] = engine.log_growth
        samples.gap_steps[:, i] = engine.gap_steps.T
        samples.max_gaps[:, i] = engine.max_gaps
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            samples.energy_error[:, i] = np.abs(problem.energies(Q[:, i], P[:, i]) - samples.H0) / np.abs(samples.H0)
        for monitor in monitors:
            monitor(samples, i)
    return samples


class EnergyGuard:
    """A monitor that stops the run with SimulationError, naming the lane, at a non-finite state or
    at a relative energy error above the lane's limit (docs/conventions.md#guards)."""

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


def progress(report):
    """A monitor that calls ``report(t, fraction done)`` after every sample but the first."""

    def monitor(samples: Samples, i: int) -> None:
        if i > 0:
            report(samples.times[i], samples.steps[i] / samples.steps[-1])

    return monitor


def warm_up(models=None) -> str:
    """Compile (or load from the on-disk cache) every kernel a sampled run of ``models`` (default:
    the models of the paper's scenes) uses: both engines, with and without the tangent map, with
    gap counting where bonds open, the energy and gap kernels of the record, and those of every
    observable the model has (modes, logarithms). Returns the cache directory. A model not warmed
    up here compiles in the first job that runs it."""
    from chainchaos import paper
    from chainchaos.chain import random_chain
    from chainchaos.scene_observables import variables
    from chainchaos.simulate import model_observables, sample_steps

    chain = random_chain(0, 2.0, 4)
    q, p, dq, dp = np.zeros((4, 2)), np.zeros((4, 2)), np.zeros((4, 2)), np.full((4, 2), 0.5)
    q[1] = 0.1
    for model in map(get_model, paper.models() if models is None else models):
        for track_gaps in sorted({False, model.has_gaps}):
            for tangent in (True, False):
                for kind in ("single", "batch"):
                    problem = Problem(model, [chain] * 2, dt=0.1, tangent=tangent, track_gaps=track_gaps,
                                      check_every=3)
                    samples = sample(problem, q, p, dq, dp, sample_steps(0.4, 0.1, 2, 0.1), kind=kind)
                    if tangent and track_gaps == model.has_gaps and kind == "batch":
                        variables(samples.run(0, np.concatenate([dq[:, 0], dp[:, 0]])), model_observables(model.name))
    return os.environ.get("NUMBA_CACHE_DIR", "")
