"""Speed of the stepping engine: nanoseconds per step of ``integrators.advance``.

The problem is a production one: the random alpha = 5 chain of seed 879 with N beads, bead
N//2 + 1 excited to energy H = 1.8, the paper's dt = 5e-4, renormalisation every 1000 steps,
no gap bookkeeping. ``benchmarks/kernel_vs_c.py`` compares these figures with a hand-written C
loop of the same scheme. The engine is serial (one thread). Timings are the best of several
runs, so background load inflates them less; they are figures to print, not to assert on.
"""

import time

import numpy as np

from chainchaos.engine.integrators import advance, get_scheme
from chainchaos.errors import require
from chainchaos.system.chain import random_chain
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import get_model

CHAIN_SEED = 879
ALPHA = 5.0
ENERGY = 1.8
DT = 5e-4
CHECK_EVERY = 1000


def benchmark_problem(model: str, N: int = 40) -> dict:
    """Arguments of ``advance`` (chain, initial state and deviation) for the benchmark problem,
    and the chain's parameters by name (A, delta, K2, K3, K4) for the C loop."""
    chain = random_chain(CHAIN_SEED, ALPHA, N)
    law = get_model(model)
    q, p, _ = initial_state(law, chain, ENERGY, N // 2 + 1)
    dq, dp = initial_deviation(N, 0)
    return dict(model=law, q=q, p=p, dq=dq, dp=dp, inv_mass=1.0 / chain.mass, bonds=law.bond_parameters(chain),
                A=chain.A, delta=chain.delta, K2=chain.K2, K3=chain.K3, K4=chain.K4)


def run_kernel(problem: dict, integrator: str, n_steps: int, tangent: bool, dt: float = DT,
               check_every: int = CHECK_EVERY) -> tuple[dict, float, float]:
    """Integrate a copy of ``problem`` for n_steps with ``advance``.

    Returns (final state dict, log growth of the deviation vector, wall-clock seconds).
    """
    scheme = get_scheme(integrator)
    s = {key: (v.copy() if isinstance(v, np.ndarray) else v) for key, v in problem.items()}
    N = s["q"].size
    f, k = np.empty(N + 1), np.empty(N + 1)
    diagnostics = np.zeros(2)
    gap_steps = np.zeros(N + 1, dtype=np.int64)
    start = time.perf_counter()
    bad = advance(s["model"], s["q"], s["p"], s["dq"], s["dp"], s["inv_mass"], s["bonds"], scheme.kicks,
                  scheme.drifts, dt, n_steps, tangent, check_every, False, gap_steps, diagnostics, f, k)
    seconds = time.perf_counter() - start
    if bad >= 0:
        raise RuntimeError(f"benchmark state became non-finite after {bad} steps")
    return s, float(diagnostics[0]), seconds


def time_kernel(model: str, integrator: str, N: int = 40, n_steps: int = 10_000,
                tangent: bool = True, repeats: int = 5) -> float:
    """Nanoseconds per step of ``advance``: best of ``repeats`` runs of n_steps from the same
    initial state, after a short warm-up run (JIT compilation or cache load)."""
    require(isinstance(n_steps, int) and n_steps >= 1, "n_steps", n_steps, "an integer >= 1")
    require(isinstance(repeats, int) and repeats >= 1, "repeats", repeats, "an integer >= 1")
    problem = benchmark_problem(model, N)
    run_kernel(problem, integrator, 10, tangent)
    best = min(run_kernel(problem, integrator, n_steps, tangent)[2] for _ in range(repeats))
    return 1e9 * best / n_steps


def kernel_report(model: str, integrator: str, N: int = 40, n_steps: int = 10_000,
                  repeats: int = 5) -> dict:
    """Nanoseconds per step of ``advance`` with (``ns_per_step_tangent``) and without
    (``ns_per_step_no_tangent``) tangent dynamics, with the settings of the measurement."""
    return {
        "model": model, "integrator": integrator, "N": N, "n_steps": n_steps, "repeats": repeats,
        "dt": DT, "energy": ENERGY,
        "ns_per_step_tangent": time_kernel(model, integrator, N, n_steps, True, repeats),
        "ns_per_step_no_tangent": time_kernel(model, integrator, N, n_steps, False, repeats),
    }
