"""How the DNLS engines' norm and energy errors grow with time, for every split scheme.

The schemes' flows A (each site turning) and B, C (the halves of the hopping, in q and in p)
are exact, but B and C alone do not conserve the norm S = sum |psi_l|^2: a scheme conserves S to
its order, as it does H. This measures whether that error stays bounded, like the energy error
of a symplectic scheme, or grows, and by which power of t: the relative errors |S(t) - S(0)|/S(0)
and |H(t) - H(0)|/|H(0)|, the largest over 4 realizations (W = 4, beta = 0.72, a block of 11
sites at norm density 1, random phases: the DNLS tutorial's case, on N = 256 sites), sampled at
every power of ten to ``--t-final``, at the tutorial's step dt = 0.1; the growth exponent is the
least-squares slope of log10 error against log10 t over the last three decades of samples (a
rule, not a window chosen by eye).

    python benchmarks/dnls_norm_error.py [--t-final 1e6] [--json out.json]
"""

import argparse
import json
import time

import numpy as np

from chainchaos import SPLIT_SCHEMES, Problem, dnls_chain, sample
from chainchaos.system.initial import Excitation, initial_deviation

N, L, LANES, DT = 256, 11, 4, 0.1


def run(scheme: str, t_final: float) -> dict:
    lattices = [dnls_chain(seed, W=4.0, N=N, beta=0.72) for seed in range(LANES)]
    q0, p0, dq0, dp0 = (np.zeros((N, LANES)) for _ in range(4))
    for j, lattice in enumerate(lattices):
        block = Excitation(kind="block", site=N // 2, width=L, phases="random", seed=j)
        q0[:, j], p0[:, j], _ = block.state("dnls", lattice, float(L))
        dq0[:, j], dp0[:, j] = initial_deviation(N, j)
    problem = Problem("dnls", lattices, integrator=scheme, dt=DT, tangent=False)
    decades = int(round(np.log10(t_final)))
    steps = [0] + [int(round(10.0**k / DT)) for k in range(0, decades + 1)]
    start = time.process_time()
    record = sample(problem, q0, p0, dq0, dp0, steps)
    cpu = time.process_time() - start
    t = np.asarray(record.times[1:])
    norm = np.asarray(record.norm_error).max(axis=0)[1:]
    energy = np.asarray(record.energy_error).max(axis=0)[1:]
    last = slice(-4, None)  # the last three decades: four samples

    def slope(err):
        return float(np.polyfit(np.log10(t[last]), np.log10(err[last]), 1)[0])

    return {"scheme": scheme, "order": SPLIT_SCHEMES[scheme].order, "cpu_s": round(cpu, 1),
            "t": t.tolist(), "norm_error": norm.tolist(), "energy_error": energy.tolist(),
            "norm_slope_last_3_decades": round(slope(norm), 3), "energy_slope_last_3_decades": round(slope(energy), 3)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--t-final", type=float, default=1e6)
    ap.add_argument("--schemes", nargs="*", default=list(SPLIT_SCHEMES))
    ap.add_argument("--json", help="write the measurements here")
    a = ap.parse_args(argv)
    rows = []
    for scheme in a.schemes:
        row = run(scheme, a.t_final)
        rows.append(row)
        print(f"{scheme:8} order {row['order']}: norm error " + ", ".join(
            f"{e:.1e}" for e in row["norm_error"]) + f" (slope {row['norm_slope_last_3_decades']}); energy error "
            + ", ".join(f"{e:.1e}" for e in row["energy_error"]) + f" (slope {row['energy_slope_last_3_decades']}); "
            f"{row['cpu_s']} CPU-s", flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"N": N, "block": L, "lanes": LANES, "dt": DT, "t_final": a.t_final, "schemes": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
