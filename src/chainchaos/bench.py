"""Speed of the stepping engine: nanoseconds per step of ``integrators.advance``.

The problem is the production one: a random alpha = 5 chain (seed 879) of N beads, one bead
(site N//2 + 1) excited to energy 1.8, the paper's dt = 5e-4, renormalisation every 1000 steps,
no gap bookkeeping. ``benchmarks/kernel_vs_c.py`` compares these figures with a C loop.
Threads: the engine is serial; run with NUMBA_NUM_THREADS=1 for a quiet machine.
"""

import time

import numpy as np

from chainchaos.chain import random_chain
from chainchaos.initial import initial_deviation, initial_state
from chainchaos.integrators import advance, get_scheme
from chainchaos.models import model_id

CHAIN_SEED = 879
ALPHA = 5.0
ENERGY = {"hertz": 1.8, "fput": 1.8}
DT = 5e-4
CHECK_EVERY = 1000


def benchmark_problem(model: str, N: int = 40) -> dict:
    """Arguments of ``advance`` (chain, initial state and deviation) for the benchmark problem."""
    mid = model_id(model)
    chain = random_chain(CHAIN_SEED, ALPHA, N)
    q, p, _ = initial_state(mid, chain, ENERGY[model], N // 2 + 1)
    dq, dp = initial_deviation(N, 0)
    return dict(model=mid, q=q, p=p, dq=dq, dp=dp, inv_mass=1.0 / chain.mass, A=chain.A,
                delta=chain.delta, K2=chain.K2, K3=chain.K3, K4=chain.K4)


def run_kernel(problem: dict, integrator: str, n_steps: int, tangent: bool, dt: float = DT,
               check_every: int = CHECK_EVERY) -> tuple[dict, float, float]:
    """Integrate a copy of ``problem`` for n_steps; returns (final state, log growth, seconds)."""
    scheme = get_scheme(integrator)
    s = {key: (v.copy() if isinstance(v, np.ndarray) else v) for key, v in problem.items()}
    N = s["q"].size
    f, k, g = np.empty(N + 1), np.empty(N + 1), np.empty(N + 1)
    diagnostics = np.zeros(2)
    gap_steps = np.zeros(N + 1, dtype=np.int64)
    start = time.perf_counter()
    bad = advance(s["model"], s["q"], s["p"], s["dq"], s["dp"], s["inv_mass"], s["A"], s["delta"],
                  s["K2"], s["K3"], s["K4"], scheme.kicks, scheme.drifts, dt, n_steps, tangent,
                  check_every, False, gap_steps, diagnostics, f, k, g)
    seconds = time.perf_counter() - start
    if bad >= 0:
        raise RuntimeError(f"benchmark state became non-finite after {bad} steps")
    return s, float(diagnostics[0]), seconds


def time_kernel(model: str, integrator: str, N: int = 40, n_steps: int = 200_000,
                tangent: bool = True, repeats: int = 5) -> float:
    """Best of ``repeats`` runs of n_steps, in nanoseconds per step (JIT warmed up first)."""
    problem = benchmark_problem(model, N)
    run_kernel(problem, integrator, 10, tangent)
    best = min(run_kernel(problem, integrator, n_steps, tangent)[2] for _ in range(repeats))
    return 1e9 * best / n_steps


def kernel_report(model: str, integrator: str, N: int = 40, n_steps: int = 200_000,
                  repeats: int = 5) -> dict:
    """ns per step of ``advance`` with and without tangent dynamics, and the run's settings."""
    return {
        "model": model, "integrator": integrator, "N": N, "n_steps": n_steps, "dt": DT,
        "ns_per_step_tangent": time_kernel(model, integrator, N, n_steps, True, repeats),
        "ns_per_step_no_tangent": time_kernel(model, integrator, N, n_steps, False, repeats),
    }
