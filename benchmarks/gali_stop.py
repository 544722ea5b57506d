"""What deciding chaos by GALI_k beside Λ costs, and what stopping GALI's vectors once decided saves.

    python benchmarks/gali_stop.py [--lanes 8] [--dt 1e-2] [--t-final 1e5] [--gali 4] [--scenes ...]

Every scene of the paper's statements (``paper.statements.statement_scenes``) runs as the ensemble
verdicts run it (``orbits.integrate``: lane 0 the scene's orbit, lanes j >= 1 perturbed; here at
the search's dt = 0.01), three times: with Λ's one deviation vector only; with GALI_k's k - 1
vectors more to the end; and with them stopped once the lane's GALI_k is below the claims'
threshold (``gali_stop``; the work is saved in a SIMD block whose lanes have all crossed). Printed
per scene: CPU seconds of each (time.process_time, after a warm-up run that compiles the kernels),
the ratios to Λ alone, and how many lanes crossed. The records of the runs with and without the
stop are compared: the orbits, Λ and every ln GALI_k up to each lane's crossing must be identical
(checked, not timed). The first line names the machine.
"""

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import yaml

from chainchaos import random_chain
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.statements import statement_scenes
from chainchaos.records.provenance import machine_line
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
from chainchaos.studies.search.archive import chosen_seed

ROOT = Path(__file__).resolve().parents[1]


def timed(orbits, settings, stop):
    t0 = time.process_time()
    t, runs = integrate(orbits, settings, gali_stop=stop)
    return time.process_time() - t0, t, runs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lanes", type=int, default=8)
    ap.add_argument("--dt", type=float, default=1e-2)
    ap.add_argument("--t-final", type=float, default=1e5)
    ap.add_argument("--gali", type=int, default=4)
    ap.add_argument("--scenes", nargs="*", default=None, help="default: every scene of the statements")
    a = ap.parse_args(argv)
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    archive = ROOT / config["search"]["archive"]
    seed = chosen_seed(archive) if archive.exists() else 879
    chain = random_chain(seed, float(config["chain"]["alpha"]), int(config["chain"]["N"]))
    site = int(config["simulation"]["excited_site"])
    stop = float(np.log(Criteria.from_config(config["claims"]).gali_threshold))
    base = OrbitSettings.from_config({**config["verdicts"]["settings"], "dt": a.dt, "t_final": a.t_final,
                                      "alignment": False})
    gali = replace(base, alignment=True, gali_order=a.gali)
    scenes = statement_scenes()
    names = a.scenes or list(scenes)
    warm = [Orbit(model=scenes[names[0]].model, energy=scenes[names[0]].energy, chain=chain, site=site, lane=0)]
    for s in (base, gali):
        integrate(warm, replace(s, t_final=10.0), gali_stop=stop if s.alignment else None)

    print(machine_line())
    print(f"chain seed {seed}; {a.lanes} orbits per scene, dt = {a.dt:g} to t = {a.t_final:g}; GALI_{a.gali} "
          f"stopped below exp({stop:.2f})")
    print("| scene | CPU s: Λ only | + GALI to the end | + GALI, stopped | ratios to Λ | lanes crossed |")
    print("|---|---:|---:|---:|---|---:|")
    totals = np.zeros(3)
    for name in names:
        sc = scenes[name]
        orbits = [Orbit(model=sc.model, energy=sc.energy, chain=chain, site=site, lane=lane) for lane in range(a.lanes)]
        c0, _, _ = timed(orbits, base, None)
        c1, t, full = timed(orbits, gali, None)
        c2, _, stopped = timed(orbits, gali, stop)
        crossed = 0
        for f, s in zip(full, stopped):
            assert np.array_equal(f["log_growth"], s["log_growth"]) and np.array_equal(f["participation"], s["participation"])
            below = np.flatnonzero(f["log_gali"] < stop)
            end = below[0] + 1 if below.size else t.size
            crossed += bool(below.size)
            assert np.array_equal(f["log_gali"][:end], s["log_gali"][:end]), name
        totals += (c0, c1, c2)
        print(f"| {name} | {c0:.1f} | {c1:.1f} | {c2:.1f} | {c1 / c0:.2f} / {c2 / c0:.2f} | {crossed} of {a.lanes} |")
    print(f"| all | {totals[0]:.1f} | {totals[1]:.1f} | {totals[2]:.1f} | {totals[1] / totals[0]:.2f} / "
          f"{totals[2] / totals[0]:.2f} | |")


if __name__ == "__main__":
    main()
