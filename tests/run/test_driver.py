"""The integration driver on its own: the sampling schedule, the monitors, the record and the
choice of engine (chainchaos.run.driver, chainchaos.engine.problem)."""

import io
import math

import numpy as np
import pytest

from chainchaos.engine.batch import SERIAL_REMAINDER
from chainchaos.engine.problem import Problem
from chainchaos.errors import ParameterError, SimulationError
from chainchaos.kernels.simd import LANES
from chainchaos.run import driver
from chainchaos.run.progress import OrbitProgress, ProgressReporter
from chainchaos.system.chain import random_chain
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import get_model, total_energy


@pytest.mark.parametrize("t_final, dt, per_decade, t_first", [(1e3, 0.01, 10, 0.1), (1e5, 5e-4, 40, 0.1),
                                                             (250.0, 0.05, 3, 1.0), (7.0, 0.1, 2, 0.5)])
def test_the_schedule_is_log_spaced_on_the_step_grid(t_final, dt, per_decade, t_first):
    steps = driver.sample_steps(t_final, dt, per_decade, t_first)
    assert steps[0] == 0 and steps[-1] == round(t_final / dt) and np.all(np.diff(steps) > 0)
    t = steps * dt
    first = math.floor(math.log10(max(t_first, dt)))
    for k in range(first, math.floor(math.log10(t_final)) + 1):  # every power of ten within the run
        if 10.0**k < t_final:
            assert np.any(np.isclose(t, 10.0**k, rtol=1e-12)), k
    inner = t[(t >= 10.0**first) & (t < t_final)]
    ratios = inner[1:] / inner[:-1]  # log-spaced: each sample per_decade-th of a decade after the last
    assert np.allclose(ratios, 10.0 ** (1.0 / per_decade), rtol=dt / inner[0] + 1e-9)


def _problem(model="hertz", lanes=3, tangent=True, track_gaps=None, dt=0.01, check_every=7):
    chain = random_chain(879, 5.0)
    model = get_model(model)
    track_gaps = model.has_gaps if track_gaps is None else track_gaps
    problem = Problem(model, [chain] * lanes, integrator="SRKN6b", dt=dt, tangent=tangent, track_gaps=track_gaps,
                      check_every=check_every)
    N = chain.N
    q0, p0, dq0, dp0 = (np.zeros((N, lanes)) for _ in range(4))
    for j, energy in enumerate((0.5, 1.8, 3.0, 0.25, 1.0)[:lanes]):
        q0[:, j], p0[:, j], _ = initial_state(model, chain, energy, 21)
        dq0[:, j], dp0[:, j] = initial_deviation(N, j)
    return problem, (q0, p0, dq0, dp0)


def test_monitors_see_every_sample_in_order():
    problem, state = _problem()
    steps = driver.sample_steps(20.0, problem.dt, 5, 1.0)
    seen = []
    samples = driver.sample(problem, *state, steps, [lambda s, i: seen.append((i, s.steps[i]))])
    assert seen == [(i, steps[i]) for i in range(len(steps))]
    assert samples.Q.shape == (problem.lanes, len(steps), problem.N)


def test_the_record_starts_from_the_initial_state_and_measures_the_energy():
    problem, state = _problem()
    samples = driver.sample(problem, *state, driver.sample_steps(50.0, problem.dt, 5, 1.0))
    q0, p0, dq0, dp0 = state
    assert np.array_equal(samples.Q[:, 0], q0.T) and np.array_equal(samples.DP[:, 0], dp0.T)
    chain = problem.chains[0]
    for j in range(problem.lanes):
        assert samples.H0[j] == pytest.approx(float(total_energy(problem.model, chain, q0[:, j], p0[:, j])), rel=1e-14)
        end = float(total_energy(problem.model, chain, samples.Q[j, -1], samples.P[j, -1]))
        assert samples.energy_error[j, -1] == pytest.approx(abs(end - samples.H0[j]) / samples.H0[j], rel=1e-9)
        assert samples.energy_error[j, 0] == 0 and samples.energy_error[j].max() < 1e-6  # SRKN6b at dt = 0.01
    assert np.all(samples.bad == -1)


def test_gap_counts_are_per_interval():
    problem, state = _problem()
    steps = driver.sample_steps(50.0, problem.dt, 5, 1.0)
    samples = driver.sample(problem, *state, steps)
    interval = np.diff(steps)
    assert np.all(samples.gap_steps[:, 1:] <= interval[None, :, None])  # reset at every sample
    assert samples.gap_steps[:, 1:].sum() > 0 and np.all(samples.gap_steps[:, 0] == 0)
    assert np.all(samples.max_gaps <= problem.N + 1)


def test_the_energy_guard_names_the_lane_that_breaks_its_limit():
    problem, state = _problem(lanes=2)
    guard = driver.EnergyGuard(["low", "tight"], [1e-2, 1e-14])
    with pytest.raises(SimulationError, match="tight"):
        driver.sample(problem, *state, driver.sample_steps(10.0, problem.dt, 5, 1.0), [guard])


