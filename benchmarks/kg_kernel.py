"""The Klein-Gordon kernels: ns per site and step against a C loop, memory, and the window's cost.

    python benchmarks/kg_kernel.py [--N 64 256 1024 4096] [--integrator ABA864] [--sites-steps 4e7]
                                   [--repeats 3] [--check-steps 1000] [--memory-N 4096] [--spreading-t 1e4]
                                   [--square 32 64 128] [--parts per_site memory spreading square]

Four tables, after a line naming the machine:

1. **Per site and step.** The KG lattice (W = 4, seed 0) from a random state of amplitude 0.1 on
   every site, integrated by ``--integrator`` at dt = 0.4: the single-trajectory engine
   (``integrators.advance``: one trajectory), the batch engine (``batch.Batch``: one SIMD block of
   ``LANES`` trajectories, per trajectory) and a hand-written C loop of the same scheme
   (``benchmarks/c_reference/kg_chain.c``, gcc -O3 -march=native, no -ffast-math), with and
   without the tangent map; best of ``--repeats`` timings of about ``--sites-steps`` site-steps
   each, and the ratios to C. The C run's final state after ``--check-steps`` steps is checked
   against the single engine's (relative difference printed; the operations are the same up to
   their order).
2. **Memory.** Peak resident memory (``ru_maxrss`` of a fresh process) of 64 realizations at
   N = ``--memory-N`` through ``orbits.integrate`` (the study's path: 20 samples per decade to
   t = 1e3, batches of 32 orbits), with and without the growing window.
3. **Cost against N.** One single-site momentum excitation (E = 0.4) per realization, 8
   realizations (one AVX-512 block), to t = ``--spreading-t``: CPU seconds for N = 512 .. 4096 on
   the whole chain and on the growing window (``chainchaos.run.window``), with the window's final
   width: the windowed cost follows the packet's width, the whole chain's N.
4. **The square lattice.** The L x L lattice ``kg_lattice(0, W, (L, L))`` (``engine.lattice``:
   single loop and SIMD blocks, and a hand-written C loop of the same scheme,
   ``benchmarks/c_reference/kg_square.c``) beside the chain of L^2 sites (``integrators`` and
   ``batch``), from the same random state, with the tangent map: ns per site and step per
   trajectory, and per bond (a square lattice has about two bonds per site, a chain one); the C
   loop's final state after ``--check-steps`` steps against the single loop's.
"""

import argparse
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from c_loops import compile_c, difference, engine_runner, per_site, run_c
from kernel_vs_c import CFLAGS, HERE

from chainchaos.engine.integrators import get_scheme
from chainchaos.engine.lattice import line_bonds
from chainchaos.engine.problem import Problem
from chainchaos.kernels.simd import LANES
from chainchaos.records.provenance import machine_line
from chainchaos.system.chain import kg_chain, kg_lattice
from chainchaos.system.models import MODELS

SOURCE = HERE / "c_reference" / "kg_chain.c"
SQUARE_SOURCE = HERE / "c_reference" / "kg_square.c"
DT, W, CHECK_EVERY = 0.4, 4.0, 1000


def start(N: int, B: int):
    """Random state of amplitude 0.1 and a deviation vector, the same on every lane."""
    rng = np.random.default_rng(1)
    q, p, dq, dp = (np.tile(rng.uniform(-0.1, 0.1, N)[:, None], (1, B)) for _ in range(4))
    return q, p, dq, dp


def c_run(args, exe: Path):
    """``c_loops.per_site``'s C loop: (ns per site and step, final state)."""
    scheme = get_scheme(args.integrator)

    def run(N: int, steps: int, tangent: bool):
        lattice = kg_chain(0, W, N)
        q, p, dq, dp = (a[:, 0] for a in start(N, 1))
        ns, final = run_c(exe, f"kg_input_{N}_{int(tangent)}", {
            "N": N, "steps": steps, "tangent": int(tangent), "check_every": CHECK_EVERY, "repeats": args.repeats,
            "dt": DT, "stages": len(scheme.drifts), "kicks": scheme.kicks, "drifts": scheme.drifts,
            "K2": np.full(N + 1, lattice.K2), "eps": lattice.eps, "q": q, "p": p, "dq": dq, "dp": dp})
        return ns / N, final
    return run


