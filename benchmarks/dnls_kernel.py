"""The DNLS engines: ns per site and step against a hand-written C loop of the same scheme.

    python benchmarks/dnls_kernel.py [--N 64 256 1024 4096] [--integrator s9ABC6] [--sites-steps 1e7]
                                     [--repeats 3] [--check-steps 1000] [--note TEXT] [--no-record]

A line naming the machine, then one table: the disordered DNLS lattice (``dnls_chain(0, W = 4,
N, beta = 1)``) from a random state of amplitude 0.3 on every site (q and p uniform in
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
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from kernel_vs_c import BUILD, CFLAGS, HERE  # the same gcc flags and build folder

from chainchaos.engine.problem import Problem
from chainchaos.engine.split_schemes import SPLIT_SCHEMES, get_split_scheme
from chainchaos.kernels.simd import LANES
from chainchaos.records.provenance import machine_line
from chainchaos.system.chain import dnls_chain
from chainchaos.system.models.dnls import MODEL

SOURCE = HERE / "c_reference" / "dnls_chain.c"
DT, W, BETA, AMPLITUDE, CHECK_EVERY = 0.1, 4.0, 1.0, 0.3, 1000
TITLE = "DNLS kernels: ns per site and step against a C loop"


def compile_c() -> Path:
    BUILD.mkdir(exist_ok=True)
    exe = BUILD / "dnls_chain"
    subprocess.run(["gcc", *CFLAGS, "-o", str(exe), str(SOURCE), "-lm"], check=True)
    return exe


def lattice(N: int):
    return dnls_chain(0, W, N, beta=BETA)


def start(N: int, B: int):
    """Random state of amplitude AMPLITUDE and a random deviation vector, the same on every lane."""
    rng = np.random.default_rng(1)
    q, p, dq, dp = (np.tile(rng.uniform(-AMPLITUDE, AMPLITUDE, N)[:, None], (1, B)) for _ in range(4))
    return q, p, dq, dp


def run_engine(N: int, kind: str, integrator: str, steps: int, tangent: bool, repeats: int):
    """(best CPU seconds of ``steps`` steps, final state of lane 0) of one engine on one block
    (``LANES`` trajectories for "batch", one for "single"), each repeat from the same state."""
    B = LANES if kind == "batch" else 1
    problem = Problem("dnls", [lattice(N)] * B, integrator=integrator, dt=DT, tangent=tangent,
                      check_every=CHECK_EVERY)
    state = start(N, B)
    problem.engine(*state, kind=kind).advance(2)  # compilation or cache load, not timed
    best, engine = np.inf, None
    for _ in range(repeats):
        engine = problem.engine(*state, kind=kind)
        t0 = time.process_time()
        engine.advance(steps)
        best = min(best, time.process_time() - t0)
    final = {key: getattr(engine, key)[:, 0].copy() for key in ("q", "p", "dq", "dp")}
    return best, final


def time_engine(N: int, kind: str, integrator: str, steps: int, tangent: bool, repeats: int) -> float:
    """Best CPU ns per site and step per trajectory of one engine."""
    seconds, _ = run_engine(N, kind, integrator, steps, tangent, repeats)
    return 1e9 * seconds / (steps * N * (LANES if kind == "batch" else 1))


def run_c(exe: Path, N: int, integrator: str, steps: int, tangent: bool, repeats: int):
    """(best ns per site and step, final state) of the C loop."""
    scheme = get_split_scheme(integrator)
    sites = MODEL.site_parameters(lattice(N))
    q, p, dq, dp = (a[:, 0] for a in start(N, 1))
    values = {"eps": sites[0], "beta": sites[1], "q": q, "p": p, "dq": dq, "dp": dp}
    lines = [f"N {N}", f"steps {steps}", f"tangent {int(tangent)}", f"check_every {CHECK_EVERY}",
             f"repeats {repeats}", f"dt {DT!r}", f"stages {scheme.stages}",
             "parts " + " ".join(str(int(k)) for k in scheme.parts),
             "coefficients " + " ".join(repr(float(c)) for c in scheme.coefficients)]
    lines += [key + " " + " ".join(repr(float(v)) for v in a) for key, a in values.items()]
    path = BUILD / f"dnls_input_{N}_{int(tangent)}.txt"
    path.write_text("\n".join(lines) + "\n")
    out = subprocess.run([str(exe), str(path)], check=True, capture_output=True, text=True).stdout
    fields = {line.split()[0]: line.split()[1:] for line in out.splitlines()}
    final = {key: np.array(fields[key], dtype=float) for key in ("q", "p", "dq", "dp")}
    return float(fields["ns_per_step"][0]) / N, final


def difference(a: dict, b: dict, tangent: bool) -> float:
    keys = ("q", "p", "dq", "dp") if tangent else ("q", "p")
    return max(float(np.max(np.abs(a[k] - b[k])) / np.max(np.abs(b[k]))) for k in keys)


def per_site(args, exe) -> list[dict]:
    rows = []
    print("| N | tangent | single ns/site/step | batch ns/site/step per lane | C ns/site/step | "
          "batch / C | single / C | C vs single: rel. diff. |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|")
    for N in args.N:
        steps = max(20, int(args.sites_steps / N))
        for tangent in (True, False):
            single = time_engine(N, "single", args.integrator, steps, tangent, args.repeats)
            batch = time_engine(N, "batch", args.integrator, max(4, steps // LANES), tangent, args.repeats)
            c, _ = run_c(exe, N, args.integrator, steps, tangent, args.repeats)
            _, s_final = run_engine(N, "single", args.integrator, args.check_steps, tangent, 1)
            _, c_final = run_c(exe, N, args.integrator, args.check_steps, tangent, 1)
            diff = difference(s_final, c_final, tangent)
            rows.append({"N": N, "tangent": tangent, "single_ns": round(single, 3), "batch_ns": round(batch, 3),
                         "c_ns": round(c, 3), "batch_over_c": round(batch / c, 2), "single_over_c": round(single / c, 2),
                         "difference": float(f"{diff:.1e}")})
            print(f"| {N} | {'on' if tangent else 'off'} | {single:.2f} | {batch:.2f} | {c:.2f} | {batch / c:.2f} | "
                  f"{single / c:.2f} | {diff:.1e} |", flush=True)
    return rows


COLUMNS = [("N", "N"), ("tangent", "tangent map"), ("single_ns", "single engine: ns per site and step"),
           ("batch_ns", "batch engine: ns per site and step per lane"), ("c_ns", "C loop: ns per site and step"),
           ("batch_over_c", "batch / C"), ("single_over_c", "single / C"),
           ("difference", "C vs single engine: relative difference of the final state")]


def parse(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--N", type=int, nargs="+", default=[64, 256, 1024, 4096])
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
    exe = compile_c()
    print(machine_line())
    print(f"DNLS lattice W = {W}, beta = {BETA}, amplitude {AMPLITUDE}, {args.integrator} at dt = {DT}, "
          f"CPU time (time.process_time; C: CLOCK_PROCESS_CPUTIME_ID), best of {args.repeats}; batch: one "
          f"block of {LANES} trajectories; C: gcc {' '.join(CFLAGS)}\n")
    rows = per_site(args, exe)
    parameters = {"W": W, "beta": BETA, "amplitude": AMPLITUDE, "integrator": args.integrator, "dt": DT,
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
