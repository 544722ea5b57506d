"""The DNLS engines: ns per site and step against a hand-written C loop of the same scheme.

    python benchmarks/dnls_kernel.py [--N 64 256 1024 4096] [--width 1] [--integrator s9ABC6]
                                     [--sites-steps 1e7] [--repeats 3] [--check-steps 1000] [--note TEXT]
                                     [--no-record]

A line naming the machine, then one table: the disordered DNLS lattice (``dnls_chain(0, W = 4,
N, beta = 1)``, or with ``--width`` w > 1 the square lattice ``dnls_lattice(0, 4, (N / w, w), 1)``
of w lines, whose cost per site a chain's should match) from a random state of amplitude 0.3 on every site (q and p uniform in
[-0.3, 0.3], a random deviation vector), integrated by the three-part scheme ``--integrator``
(``engine.split_schemes.SPLIT_SCHEMES``) at dt = 0.1, the deviation vector renormalised every
1000 steps: the single-trajectory engine (``engine.split.advance_split``: one trajectory), the
batch engine (``advance_split_batch``: one SIMD block of ``LANES`` trajectories, per trajectory)
and a hand-written C loop of the same scheme (``benchmarks/c_reference/dnls_chain.c``, gcc -O3
-march=native, no -ffast-math, the C library's sincos), with and without the tangent map; best
of ``--repeats`` timings (CPU time on both sides) of about ``--sites-steps`` site-steps each, and
the ratios to C (the goal: batch / C at most 1). The last column checks that the C loop is the
same scheme: the relative difference (max norm, per quantity) of the C run's final state
against the single engine's after ``--check-steps`` steps from the same state. The two differ
only in the sine and cosine (libm's against ``kernels.exactmath.sincos``, each within 1 ulp), so
the difference starts in the last bits and grows with the run's length as the dynamics amplifies
it; ``--check-steps`` keeps it a check of the scheme, not of the chaos.

The table is kept as a record in benchmarks/results/ (``benchmarks/record.py``'s format: commit,
CPU, load, parameters, rows) unless ``--no-record``.
"""

import argparse
import json
import shlex
import sys
from pathlib import Path

import numpy as np
from c_loops import compile_c, engine_runner, per_site, run_c
from kernel_vs_c import CFLAGS, HERE

from chainchaos.engine.split_schemes import SPLIT_SCHEMES, get_split_scheme
from chainchaos.kernels.simd import LANES
from chainchaos.records.provenance import machine_line
from chainchaos.system.chain import dnls_chain, dnls_lattice
from chainchaos.system.models.dnls import MODEL

SOURCE = HERE / "c_reference" / "dnls_chain.c"
DT, W, BETA, AMPLITUDE, CHECK_EVERY = 0.1, 4.0, 1.0, 0.3, 1000
TITLE = "DNLS kernels: ns per site and step against a C loop"