def per_site_part(args, exe) -> list[dict]:
    engine = engine_runner("kg", lambda N: kg_chain(0, W, N), start, args.integrator, DT, CHECK_EVERY, args.repeats,
                           LANES)
    return per_site(args.N, args.sites_steps, args.check_steps, LANES, engine, c_run(args, exe))


MEMORY_RUN = """
import resource, sys, numpy as np
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
from chainchaos.run.window import Window
from chainchaos.system.chain import kg_chain
from chainchaos.system.initial import Excitation
N, windowed = int(sys.argv[1]), sys.argv[2] == "1"
orbits = [Orbit(model="kg", energy=0.4, chain=kg_chain(s, 4.0, N), site=N // 2,
                excitation=Excitation(site=N // 2, variable="momentum")) for s in range(64)]
settings = OrbitSettings(t_final=1e3, dt=0.4, integrator="ABA864", samples_per_decade=20, batch_size=32)
integrate(orbits, settings, series={"participation": np.nan, "second_moment": np.nan, "mlce": np.nan},
          window=Window() if windowed else None)
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


def memory(args, exe=None) -> list[dict]:
    rows = []
    print(f"\nPeak resident memory, 64 realizations at N = {args.memory_N} (t = 1e3, batches of 32):\n")
    print("| run | peak MiB |")
    print("|---|---:|")
    for windowed in (False, True):
        out = subprocess.run([sys.executable, "-c", MEMORY_RUN, str(args.memory_N), str(int(windowed))],
                             check=True, capture_output=True, text=True).stdout
        mib = int(out.split()[-1]) / 1024  # ru_maxrss: KiB on Linux
        label = "growing window" if windowed else "whole chain"
        rows.append({"run": label, "N": args.memory_N, "peak_mib": round(mib, 1)})
        print(f"| {label} | {mib:.0f} |", flush=True)
    return rows


def spreading(args, exe=None) -> list[dict]:
    from chainchaos.run.window import Window, WindowedEngine, restricted_deviation
    from chainchaos.system.initial import Excitation, initial_deviation

    rows = []
    steps = round(args.spreading_t / DT)
    print(f"\nSpreading run to t = {args.spreading_t:g} ({steps} steps, {args.integrator}, dt = {DT}), "
          f"{LANES} realizations, E = 0.4 on the centre site, tangent map on: CPU seconds\n")
    print("| N | whole chain s | window s | window width at the end | whole / window |")
    print("|---:|---:|---:|---:|---:|")
    for N in (512, 1024, 2048, 4096):
        chains = [kg_chain(s, W, N) for s in range(LANES)]
        problem = Problem("kg", chains, integrator=args.integrator, dt=DT, check_every=CHECK_EVERY)
        q, p, dq, dp = (np.zeros((N, LANES)) for _ in range(4))
        for j, c in enumerate(chains):
            q[:, j], p[:, j], _ = Excitation(site=N // 2, variable="momentum").state(problem.model, c, 0.4)
            dq[:, j], dp[:, j] = initial_deviation(N, j)
        dq, dp = restricted_deviation(dq, dp, *Window.excited(q, p))
        whole = problem.engine(q, p, dq, dp, kind="batch")
        whole.advance(2)
        whole = problem.engine(q, p, dq, dp, kind="batch")
        t0 = time.process_time()
        whole.advance(steps)
        t_whole = time.process_time() - t0
        t0 = time.process_time()
        windowed = WindowedEngine(problem, Window(), q, p, dq, dp, kind="batch")
        windowed.advance(steps)
        t_window = time.process_time() - t0
        width = windowed.hi - windowed.lo
        rows.append({"N": N, "whole_s": round(t_whole, 2), "window_s": round(t_window, 2), "width": width,
                     "ratio": round(t_whole / t_window, 1)})
        print(f"| {N} | {t_whole:.2f} | {t_window:.2f} | {width} | {t_whole / t_window:.1f} |", flush=True)
    return rows


def square_c_run(args, exe: Path):
    """The square lattice's C loop: (ns per site and step, final state)."""
    scheme = get_scheme(args.integrator)

    def run(L: int, steps: int):
        lattice = kg_lattice(0, W, (L, L))
        px, py = line_bonds(lattice.geometry, MODELS["kg"].bond_parameters(lattice))
        q, p, dq, dp = (a[:, 0] for a in start(L * L, 1))
        ns, final = run_c(exe, f"kg_square_input_{L}", {
            "nx": L, "ny": L, "steps": steps, "tangent": 1, "check_every": CHECK_EVERY, "repeats": args.repeats,
            "dt": DT, "stages": len(scheme.drifts), "kicks": scheme.kicks, "drifts": scheme.drifts,
            "KX": px[0], "KY": py[0], "eps": lattice.eps, "q": q, "p": p, "dq": dq, "dp": dp})
        return ns / (L * L), final
    return run


