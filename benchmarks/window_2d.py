"""The growing window on the square lattices: the cost of a run follows its packet, not its lattice.

    python benchmarks/window_2d.py [--model dnls] [--L 101 201 401] [--steps 1000] [--lanes 1] [--repeats 1]
    python benchmarks/record.py window_2d -- [the same options]

A line naming the machine, then one table: the disordered lattice of L x L sites (one
realization per lane) with a block of 3 x 3 sites at its centre, integrated with the tangent map
for ``--steps`` steps: ``--model dnls``, ``dnls_lattice(seed, W = 10, (L, L), beta = 1)`` at norm
4.5 by s9ABC6 at dt = 0.05; ``--model kg``, ``kg_lattice(seed, W = 10, (L, L))`` at energy 0.4
(displacements) by ABA864 at dt = 0.1; on the growing window (``run.window``, its default rule)
and on the whole lattice: CPU seconds (best of ``--repeats``, time.process_time, compilation excluded), the
window's final size, and the largest difference of the two final states. At a fixed packet the
windowed cost stays the same as L grows while the whole lattice's grows as L^2.
"""

import argparse
import sys
import time

import numpy as np

from chainchaos.engine.problem import Problem
from chainchaos.records.provenance import machine_line
from chainchaos.run.window import Window, WindowedEngine, restricted_deviation
from chainchaos.system.chain import dnls_lattice, kg_lattice
from chainchaos.system.initial import Excitation

W, WIDTH = 10.0, 3
#: Per model: its lattice, the block's norm or energy, the scheme and the time step.
MODELS = {"dnls": (lambda seed, L: dnls_lattice(seed, W, (L, L), 1.0), 4.5, "s9ABC6", 0.05),
          "kg": (lambda seed, L: kg_lattice(seed, W, (L, L)), 0.4, "ABA864", 0.1)}
TITLE = "Growing window on the square {model} lattice: CPU time against the lattice's size at a fixed packet"


def states(model: str, L: int, lanes: int):
    """The lanes' lattices and their block states (q, p, dq, dp), each (L^2, lanes)."""
    make, amount, _, _ = MODELS[model]
    lattices = [make(seed, L) for seed in range(lanes)]
    centre = (L + 1) // 2
    q, p, _ = Excitation(kind="block", site=(centre, centre), width=WIDTH).state(model, lattices[0], amount)
    rng = np.random.default_rng(0)
    dq, dp = rng.normal(size=(L * L, lanes)), rng.normal(size=(L * L, lanes))
    q, p = np.tile(q[:, None], (1, lanes)), np.tile(p[:, None], (1, lanes))
    dq, dp = restricted_deviation(dq, dp, *Window.excited(q, p, lattices[0].geometry), geometry=lattices[0].geometry)
    return lattices, (q, p, dq, dp)


def timed(make, steps: int, repeats: int):
    make().advance(2)  # compilation or the cache's load
    best, engine = np.inf, None
    for _ in range(repeats):
        engine = make()
        t0 = time.process_time()
        engine.advance(steps)
        best = min(best, time.process_time() - t0)
    return best, engine


def parse(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--model", choices=sorted(MODELS), default="dnls")
    parser.add_argument("--L", type=int, nargs="+", default=[101, 201, 401])
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--lanes", type=int, default=1)
    parser.add_argument("--repeats", type=int, default=1)
    return parser.parse_args(argv)


def main(argv=None) -> dict:
    """Print the table; return ``record.py``'s part of a record."""
    args = parse(argv)
    print(machine_line())
    _, amount, scheme, dt = MODELS[args.model]
    print(f"{args.model}, W = {W}, {WIDTH} x {WIDTH} block at {'norm' if args.model == 'dnls' else 'energy'} {amount}, "
          f"{scheme}, dt = {dt}, {args.steps} steps, {args.lanes} lanes, tangent map\n")
    print("| L | sites | window at the end | windowed CPU s | whole lattice CPU s | max difference |\n"
          "|---:|---:|---|---:|---:|---:|")
    rows = []
    for L in args.L:
        lattices, state = states(args.model, L, args.lanes)
        problem = Problem(args.model, lattices, integrator=scheme, dt=dt, check_every=100)
        windowed_s, windowed = timed(lambda: WindowedEngine(problem, Window(), *state), args.steps, args.repeats)
        whole_s, whole = timed(lambda: problem.engine(*(a.copy() for a in state)), args.steps, args.repeats)
        _, lo_x, hi_x, lo_y, hi_y = windowed.spans[-1]
        diff = float(max(np.abs(windowed.q - whole.q).max(), np.abs(windowed.p - whole.p).max()))
        rows.append({"L": L, "sites": L * L, "window": f"{hi_x - lo_x} x {hi_y - lo_y}",
                     "windowed_cpu_s": round(windowed_s, 3), "whole_cpu_s": round(whole_s, 3),
                     "max_difference": float(f"{diff:.1e}")})
        print(f"| {L} | {L * L} | {hi_x - lo_x} x {hi_y - lo_y} | {windowed_s:.2f} | {whole_s:.2f} | {diff:.1e} |",
              flush=True)
    columns = {"L": "L", "sites": "sites", "window": "window at the end", "windowed_cpu_s": "windowed CPU s",
               "whole_cpu_s": "whole lattice CPU s", "max_difference": "largest difference of the final states"}
    return {"title": TITLE.format(model=args.model.upper()),
            "parameters": {"model": args.model, "W": W, "block": WIDTH, "amount": amount, "scheme": scheme, "dt": dt,
                           "steps": args.steps, "lanes": args.lanes, "repeats": args.repeats},
            "columns": [{"key": k, "label": v} for k, v in columns.items()], "rows": rows}


if __name__ == "__main__":
    main(sys.argv[1:])
