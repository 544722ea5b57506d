"""Cost of k deviation vectors per orbit on the batch engine, against the orbit with its one
(mLCE) vector: µs of CPU per step and trajectory, for the Lyapunov spectrum (vectors
orthonormalised every ``check_every`` steps) and for GALI (vectors only normalised).

    python benchmarks/deviation_vectors.py [--steps 4000] [--vectors 1 2 4 8 16 80] [--repeats 3]

The orbits are those of ``benchmarks/batch_throughput.py`` (one SIMD block of single-site
excitations of the alpha = 5 chain of seed 879, N = 40, SRKN6b, dt = 5e-3, the Hertz gap count
on), timed with time.process_time after a warm-up call. Printed per model and k: the time per
step and trajectory, its ratio to k = 1, and the cost of each vector beyond the first as a
fraction of the k = 1 step (the goals: at most 0.5 per extra vector, at most 40x for the full
spectrum of 2N = 80). The first line names the machine.
"""

import argparse
import time

import numpy as np

from chainchaos import random_chain
from chainchaos.engine.problem import Problem
from chainchaos.kernels.simd import LANES
from chainchaos.records.provenance import machine_line
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import get_model


def seconds_per_step(name, chain, k, kind, steps, repeats, dt=5e-3, check_every=1000):
    """CPU seconds per step and trajectory of one block with k deviation vectors per orbit."""
    model = get_model(name)
    energies = np.geomspace(0.2, 5.0, LANES)
    q, p = (np.stack(a, 1) for a in zip(*[initial_state(model, chain, float(E), 21)[:2] for E in energies]))
    dq, dp = (np.tile(a[:, None], (1, LANES)) for a in initial_deviation(chain.N, 0))
    spectrum, gali = (k, 1) if kind == "spectrum" else (1, k)
    problem = Problem(model, [chain] * LANES, integrator="SRKN6b", dt=dt, tangent=True, track_gaps=model.has_gaps,
                      check_every=check_every, spectrum=spectrum, gali=gali)
    x = np.random.default_rng(1).uniform(-1, 1, (problem.extra_vectors, chain.N, LANES)) / np.sqrt(2 * chain.N)
    best = np.inf
    for r in range(repeats + 1):
        engine = problem.engine(q, p, dq, dp, "batch", x, x)
        t0 = time.process_time()
        engine.advance(10 if r == 0 else steps)
        if r > 0:
            best = min(best, time.process_time() - t0)
    return best / (steps * LANES)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", type=int, default=4000)
    ap.add_argument("--vectors", type=int, nargs="+", default=[1, 2, 4, 8, 16, 80])
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args(argv)
    chain = random_chain(879, 5.0, 40)
    print(machine_line())
    print(f"N = {chain.N}, SRKN6b, dt = 5e-3, one block of {LANES} orbits, {a.steps} steps")
    print("| model | vectors | kind | µs/step/traj | / k = 1 | per extra vector / (k = 1 step) |")
    print("|---|---:|---|---:|---:|---:|")
    for name in ("hertz", "fput"):
        one = seconds_per_step(name, chain, 1, "spectrum", a.steps, a.repeats)
        for k in sorted(a.vectors):
            for kind in ("spectrum", "gali") if k > 1 else ("spectrum",):
                s = one if k == 1 else seconds_per_step(name, chain, k, kind, a.steps, a.repeats)
                extra = (s / one - 1) / (k - 1) if k > 1 else float("nan")
                print(f"| {name} | {k} | {kind if k > 1 else 'mLCE only'} | {1e6 * s:.3f} | {s / one:.2f} | "
                      f"{extra:.2f} |")


if __name__ == "__main__":
    main()
