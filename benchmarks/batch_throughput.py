"""Throughput of the batch engine (chainchaos.engine.batch) against the single-trajectory engine
(chainchaos.engine.integrators.advance) at N = 40: trajectories x steps per second, both models, with the
tangent map (the scan's configuration: SRKN6b, Hertz with gap counting).

    python benchmarks/batch_throughput.py [--steps 20000] [--lanes B ...] [--json out.json]

``--lanes`` defaults to one, two and eight SIMD blocks (``chainchaos.kernels.simd.LANES`` trajectories
each). The first line names the machine: CPU model, vector extensions, Numba's target, the width.

Both engines integrate the same trajectories: B single-site excitations of the alpha = 5 chain of
seed 879 at energies log-spaced from 0.2 to 5 (a state's tails can underflow to subnormal
numbers, whose arithmetic is slower, so the work must be the same). The single engine runs them
one after the other. Each measurement runs after a warm-up call (compilation or cache load
excluded) and is the best of ``--repeats`` timings of the process's CPU time (time.process_time:
the kernels are single-threaded, and CPU time is far less disturbed than wall time on a shared,
busy machine). The ratio printed is batch throughput / single throughput on the same B
trajectories; the single engine's row is its throughput on the largest B.

The last lines measure the square-root floor: either engine takes one square root per bond and
force evaluation, and a vectorised loop of independent hardware square roots gives the least time
they take on this CPU. They print each Hertz time per trajectory-step as a ratio to that floor,
and the bound it sets on the batch/single ratio.
"""

import argparse
import json
import time

import numba
import numpy as np

from chainchaos import random_chain
from chainchaos.engine.batch import Batch
from chainchaos.engine.integrators import advance, get_scheme
from chainchaos.engine.problem import Problem
from chainchaos.kernels.simd import LANES
from chainchaos.records.provenance import machine_line
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import get_model


def states(model, chain, B, site=21):
    energies = np.geomspace(0.2, 5.0, B)
    qs, ps = zip(*[initial_state(model, chain, float(E), site)[:2] for E in energies])
    dq, dp = initial_deviation(chain.N, 0)
    return np.stack(qs, 1), np.stack(ps, 1), np.tile(dq[:, None], (1, B)), np.tile(dp[:, None], (1, B))


def single_rate(name, chain, B, steps, dt, integrator, tangent, repeats):
    """Trajectories x steps per CPU second of ``integrators.advance`` over the B trajectories."""
    model = get_model(name)
    scheme = get_scheme(integrator)
    bonds = model.bond_parameters(chain)
    Q, P, DQ, DP = states(model, chain, B)
    N = chain.N
    best = np.inf
    for r in range(repeats + 1):
        n = 10 if r == 0 else steps
        elapsed = 0.0
        for j in range(B):
            q, p, dq, dp = Q[:, j].copy(), P[:, j].copy(), DQ[:, j].copy(), DP[:, j].copy()
            diag, gaps = np.zeros(2), np.zeros(N + 1, dtype=np.int64)
            f, k = np.empty(N + 1), np.empty(N + 1)
            t0 = time.process_time()
            advance(model, q, p, dq, dp, 1.0 / chain.mass, bonds, scheme.kicks, scheme.drifts, dt, n, tangent,
                    1000, model.has_gaps, gaps, diag, f, k)
            elapsed += time.process_time() - t0
        if r > 0:
            best = min(best, elapsed)
    return B * steps / best


@numba.njit(cache=True)
def _square_roots(x, y, repeats):
    for _ in range(repeats):
        for i in range(x.size):
            y[i] = np.sqrt(x[i])


def square_root_seconds(repeats=3, passes=50000):
    """CPU seconds per square root of a double in a vectorised loop of independent square roots."""
    x = np.linspace(1.0, 2.0, 512)
    y = np.empty_like(x)
    _square_roots(x, y, 1)
    best = np.inf
    for _ in range(repeats):
        t0 = time.process_time()
        _square_roots(x, y, passes)
        best = min(best, time.process_time() - t0)
    return best / (passes * x.size)


def batch_rate(name, chain, B, steps, dt, integrator, tangent, repeats):
    q, p, dq, dp = states(name, chain, B)
    best = np.inf
    for r in range(repeats + 1):
        problem = Problem(name, [chain] * B, integrator=integrator, dt=dt, tangent=tangent,
                          track_gaps=get_model(name).has_gaps, check_every=1000)
        b = Batch(problem, q, p, dq, dp)
        n = 10 if r == 0 else steps
        t0 = time.process_time()
        b.advance(n)
        if r > 0:
            best = min(best, time.process_time() - t0)
    return B * steps / best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--lanes", type=int, nargs="+", default=[LANES, 2 * LANES, 8 * LANES])
    ap.add_argument("--dt", type=float, default=5e-3)
    ap.add_argument("--integrator", default="SRKN6b")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--no-tangent", action="store_true")
    ap.add_argument("--json", help="also write the results here")
    a = ap.parse_args(argv)
    chain = random_chain(879, 5.0, 40)
    tangent = not a.no_tangent
    rows = []
    print(machine_line())
    print(f"N = {chain.N}, {a.integrator}, dt = {a.dt}, tangent = {tangent}, {a.steps} steps")
    print(f"{'model':6} {'engine':8} {'lanes':>5} {'traj*steps/s':>14} {'us/step/traj':>13} {'ratio':>6}")
    for name in ("hertz", "fput"):
        for B in sorted(a.lanes):
            single = single_rate(name, chain, B, a.steps, a.dt, a.integrator, tangent, a.repeats)
            rate = batch_rate(name, chain, B, a.steps, a.dt, a.integrator, tangent, a.repeats)
            print(f"{name:6} {'batch':8} {B:5d} {rate:14.4g} {1e6 / rate:13.3f} {rate / single:6.2f}")
            rows.append({"model": name, "engine": "batch", "lanes": B, "rate": rate, "ratio": rate / single,
                         "single_rate": single})
        print(f"{name:6} {'single':8} {1:5d} {single:14.4g} {1e6 / single:13.3f} {1.0:6.2f}")
    per_root = square_root_seconds()
    roots = (chain.N + 1) * get_scheme(a.integrator).force_evaluations
    floor = roots * per_root
    hertz_single = max((r for r in rows if r["model"] == "hertz"), key=lambda r: r["lanes"])["single_rate"]
    print(f"hertz square roots alone ({roots} per step and trajectory, {1e9 * per_root:.2f} ns each): "
          f"{1e6 * floor:.3f} us/step/traj, so batch/single <= {1 / (floor * hertz_single):.2f}")
    ratios = ", ".join(f"batch {r['lanes']} {1 / (r['rate'] * floor):.2f}" for r in rows if r["model"] == "hertz")
    print(f"hertz time per step and trajectory / square-root floor: {ratios}, single {1 / (hertz_single * floor):.2f}")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump({"machine": machine_line(), "N": chain.N, "integrator": a.integrator, "dt": a.dt, "tangent": tangent,
                       "steps": a.steps, "results": rows}, fh, indent=1)
    return rows


if __name__ == "__main__":
    main()