def lattice_of(width: int):
    """The lattice of N sites the runs integrate: the chain, or ``width`` lines of N / width."""
    def lattice(N: int):
        return dnls_chain(0, W, N, beta=BETA) if width == 1 else dnls_lattice(0, W, (N // width, width), beta=BETA)
    return lattice


def start(N: int, B: int):
    """Random state of amplitude AMPLITUDE and a random deviation vector, the same on every lane."""
    rng = np.random.default_rng(1)
    q, p, dq, dp = (np.tile(rng.uniform(-AMPLITUDE, AMPLITUDE, N)[:, None], (1, B)) for _ in range(4))
    return q, p, dq, dp


def c_run(args, exe: Path):
    """``c_loops.per_site``'s C loop: (ns per site and step, final state)."""
    scheme = get_split_scheme(args.integrator)

    def run(N: int, steps: int, tangent: bool):
        sites = MODEL.site_parameters(lattice_of(args.width)(N))
        q, p, dq, dp = (a[:, 0] for a in start(N, 1))
        ns, final = run_c(exe, f"dnls_input_{N}_{args.width}_{int(tangent)}", {
            "width": args.width, "N": N, "steps": steps, "tangent": int(tangent), "check_every": CHECK_EVERY, "repeats": args.repeats,
            "dt": DT, "stages": scheme.stages, "parts": np.asarray(scheme.parts, dtype=int),
            "coefficients": scheme.coefficients, "eps": sites[0], "beta": sites[1], "q": q, "p": p, "dq": dq, "dp": dp})
        return ns / N, final
    return run


COLUMNS = [("N", "N"), ("tangent", "tangent map"), ("single_ns", "single engine: ns per site and step"),
           ("batch_ns", "batch engine: ns per site and step per lane"), ("c_ns", "C loop: ns per site and step"),
           ("batch_over_c", "batch / C"), ("single_over_c", "single / C"),
           ("difference", "C vs single engine: relative difference of the final state")]


def parse(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--N", type=int, nargs="+", default=[64, 256, 1024, 4096])
    parser.add_argument("--width", type=int, default=1,
                        help="lines of a square lattice of N sites (default 1: the chain); divides every N")
    parser.add_argument("--integrator", default="s9ABC6", choices=sorted(SPLIT_SCHEMES))
    parser.add_argument("--sites-steps", type=float, default=1e7, help="site-steps per timed run (default 1e7)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--check-steps", type=int, default=1000,
                        help="steps of the runs whose final states are compared (default 1000)")
    parser.add_argument("--note", default="", help="kept with the record (e.g. the machine was loaded)")
    parser.add_argument("--no-record", action="store_true", help="print the table, write no record")
    return parser.parse_args(argv)


def main(argv=None) -> dict:
    """Print the table; return ``record.py``'s part of a record (title, parameters, columns, rows)."""
    args = parse(argv)
    bad = [N for N in args.N if N % args.width or N // args.width < 2]
    if args.width < 1 or bad:
        raise SystemExit(f"--width {args.width}: allowed is an integer >= 1 dividing every N into lines of >= 2 sites "
                         f"(not {bad})")
    exe = compile_c(SOURCE)
    print(machine_line())
    shape = "chain" if args.width == 1 else f"square lattice of {args.width} lines"
    print(f"DNLS {shape}, W = {W}, beta = {BETA}, amplitude {AMPLITUDE}, {args.integrator} at dt = {DT}, "
          f"CPU time (time.process_time; C: CLOCK_PROCESS_CPUTIME_ID), best of {args.repeats}; batch: one "
          f"block of {LANES} trajectories; C: gcc {' '.join(CFLAGS)}\n")
    engine = engine_runner("dnls", lattice_of(args.width), start, args.integrator, DT, CHECK_EVERY, args.repeats,
                           LANES)
    rows = per_site(args.N, args.sites_steps, args.check_steps, LANES, engine, c_run(args, exe))
    parameters = {"width": args.width, "W": W, "beta": BETA, "amplitude": AMPLITUDE, "integrator": args.integrator, "dt": DT,
                  "check_every": CHECK_EVERY, "sites_steps": args.sites_steps, "repeats": args.repeats,
                  "check_steps": args.check_steps, "lanes": LANES, "cflags": " ".join(CFLAGS),
                  "timer": "process CPU time, best of the repeats"}
    return {"title": TITLE, "parameters": parameters,
            "columns": [{"key": k, "label": label} for k, label in COLUMNS], "rows": rows}


def record(argv: list[str]) -> Path:
    """Run the benchmark through ``record.record`` (commit, CPU, load) and write its record."""
    sys.path.insert(0, str(HERE))
    import record as records

    records.BENCHMARKS.setdefault("dnls_kernel", main)
    path = records.record("dnls_kernel", argv, parse(argv).note)
    kept = json.loads(path.read_text())
    kept["command"] = shlex.join(["python", "benchmarks/dnls_kernel.py", *argv])  # not record.py's own
    path.write_text(json.dumps(kept, indent=1, ensure_ascii=False) + "\n")
    return path


if __name__ == "__main__":
    argv = sys.argv[1:]
    if parse(argv).no_record:
        main(argv)
    else:
        print(f"wrote {record(argv)}", file=sys.stderr)
