"""Numba engine against a hand-written C loop of the same scheme, on the same problem, in one run.

    python benchmarks/kernel_vs_c.py [--N 40] [--steps 4000] [--repeats 100]

Compiles benchmarks/c_reference/srkn6b_chain.c into benchmarks/build/ (gcc -O3 -march=native
-std=c99 -fno-math-errno: no -ffast-math, as Numba runs without fastmath; -fno-math-errno only
lets gcc vectorise sqrt, like Numba's), integrates the benchmark problem of chainchaos.studies.numerics.bench
(N = 40, alpha = 5 chain of seed 879, H = 1.8, dt = 5e-4, renormalisation every 1000 steps) with
both, checks that they end in the same state (q, p, dq, dp and the log growth), and prints
Markdown tables: ns per step (best of the repeats) of Numba and C and their ratio for SRKN6b,
Hertz and FPUT, tangent dynamics on and off; then ns per step of every scheme in Numba.
Exits 1 if the final states differ by more than --rtol (relative, max norm).
"""

import argparse
import os
import subprocess
import sys
from pathlib import Path

os.environ["NUMBA_NUM_THREADS"] = "1"  # single thread, before numba is imported

import numpy as np  # noqa: E402

from chainchaos.engine.integrators import SCHEMES  # noqa: E402
from chainchaos.records.provenance import machine_line  # noqa: E402
from chainchaos.studies.numerics.bench import (  # noqa: E402
    CHECK_EVERY,
    DT,
    benchmark_problem,
    run_kernel,
)

HERE = Path(__file__).resolve().parent
SOURCE = HERE / "c_reference" / "srkn6b_chain.c"
BUILD = HERE / "build"
#: gcc targets the CPU Numba compiles for (NUMBA_CPU_NAME, e.g. haswell for an AVX2 build), else the host.
MARCH = os.environ.get("NUMBA_CPU_NAME") or "native"
CFLAGS = ["-O3", f"-march={MARCH}", "-std=c99", "-fno-math-errno"]


def compile_c(N: int) -> Path:
    BUILD.mkdir(exist_ok=True)
    exe = BUILD / f"srkn6b_chain_N{N}"
    subprocess.run(["gcc", *CFLAGS, f"-DNB={N}", "-o", str(exe), str(SOURCE), "-lm"], check=True)
    return exe


def run_c(exe: Path, problem: dict, n_steps: int, tangent: bool, repeats: int) -> tuple[dict, float, float]:
    """Run the C program on ``problem``; returns (final state, log growth, best ns per step)."""
    N = problem["q"].size
    c_model = 0 if problem["model"].name == "hertz" else 1  # the C loop's codes: 0 Hertz, 1 FPUT
    lines = [f"model {c_model}", f"N {N}", f"steps {n_steps}", f"tangent {int(tangent)}",
             f"check_every {CHECK_EVERY}", f"repeats {repeats}", f"dt {DT!r}"]
    for key in ("A", "delta", "K2", "K3", "K4", "inv_mass", "q", "p", "dq", "dp"):
        lines.append(key + " " + " ".join(repr(float(v)) for v in problem[key]))
    path = BUILD / f"input_{problem['model'].name}_{int(tangent)}.txt"
    path.write_text("\n".join(lines) + "\n")
    out = subprocess.run([str(exe), str(path)], check=True, capture_output=True, text=True).stdout
    fields = {line.split()[0]: line.split()[1:] for line in out.splitlines()}
    if int(fields["bad_step"][0]) >= 0:
        raise RuntimeError(f"C run became non-finite at step {fields['bad_step'][0]}")
    state = {key: np.array(fields[key], dtype=float) for key in ("q", "p", "dq", "dp")}
    return state, float(fields["log_growth"][0]), float(fields["ns_per_step"][0])


def time_numba(problem: dict, integrator: str, n_steps: int, tangent: bool, repeats: int):
    """(final state, log growth, best ns per step) of the Numba engine on ``problem``."""
    run_kernel(problem, integrator, 10, tangent)  # JIT compilation or cache load, not timed
    runs = [run_kernel(problem, integrator, n_steps, tangent) for _ in range(repeats)]
    state, growth, _ = runs[-1]
    return state, growth, 1e9 * min(r[2] for r in runs) / n_steps


def difference(a: dict, b: dict, tangent: bool) -> float:
    """Largest relative difference of the final states (each vector against its max norm)."""
    keys = ("q", "p", "dq", "dp") if tangent else ("q", "p")
    return max(float(np.max(np.abs(a[key] - b[key])) / np.max(np.abs(b[key]))) for key in keys)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--N", type=int, default=40)
    parser.add_argument("--steps", type=int, default=4_000, help="steps per timed run")
    parser.add_argument("--repeats", type=int, default=100, help="timed runs; the best one counts")
    parser.add_argument("--rtol", type=float, default=1e-12)
    args = parser.parse_args(argv)

    exe = compile_c(args.N)
    problems = {model: benchmark_problem(model, args.N) for model in ("hertz", "fput")}
    print(machine_line())
    print(f"N = {args.N}, H = 1.8, dt = {DT}, best of {args.repeats} runs of {args.steps} steps, "
          f"one thread (NUMBA_NUM_THREADS = {os.environ['NUMBA_NUM_THREADS']}); "
          f"C: gcc {' '.join(CFLAGS)}\n")
    print("| scheme | model | tangent | Numba ns/step | C ns/step | Numba/C | final state rel. diff. |")
    print("|---|---|---|---:|---:|---:|---:|")
    ok = True
    for model, problem in problems.items():
        for tangent in (True, False):
            s_nb, g_nb, ns_nb = time_numba(problem, "SRKN6b", args.steps, tangent, args.repeats)
            s_c, g_c, ns_c = run_c(exe, problem, args.steps, tangent, args.repeats)
            diff = difference(s_nb, s_c, tangent)
            if tangent:
                diff = max(diff, abs(g_nb - g_c) / abs(g_c))
            ok &= diff <= args.rtol
            print(f"| SRKN6b | {model} | {'on' if tangent else 'off'} | {ns_nb:.0f} | {ns_c:.0f} | "
                  f"{ns_nb / ns_c:.2f} | {diff:.1e} |", flush=True)

    print("\nNumba engine, every scheme (ns per step, tangent on / off):\n")
    print("| scheme | order | force evaluations/step | Hertz on | Hertz off | FPUT on | FPUT off |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name, scheme in SCHEMES.items():
        cells = [time_numba(problems[model], name, args.steps, tangent, args.repeats)[2]
                 for model in ("hertz", "fput") for tangent in (True, False)]
        print(f"| {name} | {scheme.order} | {scheme.force_evaluations} | "
              + " | ".join(f"{ns:.0f}" for ns in cells) + " |", flush=True)

    if not ok:
        print(f"\nFAIL: Numba and C final states differ by more than rtol = {args.rtol:g}", file=sys.stderr)
        return 1
    print(f"\nNumba and C final states agree within rtol = {args.rtol:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
