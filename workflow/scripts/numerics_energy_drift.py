"""Long-time energy drift of one scene at the production step (results/numerics/energy_drift.nc);
progress in the log."""

import argparse
import contextlib
import json
import sys

from chainchaos.io import read_chain, write_netcdf
from chainchaos.numerics.runs import warm_up
from chainchaos.numerics.stability import drift_dataset, energy_drift, progress_printer


def main(chain_file, out, s, integrator):
    chain = read_chain(chain_file)
    warm_up(chain)
    name = f"drift {s['model']} H={s['energy']:g}"
    r = energy_drift(s["model"], chain, float(s["energy"]), integrator, float(s["dt"]), float(s["t_final"]),
                     check_interval=s.get("check_interval", 1.0), samples_per_decade=s.get("samples_per_decade", 10),
                     excited_site=s.get("excited_site", 21), progress=progress_printer(name, 30.0))
    print(f"{name}: {r['n_steps']} steps in {r['seconds']:.1f} s ({1e9 * r['seconds'] / r['n_steps']:.0f} ns/step), "
          f"max |dH/H| = {r['max_abs_error'].max():.3e}, growth exponent {r['growth_exponent']:.3f}",
          file=sys.stderr, flush=True)
    write_netcdf(drift_dataset(r, s["model"], float(s["energy"]), integrator, float(s["dt"]), chain), out)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.input.chain, snakemake.output.data, snakemake.params.settings, snakemake.params.integrator)
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--chain", required=True)
    parser.add_argument("--settings", required=True, help="JSON of the config's numerics.drift block")
    parser.add_argument("--integrator", default="SRKN6b")
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    main(a.chain, a.out, json.loads(a.settings), a.integrator)
