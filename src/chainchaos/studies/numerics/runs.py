"""Single measured runs: a splitting scheme of the package, or one of scipy's solve_ivp methods.

Every run starts from the package's initial state (bead ``site`` displaced so that H = energy,
all momenta zero; :func:`chainchaos.system.initial.initial_state`) and, with ``tangent``, the package's
initial deviation vector (:func:`chainchaos.system.initial.initial_deviation`). It records

- the largest relative energy error |H(t) - H(0)| / H(0) (dimensionless) seen on the check grid,
- the phase-space state (u, p) at t_probe (units: docs/conventions.md#units),
- the finite-time mLCE Lambda(t_final) (units of omega_max, i.e. 1 / time unit),
- the wall-clock seconds of the integration (time.perf_counter; the best of ``repeats`` runs when
  one run is shorter than ``repeat_below`` seconds, so that short runs are not timer noise), and
  the process CPU seconds of the same run (time.process_time, less sensitive to other load).

Call :func:`chainchaos.run.warmup.warm_up` once per process before timing: the first call of a
Numba kernel with new argument types loads or compiles it.

Times are in units of 1/omega_max of the homogeneous linear chain (docs/conventions.md#units).
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy import integrate

from chainchaos.engine.checked import CheckedRun
from chainchaos.engine.problem import Problem, check_step
from chainchaos.engine.rhs import RightHandSide
from chainchaos.errors import require
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import get_model

IVP_METHODS = ("RK45", "DOP853")


@dataclass(kw_only=True)
class RunResult:
    """Outcome of one measured run (see the module docstring for quantities and units)."""

    method: str
    dt: float = math.nan
    rtol: float = math.nan
    seconds: float = math.nan
    cpu_seconds: float = math.nan
    n_steps: int = 0
    force_evaluations: int = 0
    max_energy_error: float = math.nan
    final_energy_error: float = math.nan
    lambda_final: float = math.nan
    state_probe: np.ndarray | None = None
    stable: bool = True
    t_stopped: float = math.nan
    max_open_gaps: int = 0
    open_fraction: float = 0.0
    bonds_ever_open: int = 0
    energy_errors: np.ndarray | None = field(default=None, repr=False)  # signed, per check


def grid_steps(t: float, dt: float, name: str) -> int:
    """The number of steps dt in the time t (the value of ``name``), which must be a multiple of dt."""
    n = int(round(t / dt))
    require(n >= 1 and abs(n * dt - t) <= 1e-9 * t, name, t, f"a multiple of dt = {dt:g}")
    return n


def _check_plan(n_steps: int, chunk: int) -> list[tuple[int, int]]:
    """(n_chunks, chunk_steps) pairs covering n_steps: full chunks, then the remainder."""
    plan = [(n_steps // chunk, chunk)]
    if n_steps % chunk:
        plan.append((1, n_steps % chunk))
    return [(n, c) for n, c in plan if n > 0]


def run_scheme(model, chain, energy: float, scheme: str, dt: float, t_final: float,
               t_probe: float | None = None, tangent: bool = True, check_interval: float = 0.1,
               repeats: int = 3, repeat_below: float = 0.5, stop_error: float = math.inf,
               excited_site: int = 21, deviation_seed: int = 0, track_gaps: bool = False,
               keep_errors: bool = False) -> RunResult:
    """Integrate with splitting scheme ``scheme`` (a name of chainchaos.engine.integrators.SCHEMES) at
    step ``dt`` to ``t_final`` and measure it (module docstring).

    The energy error is checked every ``check_interval`` time units (every step if dt is larger);
    a run whose energy error exceeds ``stop_error`` or whose state turns non-finite stops there
    and is reported with ``stable = False`` and ``t_stopped``. ``t_probe`` (a multiple of dt)
    is where the phase-space state is kept. With ``track_gaps`` (Hertz) the contact statistics
    of the run are recorded: largest number of simultaneously open bonds, fraction of bond-steps
    open, number of bonds that opened at least once (at step ends).
    """
    check_step(dt)
    n_total = grid_steps(t_final, dt, "t_final")
    n_probe = grid_steps(t_probe, dt, "t_probe") if t_probe is not None else n_total
    require(n_probe <= n_total, "t_probe", t_probe, f"<= t_final = {t_final}")
    chunk = max(1, int(round(check_interval / dt)))
    model = get_model(model)
    # a model whose bonds never open has no gaps to count: its statistics stay zero
    problem = Problem(model, [chain], integrator=scheme, dt=dt, tangent=tangent,
                      track_gaps=track_gaps and model.has_gaps, check_every=chunk)
    s = problem.scheme
    segments = [_check_plan(n_probe, chunk), _check_plan(n_total - n_probe, chunk)]
    n_checks = sum(n for seg in segments for n, _ in seg)

    q0, p0, _ = initial_state(model, chain, energy, excited_site)
    dq0, dp0 = initial_deviation(chain.N, deviation_seed) if tangent else (None, None)
    N = chain.N

    best = math.inf
    for attempt in range(max(1, repeats)):
        run = CheckedRun(problem, q0, p0, dq0, dp0)
        err = np.zeros(n_checks)
        probe, offset, stop_index, steps_done = None, 0, -1, 0
        start, cpu_start = time.perf_counter(), time.process_time()
        for si, seg in enumerate(segments):
            for n_chunks, c in seg:
                bad = run.advance(n_chunks, c, err, offset, stop_error)
                if bad >= 0:
                    stop_index = offset + bad
                    steps_done += (bad + 1) * c
                    break
                offset += n_chunks
                steps_done += n_chunks * c
            if stop_index >= 0:
                break
            if si == 0:
                probe = np.concatenate([run.q, run.p])
        elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu_start
        if elapsed < best:
            best, best_cpu = elapsed, cpu
        if elapsed >= repeat_below or stop_index >= 0:
            break

    stable = stop_index < 0
    signed = err if stable else err[:stop_index + 1]
    checked = np.abs(signed)
    result = RunResult(
        method=scheme, dt=float(dt), seconds=best, cpu_seconds=best_cpu, n_steps=int(steps_done),
        force_evaluations=int(steps_done * s.force_evaluations),
        max_energy_error=float(np.max(checked)) if checked.size else 0.0,
        final_energy_error=float(checked[-1]) if checked.size else 0.0,
        lambda_final=float(run.diagnostics[0] / t_final) if tangent and stable else math.nan,
        state_probe=probe, stable=stable, t_stopped=math.nan if stable else float(steps_done * dt),
        energy_errors=signed.copy() if keep_errors else None)
    if track_gaps:
        result.max_open_gaps = int(run.diagnostics[1])
        result.open_fraction = float(run.gap_steps.sum() / (max(steps_done, 1) * (N + 1)))
        result.bonds_ever_open = int(np.count_nonzero(run.gap_steps))
    return result


def run_solve_ivp(model, chain, energy: float, method: str, rtol: float, t_final: float,
                  t_probe: float | None = None, atol: float | None = None, tangent: bool = True,
                  repeats: int = 3, repeat_below: float = 0.5, excited_site: int = 21,
                  deviation_seed: int = 0) -> RunResult:
    """Integrate with scipy's ``method`` ("RK45" or "DOP853") at relative tolerance ``rtol``
    (absolute tolerance ``atol``, default rtol: the state is of order one in these units) on
    the compiled right-hand side :class:`RightHandSide` and measure it (module docstring).

    The solver is scipy.integrate's own stepper class, driven step by step exactly as
    ``solve_ivp`` drives it (solve_ivp is that loop plus storage); the energy error is taken at
    every accepted step. The run is split at t_probe so that the phase-space state there is a
    solver step, not an interpolant (the step-size controller restarts there). Lambda(t_final)
    is ln |v(t_final)| / t_final with |v(0)| = 1 (no renormalisation is needed to t = 1e3).
    """
    require(method in IVP_METHODS, "method", method, f"one of {IVP_METHODS}")
    require(np.isfinite(rtol) and rtol > 0, "rtol", rtol, "a tolerance > 0")
    atol = rtol if atol is None else atol
    q0, p0, _ = initial_state(model, chain, energy, excited_site)
    parts = [q0, p0]
    if tangent:
        parts += list(initial_deviation(chain.N, deviation_seed))
    y0 = np.concatenate(parts)
    fun = RightHandSide(model, chain, tangent)
    H0 = fun.energy(y0)
    solver_class = getattr(integrate, method)
    bounds = [t for t in ((t_probe,) if t_probe is not None else ()) if t < t_final] + [t_final]

    best, result = math.inf, None
    for attempt in range(max(1, repeats)):
        fun.nfev = 0
        y, t0, n_steps, max_err, probe, ok = y0.copy(), 0.0, 0, 0.0, None, True
        start, cpu_start = time.perf_counter(), time.process_time()
        for t_bound in bounds:
            solver = solver_class(fun, t0, y, t_bound, rtol=rtol, atol=atol)
            while solver.status == "running":
                solver.step()
                n_steps += 1
                e = abs(fun.energy(solver.y) - H0) / abs(H0)
                if not e <= max_err:
                    max_err = e if np.isfinite(e) else math.inf
            if solver.status != "finished":
                ok = False
                break
            t0, y = t_bound, solver.y.copy()
            if t_probe is not None and t_bound == t_probe:
                probe = y[:2 * chain.N].copy()
        elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu_start
        if elapsed < best:
            best, best_cpu = elapsed, cpu
        if result is None:
            v = np.linalg.norm(y[2 * chain.N:]) if tangent else math.nan
            result = RunResult(
                method=method, rtol=float(rtol), n_steps=n_steps, force_evaluations=fun.nfev,
                max_energy_error=max_err, final_energy_error=abs(fun.energy(y) - H0) / abs(H0),
                lambda_final=float(np.log(v) / t_final) if tangent and ok else math.nan,
                state_probe=probe if probe is not None else (y[:2 * chain.N].copy() if t_probe is None else None),
                stable=ok, t_stopped=math.nan if ok else float(t0))
        if elapsed >= repeat_below:
            break
    result.seconds, result.cpu_seconds = best, best_cpu
    return result


def phase_space_error(state, reference) -> float:
    """Relative phase-space error |x - x_ref| / |x_ref| of x = (u, p) (Euclidean norm over the
    2N components in the units of docs/conventions.md#units; dimensionless)."""
    if state is None:
        return math.nan
    return float(np.linalg.norm(state - reference) / np.linalg.norm(reference))