def square(args, exe=None) -> list[dict]:
    rows = []
    c_loop = square_c_run(args, compile_c(SQUARE_SOURCE))
    print(f"\nThe square lattice beside the chain of as many sites ({args.integrator}, dt = {DT}, tangent map): "
          "ns per site and step per trajectory (per bond in brackets), and the square lattice's C loop\n")
    print("| L | sites | lattice single | lattice batch | chain single | chain batch | lattice / chain, batch | "
          "lattice C | lattice batch / C | C vs single: rel. diff. |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for L in args.square:
        N = L * L
        steps = max(20, int(args.sites_steps / N))
        ns = {}
        for shape, lattice in (("lattice", lambda n: kg_lattice(0, W, (L, L))), ("chain", lambda n: kg_chain(0, W, n))):
            run = engine_runner("kg", lattice, start, args.integrator, DT, CHECK_EVERY, args.repeats, LANES)
            for kind in ("single", "batch"):
                ns[shape, kind] = run(N, kind, steps if kind == "single" else max(4, steps // LANES), True)[0]
        c, _ = c_loop(L, steps)
        lattice_run = engine_runner("kg", lambda n: kg_lattice(0, W, (L, L)), start, args.integrator, DT, CHECK_EVERY,
                                    1, LANES)
        diff = difference(lattice_run(N, "single", args.check_steps, True)[1], c_loop(L, args.check_steps)[1], True)
        bonds = {"lattice": kg_lattice(0, W, (L, L)).geometry.n_bonds, "chain": N + 1}
        row = {"L": L, "sites": N, **{f"{shape}_{kind}_ns": round(v, 2) for (shape, kind), v in ns.items()},
               **{f"{shape}_{kind}_ns_per_bond": round(v * N / bonds[shape], 2) for (shape, kind), v in ns.items()},
               "ratio_batch": round(ns["lattice", "batch"] / ns["chain", "batch"], 2), "lattice_c_ns": round(c, 2),
               "lattice_batch_over_c": round(ns["lattice", "batch"] / c, 2), "difference": float(f"{diff:.1e}")}
        rows.append(row)
        cell = {k: f"{v:.1f} ({v * N / bonds[k[0]]:.1f})" for k, v in ns.items()}
        print(f"| {L} | {N} | {cell['lattice', 'single']} | {cell['lattice', 'batch']} | {cell['chain', 'single']} | "
              f"{cell['chain', 'batch']} | {row['ratio_batch']:.2f} | {c:.1f} | {row['lattice_batch_over_c']:.2f} | "
              f"{diff:.1e} |", flush=True)
    return rows


PARTS = {"per_site": per_site_part, "memory": memory, "spreading": spreading, "square": square}


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--N", type=int, nargs="+", default=[64, 256, 1024, 4096])
    parser.add_argument("--integrator", default="ABA864")
    parser.add_argument("--sites-steps", type=float, default=4e7, help="site-steps per timed run")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--check-steps", type=int, default=1000,
                        help="steps of the runs whose final states are compared (default 1000)")
    parser.add_argument("--memory-N", type=int, default=4096)
    parser.add_argument("--spreading-t", type=float, default=1e4)
    parser.add_argument("--square", type=int, nargs="+", default=[32, 64, 128], help="L of the L x L lattices")
    parser.add_argument("--parts", nargs="+", choices=PARTS, default=list(PARTS))
    args = parser.parse_args(argv)
    exe = compile_c(SOURCE)
    print(machine_line())
    print(f"KG lattice W = {W}, {args.integrator} at dt = {DT}, CPU time (time.process_time), best of "
          f"{args.repeats}; batch: one block of {LANES} trajectories; C: gcc {' '.join(CFLAGS)}\n")
    return {part: PARTS[part](args, exe) for part in args.parts}


if __name__ == "__main__":
    main()
    print(f"peak memory of this process: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB")
