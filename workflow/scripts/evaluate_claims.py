"""Measure the paper's claims on the results: claims.csv, claims_table.tex, claims_notes.tex and
macros.tex (every number the manuscript prints, as \\cc{key})."""

import argparse
import contextlib
import json
from pathlib import Path

from chainchaos.claims import evaluate as main

if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(dict(snakemake.input.items()), dict(snakemake.output.items()), dict(snakemake.params.items()))
else:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("results", help="results directory (scenes/, chain/, ensemble/, scan/)")
    parser.add_argument("--out", required=True, help="output directory")
    parser.add_argument("--params", default="{}", help="JSON: {claims: {...}, simulation: {...}}")
    a = parser.parse_args()
    root = Path(a.results)
    files = {"chain": root / "chain" / "chain.nc", "ensemble": root / "ensemble" / "participation_stats.nc",
             "energy_scan": root / "scan" / "energy_scan.nc", "disorder": root / "scan" / "disorder_statistics.nc",
             "search": root / "search" / "search.nc"}
    files.update({f"verdict_{p.stem}": p for p in sorted((root / "verdicts").glob("*.nc"))})
    files.update({p.stem: p for p in sorted((root / "scenes").glob("*.nc"))})
    out = Path(a.out)
    main(files, {k: out / f for k, f in (("csv", "claims.csv"), ("table", "claims_table.tex"),
                                         ("notes", "claims_notes.tex"), ("scenes", "scenes_table.tex"),
                                         ("macros", "macros.tex"), ("search", "search_table.tex"))},
         json.loads(a.params))
