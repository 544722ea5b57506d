"""Error against run time, and stability on extreme cases, of the square KG and DNLS lattices.

    python benchmarks/work_precision_2d.py [--L 32] [--t-final 100] [--dts 0.4 0.2 0.1 0.05]
    python benchmarks/record.py work_precision_2d -- [the same options]

A line naming the machine, then two tables.

1. **Work and precision.** Every scheme of each model at each step ``--dts``, on ``LANES``
   realizations of the L x L lattice (one SIMD block, tangent map on) to ``--t-final``: the largest
   relative energy error over the lanes and the samples (and the DNLS norm error), and the CPU
   seconds (best of ``--repeats``; compilation excluded). The KG lattice (W = 10, a 3 x 3 block at
   energy 0.9 as displacements, ``chain.kg_lattice``) runs the two-part symplectic schemes of
   ``engine.integrators``; the DNLS lattice (W = 10, beta = 1, a 3 x 3 block at norm 4.5 with
   random phases, ``chain.dnls_lattice``) the three-part ABC schemes of ``engine.split_schemes``.
   A scheme of order p has its error fall as dt^p until round-off: the observed order (the slope
   of log10 error against log10 dt over the two smallest steps above 1e-13) is printed beside p.
2. **Stiff and extreme cases**, at the finest step of table 1 with the kept studies' schemes
   (ABA864, order 4, for KG; s9ABC6, order 6, for DNLS): weak and strong disorder (W = 1 and W = 40), strong
   nonlinearity (KG: the block at energy 40, frequencies far above the linear band; DNLS: beta =
   30 on one site of norm 1, a self-trapped breather, its frequency shift beta above the band width
   W + 8), and whether the state stayed finite with its errors.
"""

import argparse
import sys
import time

import numpy as np

from chainchaos import SPLIT_SCHEMES, Problem, sample
from chainchaos.engine.integrators import SCHEMES
from chainchaos.kernels.simd import LANES
from chainchaos.records.provenance import machine_line
from chainchaos.system.chain import dnls_lattice, kg_lattice
from chainchaos.system.initial import Excitation, initial_deviation

TITLE = "Square KG and DNLS lattices: energy (and norm) error against CPU time, and extreme cases"
STUDY_SCHEMES = {"kg": "ABA864", "dnls": "s9ABC6"}  # the kept 2D studies'


