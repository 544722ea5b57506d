"""When each chaos indicator decides, on the paper's ten scenes: Λ(t) against SALI and GALI_k.

    python benchmarks/time_to_verdict.py [--seed S] [--lanes 8] [--dt 5e-3] [--t-final 1e5] [--gali 4]

Every scene of the paper's statements (``paper.statements.statement_scenes``) runs as the ensemble
verdicts run it (config/config.yaml ``verdicts``: lane 0 the scene's orbit, lanes j >= 1 with u0
perturbed at 1e-9 and their own deviation vectors), with ``--gali`` - 1 deviation vectors beside the
mLCE vector, each only normalised. Per orbit:

- Λ: chaotic at the end by the claims' criterion (``reductions.is_chaotic``: slope of Λ over the
  last decade above -0.5 and the vector grown more than a regular orbit can), decided at the end
  of the first window from which it holds to the end of the run (``reductions.chaos_onset``
  gives that window's centre; the decision needs the window's end);
- SALI (of the mLCE vector and the second, Skokos 2001) and GALI_k (Skokos, Bountis &
  Antonopoulos 2007): chaotic once the indicator falls below ``--threshold`` (1e-8, the usual
  choice for SALI), decided at the first sample below it; an orbit above it at the end is regular
  by that indicator. On an N-torus GALI_k stays of order one for k <= N, so a regular orbit does
  not cross it.

Printed per scene: the fraction of orbits chaotic by each indicator at the end, the median time at
which each decides "chaotic" over the orbits it calls chaotic, and the orbits on which Λ and the
alignment indicator disagree. A regular verdict is reached by no indicator before the run ends.
The CPU time of the run is printed with the machine line: it is not a timing benchmark of the
indicators (``benchmarks/deviation_vectors.py`` is).
"""

import argparse
import time
from pathlib import Path

import numpy as np
import yaml

from chainchaos import random_chain
from chainchaos.observe.reductions import chaos_onset, gali_crossing, is_chaotic
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.statements import statement_scenes
from chainchaos.records.provenance import machine_line
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
from chainchaos.studies.search.archive import chosen_seed as archive_seed

ROOT = Path(__file__).resolve().parents[1]


def chosen_seed() -> int:
    """The archived full search's chosen seed, else the configuration's pinned one, else 879."""
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    archive = ROOT / config["search"]["archive"]
    if archive.exists():
        return archive_seed(archive)
    return int(config["search"].get("pinned_seed") or 879)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=None, help="the chain's seed (default: the chosen chain)")
    ap.add_argument("--lanes", type=int, default=8)
    ap.add_argument("--dt", type=float, default=None, help="default: the verdicts' step")
    ap.add_argument("--t-final", type=float, default=None, help="default: the verdicts' t_final")
    ap.add_argument("--gali", type=int, default=4, help="k of GALI_k (SALI is read from its first two vectors)")
    ap.add_argument("--threshold", type=float, default=1e-8)
    a = ap.parse_args(argv)
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    block = dict(config["verdicts"]["settings"], gali_order=a.gali, alignment=True)
    block.update({k: v for k, v in (("dt", a.dt), ("t_final", a.t_final)) if v is not None})
    settings = OrbitSettings.from_config(block)
    seed = chosen_seed() if a.seed is None else a.seed
    chain = random_chain(seed, float(config["chain"]["alpha"]), int(config["chain"]["N"]))
    site = int(config["simulation"]["excited_site"])
    c = Criteria.from_config(config["claims"])

    print(machine_line())
    print(f"chain seed {seed}; {a.lanes} orbits per scene, SRKN6b dt = {settings.dt:g} to t = {settings.t_final:g}; "
          f"SALI and GALI_{a.gali} chaotic below {a.threshold:g}; Λ by slope > {c.chaos_slope} over "
          f"{c.chaos_window_decades} decade(s)")
    print("| scene | chaotic: Λ / SALI / GALI | median time to 'chaotic': Λ / SALI / GALI | Λ and SALI disagree "
          "| CPU s |")
    print("|---|---|---|---|---:|")
    for name, scene in statement_scenes().items():
        orbits = [Orbit(model=scene.model, energy=scene.energy, chain=chain, site=site, lane=lane)
                  for lane in range(a.lanes)]
        t0 = time.process_time()
        t, runs = integrate(orbits, settings)
        cpu = time.process_time() - t0
        if not all(r["valid"] for r in runs):
            print(f"| {name} | an orbit has no initial state or left the energy bound | | | |")
            continue
        lam, lam_t, sali, sali_t, gali, gali_t = ([] for _ in range(6))
        for r in runs:
            g = r["log_growth"]
            lam.append(is_chaotic(t, g, c.chaos_slope, c.chaos_growth_margin, c.chaos_window_decades))
            onset = chaos_onset(t, g, c.chaos_slope, c.chaos_growth_margin, c.chaos_window_decades)
            lam_t.append(onset * 10.0 ** (c.chaos_window_decades / 2))  # the window's end: when it is known
            with np.errstate(divide="ignore"):
                sali_t.append(gali_crossing(t, np.log(r["sali"]), a.threshold))  # SALI ~ GALI_2
            gali_t.append(gali_crossing(t, r["log_gali"], a.threshold))
            sali.append(np.isfinite(sali_t[-1]))
            gali.append(np.isfinite(gali_t[-1]))

        def median(times):
            times = np.asarray(times)
            return f"{np.median(times[np.isfinite(times)]):.3g}" if np.isfinite(times).any() else "--"

        disagree = int(np.sum(np.asarray(lam) != np.asarray(sali)))
        print(f"| {name} | {np.mean(lam):.2f} / {np.mean(sali):.2f} / {np.mean(gali):.2f} | "
              f"{median(lam_t)} / {median(sali_t)} / {median(gali_t)} | {disagree} of {a.lanes} | {cpu:.0f} |")


if __name__ == "__main__":
    main()
