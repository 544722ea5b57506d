"""Compare two energy scans of the same chain run at different steps: which orbits' verdicts differ.

    python benchmarks/scan_step.py REFERENCE.nc OTHER.nc

Both are ``results/scan/energy_scan.nc`` files (e.g. the default step and a finer one: run ``all``'s
scan into another results directory with ``--config results=<dir>`` and a config layer that sets
``scan.energy_scan.dt``). Prints each file's step and largest energy error, then per model and
criterion (delocalized, chaotic by Λ, chaotic by GALI_k) the energies whose verdict differs, and
both files' threshold tables (``chainchaos.paper.thresholds``). The claims table reads the
scan only through those threshold statements; re-evaluate it on each scan to see whether a claim's
verdict moves.
"""

import sys

import numpy as np
import xarray as xr

from chainchaos.paper.thresholds import thresholds_table

VERDICTS = ("delocalized", "chaotic", "chaotic_gali")


def main(reference: str, other: str) -> None:
    a, b = xr.load_dataset(reference), xr.load_dataset(other)
    if not np.array_equal(a.energy.values, b.energy.values):
        sys.exit("the two scans have different energy grids")
    for name, ds in (("reference", a), ("other", b)):
        print(f"{name}: dt = {ds.attrs['dt']:g}, largest energy error "
              + ", ".join(f"{m} {float(ds.energy_error_max.sel(model=m).max()):.2g}" for m in ds.model.values))
    for m in a.model.values:
        for key in (k for k in VERDICTS if k in a and k in b):
            x, y = a[key].sel(model=m).values, b[key].sel(model=m).values
            differ = np.flatnonzero(x != y)
            where = ", ".join(f"H = {a.energy.values[i]:.3g} ({int(x[i])} -> {int(y[i])})" for i in differ)
            print(f"{m} {key}: {len(differ)} of {len(x)} differ" + (f": {where}" if where else ""))
    for name, ds in (("reference", a), ("other", b)):
        print(f"thresholds, {name} (model, criterion, first H, all H above):")
        for r in thresholds_table(ds):
            print(f"  {r['model']} {r['criterion']}: {r['first_energy']:.3g} {r['always_above']:.3g}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