def case(model: str, L: int, W: float, amount: float, beta: float = 1.0, width: int = 3):
    """The lanes' lattices and states (q, p, dq, dp), each (L^2, LANES), of one case."""
    if model == "kg":
        lattices = [kg_lattice(seed, W, (L, L)) for seed in range(LANES)]
    else:
        lattices = [dnls_lattice(seed, W, (L, L), beta) for seed in range(LANES)]
    centre = ((L + 1) // 2, (L + 1) // 2)
    N = L * L
    q, p, dq, dp = (np.zeros((N, LANES)) for _ in range(4))
    for j, lattice in enumerate(lattices):
        kind = "block" if width > 1 else "site"
        excitation = Excitation(kind=kind, site=centre, width=width, phases="random", seed=j) if model == "dnls" \
            else Excitation(kind=kind, site=centre, width=width)
        q[:, j], p[:, j], _ = excitation.state(model, lattice, amount)
        dq[:, j], dp[:, j] = initial_deviation(N, j)
    return lattices, (q, p, dq, dp)


def measure(model: str, lattices, state, scheme: str, dt: float, t_final: float, repeats: int) -> dict:
    """Largest errors over lanes and samples, finiteness and best CPU seconds of one run."""
    problem = Problem(model, lattices, integrator=scheme, dt=dt, check_every=100)
    steps = np.unique(np.rint(np.geomspace(1.0, t_final, 9) / dt).astype(np.int64))
    steps = np.concatenate(([0], steps[steps > 0]))
    sample(problem, *(a.copy() for a in state), steps[:2], kind="batch")  # compilation or the cache's load
    best, record = np.inf, None
    for _ in range(repeats):
        start = time.process_time()
        record = sample(problem, *(a.copy() for a in state), steps, kind="batch")
        best = min(best, time.process_time() - start)
    finite = bool(np.all(np.isfinite(record.Q)) and np.all(np.isfinite(record.P)))
    out = {"energy_error": float(np.max(record.energy_error)), "finite": finite, "cpu_s": round(best, 3)}
    if model == "dnls":
        out["norm_error"] = float(np.max(record.norm_error))
    return out


def order(dts, errors) -> float:
    """Slope of log10 error against log10 dt over the two smallest steps whose errors are above 1e-13."""
    pairs = [(dt, e) for dt, e in zip(dts, errors) if e > 1e-13]
    if len(pairs) < 2:
        return float("nan")
    (d1, e1), (d2, e2) = sorted(pairs)[:2]
    return float(np.log10(e2 / e1) / np.log10(d2 / d1))


def parse(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--L", type=int, default=32)
    parser.add_argument("--t-final", type=float, default=100.0)
    parser.add_argument("--dts", type=float, nargs="+", default=[0.4, 0.2, 0.1, 0.05])
    parser.add_argument("--repeats", type=int, default=1)
    return parser.parse_args(argv)


def main(argv=None) -> dict:
    """Print both tables; return ``record.py``'s part of a record."""
    args = parse(argv)
    print(machine_line())
    print(f"{args.L} x {args.L} lattices, {LANES} realizations (one SIMD block), tangent map, to t = {args.t_final:g}\n")
    print("| model | scheme | order | dt | energy error | norm error | CPU s |\n|---|---|---:|---:|---:|---:|---:|")
    rows = []
    for model, schemes, amount in (("kg", SCHEMES, 0.9), ("dnls", SPLIT_SCHEMES, 4.5)):
        lattices, state = case(model, args.L, 10.0, amount)
        for scheme, spec in schemes.items():
            errors = []
            for dt in args.dts:
                m = measure(model, lattices, state, scheme, dt, args.t_final, args.repeats)
                errors.append(m["energy_error"])
                rows.append({"model": model, "scheme": scheme, "order": spec.order, "dt": dt, **m})
                print(f"| {model} | {scheme} | {spec.order} | {dt:g} | {m['energy_error']:.1e} | "
                      f"{m.get('norm_error', float('nan')):.1e} | {m['cpu_s']:.2f} |", flush=True)
            rows[-1]["observed_order"] = round(order(args.dts, errors), 2)
            print(f"|  | {scheme}: observed order {rows[-1]['observed_order']} |  |  |  |  |  |")
    extreme = []
    print(f"\nStiff and extreme cases, dt = {min(args.dts):g}, the kept studies' schemes (KG ABA864, DNLS s9ABC6)\n")
    print("| model | case | finite | energy error | norm error |\n|---|---|---|---:|---:|")
    cases = [("kg", "weak disorder W = 1", dict(W=1.0, amount=0.9)),
             ("kg", "strong disorder W = 40", dict(W=40.0, amount=0.9)),
             ("kg", "strong nonlinearity E = 40", dict(W=10.0, amount=40.0)),
             ("dnls", "weak disorder W = 1", dict(W=1.0, amount=4.5)),
             ("dnls", "strong disorder W = 40", dict(W=40.0, amount=4.5)),
             ("dnls", "self-trapping beta = 30, one site", dict(W=10.0, amount=1.0, beta=30.0, width=1))]
    for model, label, kw in cases:
        lattices, state = case(model, args.L, **kw)
        m = measure(model, lattices, state, STUDY_SCHEMES[model], min(args.dts), args.t_final, 1)
        extreme.append({"model": model, "case": label, **m})
        print(f"| {model} | {label} | {m['finite']} | {m['energy_error']:.1e} | "
              f"{m.get('norm_error', float('nan')):.1e} |", flush=True)
    return {"title": TITLE, "parameters": {"L": args.L, "t_final": args.t_final, "dts": args.dts,
                                          "repeats": args.repeats, "lanes": LANES},
            "columns": [{"key": k, "label": k} for k in ("model", "scheme", "order", "dt", "energy_error",
                                                          "norm_error", "cpu_s", "observed_order")],
            "rows": rows, "extreme": extreme}


if __name__ == "__main__":
    main(sys.argv[1:])
