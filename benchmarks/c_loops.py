"""What the benchmarks that race the engines against a hand-written C loop share: compiling the
loop, the input file it reads and the lines it prints, timing an engine, and the per-site table.

A C loop (``benchmarks/c_reference/*.c``) reads ``key value ...`` lines (scalars, then the
scheme's coefficients and the site arrays) and prints ``ns_per_step`` and the final ``q p dq dp``.
"""

import subprocess
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from kernel_vs_c import BUILD, CFLAGS  # the bead chains' gcc flags and build folder

from chainchaos.engine.problem import Problem

PER_SITE_HEADER = ("| N | tangent | single ns/site/step | batch ns/site/step per lane | C ns/site/step | "
                   "batch / C | single / C | C vs single: rel. diff. |\n|---:|---|---:|---:|---:|---:|---:|---:|")


def compile_c(source: Path) -> Path:
    """The executable of ``source``, built by gcc with ``CFLAGS`` into ``BUILD``."""
    BUILD.mkdir(exist_ok=True)
    exe = BUILD / source.stem
    subprocess.run(["gcc", *CFLAGS, "-o", str(exe), str(source), "-lm"], check=True)
    return exe


def _text(values) -> str:
    a = np.ravel(values)
    return " ".join(str(int(v)) if np.issubdtype(a.dtype, np.integer) else repr(float(v)) for v in a)


def run_c(exe: Path, name: str, fields: dict) -> tuple[float, dict]:
    """(ns per step, final q, p, dq, dp) of the C loop ``exe`` on the input ``fields`` (key:
    number or array; integers written as integers), kept as ``BUILD/<name>.txt``."""
    path = BUILD / f"{name}.txt"
    path.write_text("".join(f"{key} {_text(value)}\n" for key, value in fields.items()))
    out = subprocess.run([str(exe), str(path)], check=True, capture_output=True, text=True).stdout
    printed = {line.split()[0]: line.split()[1:] for line in out.splitlines()}
    final = {key: np.array(printed[key], dtype=float) for key in ("q", "p", "dq", "dp")}
    return float(printed["ns_per_step"][0]), final


def time_engine(problem, state, kind: str, steps: int, repeats: int) -> tuple[float, dict]:
    """(best CPU seconds of ``steps`` steps, final state of lane 0) of ``problem``'s engine
    ``kind`` from ``state`` (q, p, dq, dp), each repeat from that state; compiling or loading the
    cache is not timed."""
    problem.engine(*state, kind=kind).advance(2)
    best, engine = np.inf, None
    for _ in range(repeats):
        engine = problem.engine(*state, kind=kind)
        t0 = time.process_time()
        engine.advance(steps)
        best = min(best, time.process_time() - t0)
    return best, {key: getattr(engine, key)[:, 0].copy() for key in ("q", "p", "dq", "dp")}


def engine_runner(model: str, lattice: Callable, start: Callable, integrator: str, dt: float, check_every: int,
                  repeats: int, lanes: int) -> Callable[..., tuple[float, dict]]:
    """:func:`per_site`'s engine for ``model``: ``run(N, kind, steps, tangent)`` gives (ns per site
    and step per trajectory, final state of lane 0) on ``lattice(N)`` from ``start(N, B)``, with
    ``lanes`` trajectories for the batch engine and one for the single engine."""
    def run(N: int, kind: str, steps: int, tangent: bool):
        B = lanes if kind == "batch" else 1
        problem = Problem(model, [lattice(N)] * B, integrator=integrator, dt=dt, tangent=tangent,
                          check_every=check_every)
        seconds, final = time_engine(problem, start(N, B), kind, steps, repeats)
        return 1e9 * seconds / (steps * N * B), final
    return run


def difference(a: dict, b: dict, tangent: bool) -> float:
    """Largest relative difference (max norm, per quantity) of two final states."""
    keys = ("q", "p", "dq", "dp") if tangent else ("q", "p")
    return max(float(np.max(np.abs(a[k] - b[k])) / np.max(np.abs(b[k]))) for k in keys)


def per_site(Ns, sites_steps: float, check_steps: int, lanes: int,
             engine: Callable[..., tuple[float, dict]], c_loop: Callable[..., tuple[float, dict]]) -> list[dict]:
    """Print and return the table of ns per site and step of both engines and the C loop, with and
    without the tangent map, for each N of ``Ns``: about ``sites_steps`` site-steps per timed run,
    and the relative difference of the C loop's final state from the single engine's after
    ``check_steps`` steps. ``engine(N, kind, steps, tangent)`` and ``c_loop(N, steps, tangent)``
    give (ns per site and step per trajectory, final state)."""
    rows = []
    print(PER_SITE_HEADER)
    for N in Ns:
        steps = max(20, int(sites_steps / N))
        for tangent in (True, False):
            single, _ = engine(N, "single", steps, tangent)
            batch, _ = engine(N, "batch", max(4, steps // lanes), tangent)
            c, _ = c_loop(N, steps, tangent)
            diff = difference(engine(N, "single", check_steps, tangent)[1], c_loop(N, check_steps, tangent)[1],
                              tangent)
            rows.append({"N": N, "tangent": tangent, "single_ns": round(single, 3), "batch_ns": round(batch, 3),
                         "c_ns": round(c, 3), "batch_over_c": round(batch / c, 2), "single_over_c": round(single / c, 2),
                         "difference": float(f"{diff:.1e}")})
            print(f"| {N} | {'on' if tangent else 'off'} | {single:.2f} | {batch:.2f} | {c:.2f} | {batch / c:.2f} | "
                  f"{single / c:.2f} | {diff:.1e} |", flush=True)
    return rows