def test_the_energy_guard_stops_a_non_finite_state():
    problem, (q0, p0, dq0, dp0) = _problem(lanes=1, tangent=False)
    p0[20, 0] = np.inf  # an escaped orbit
    guard = driver.EnergyGuard(["escaped"], [1e300])
    with pytest.raises(SimulationError, match="escaped.*non-finite"):
        driver.sample(problem, q0, p0, dq0, dp0, driver.sample_steps(10.0, problem.dt, 5, 1.0), [guard])


def test_progress_reports_time_and_fraction():
    problem, state = _problem(lanes=1)
    steps = driver.sample_steps(10.0, problem.dt, 4, 1.0)
    calls = []
    driver.sample(problem, *state, steps, [driver.progress(lambda t, f: calls.append((t, f)))])
    assert [t for t, _ in calls] == pytest.approx(list(steps[1:] * problem.dt))
    assert calls[-1][1] == 1.0 and all(0 < f <= 1 for _, f in calls)


def test_the_progress_reporter_prints_at_most_every_interval_and_always_the_end():
    out = io.StringIO()
    report = ProgressReporter("run", 100.0, every=1e9, stream=out)
    report(50.0, 0.5)
    assert out.getvalue() == ""
    report(100.0, 1.0)
    assert "[run] t = 100 / 100 (100.0%)" in out.getvalue()


def test_an_ensemble_s_progress_counts_orbits_in_the_same_format():
    out = io.StringIO()
    report = OrbitProgress("study s group 1 of 3", every=0.0, stream=out)
    report(0.0024, 24)
    report(24.0, 24)
    first, last = out.getvalue().splitlines()
    assert first.startswith("[study s group 1 of 3] 0.0 of 24 orbits (  0.0%), elapsed ")
    assert last.startswith("[study s group 1 of 3] 24.0 of 24 orbits (100.0%), elapsed ") and "left ~0.0 s" in last


@pytest.mark.parametrize("lanes", [1, LANES - 1, LANES, LANES + 1, LANES + SERIAL_REMAINDER + 1])
def test_every_engine_kind_gives_the_same_numbers(lanes):
    """The engine choice changes where lanes run, never a number (bit for bit, by design)."""
    problem = Problem("hertz", [random_chain(879 + j, 5.0) for j in range(lanes)], integrator="SRKN6b", dt=0.02,
                      tangent=True, track_gaps=True, check_every=7)
    q0 = np.zeros((problem.N, lanes))
    q0[20] = np.linspace(0.05, 0.3, lanes)
    dq0 = np.ones((problem.N, lanes)) / np.sqrt(problem.N)
    steps = driver.sample_steps(5.0, problem.dt, 3, 1.0)
    records = {kind: driver.sample(problem, q0, np.zeros_like(q0), dq0, np.zeros_like(q0), steps, kind=kind)
               for kind in ("auto", "batch", "single")}
    for kind in ("batch", "single"):
        for key in ("Q", "P", "DQ", "DP", "log_growth", "gap_steps", "max_gaps", "energy_error"):
            assert np.array_equal(getattr(records[kind], key), getattr(records["auto"], key)), (kind, key)


@pytest.mark.parametrize("lanes", [1, LANES, LANES + 1, 2 * LANES + SERIAL_REMAINDER + 1])
def test_the_engine_kind_decides_which_lanes_run_serially(lanes):
    problem = Problem("fput", [random_chain(879, 5.0)] * lanes, dt=0.01)
    q = np.zeros((problem.N, lanes))
    serial = {kind: lanes - problem.engine(q, q, q, q, kind).block_lanes for kind in ("batch", "single", "auto")}
    remainder = lanes % LANES
    assert serial["batch"] == 0 and serial["single"] == lanes
    assert serial["auto"] == (remainder if remainder <= SERIAL_REMAINDER else 0)


def test_an_unknown_engine_kind_is_refused_by_name():
    problem, state = _problem(lanes=1)
    with pytest.raises(ParameterError, match="engine.*'gpu'.*auto"):
        driver.sample(problem, *state, [0, 1], kind="gpu")


def test_the_energy_guard_stops_a_split_model_at_its_norm_error():
    """The norm of a split model is guarded by the energy's rule: the lane named, the bound given."""
    from types import SimpleNamespace

    from chainchaos.errors import SimulationError
    from chainchaos.run.driver import EnergyGuard

    samples = SimpleNamespace(bad=np.array([-1]), times=np.array([0.0, 5.0]), energy_error=np.array([[0.0, 1e-9]]),
                              norm_error=np.array([[0.0, 2e-3]]), problem=SimpleNamespace(dt=0.1))
    EnergyGuard(["dnls_S1"], [1e-2])(samples, 1)
    with pytest.raises(SimulationError, match="relative norm error"):
        EnergyGuard(["dnls_S1"], [1e-3])(samples, 1)
