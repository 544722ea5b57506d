"""What each part of a pipeline run cost, and on which machine: from the run's own records.

    python benchmarks/pipeline_cost.py [RESULTS] [--json out.json]

Every rule has a ``benchmark:`` file (``RESULTS/benchmarks/<rule>/<job>.tsv``, written by Snakemake
when the job ends); its ``s`` column is the job's wall time. With one job per core (``--cores 2``,
single-threaded jobs) that is the core time the job took, so the sum over a part is what the part
costs (Snakemake's own ``cpu_time`` column is sampled and misses short jobs). The run's span is
from the first job's start (end time of its file minus its ``s``) to the last job's end: the wall
time of the run without Snakemake's start-up. The machine is the one that wrote the results (the
provenance of a scene file: CPU model, vector extensions, Numba's target), which need not be the
one running this script.

Prints a Markdown table: per part, its jobs, their summed and longest seconds, and its share.
"""

import argparse
import csv
import json
import re
from pathlib import Path

import xarray as xr

from chainchaos.records.provenance import machine_line

#: Parts of the pipeline, by the rules whose jobs they are, matched against "<rule>/<job>" (first
#: match wins), in table order. Every ensemble's orbits run in the jobs of its study (study_group):
#: the scans', the search's stages' (<search>-filter-<model>, <search>-score-<model>) and the
#: verdicts' (verdicts_<model>).
PARTS = (
    ("kernel compilation", r"compile_kernels"),
    ("realization search: linear rule and filter",
     r"search_(seeds|candidates|filter)|study_group/search(_full)?-filter-"),
    ("realization search: scores", r"search_merge|select_chain|study_group/search(_full)?-score-"),
    ("scenes", r"simulate_scene"),
    ("ensemble verdicts", r"ensemble_verdicts|study_group/verdicts_"),
    ("energy scan", r"study_group/energy_scan-|merge_energy_scan"),
    ("disorder statistics", r"study_group/disorder(_full)?-|merge_disorder"),
    ("studies", r"study_|plot_study"),
    ("Lyapunov spectra", r"lyapunov_spectrum"),
    ("disorder ensemble of Fig. 1(a)", r"compute_ensemble"),
    ("long-time energy drift", r"numerics_energy_drift"),
    ("other numerics (work-precision, stability, step advice, Taylor sign)", r"numerics_(?!plot)"),
    ("figures", r"plot_|numerics_plot_"),
    ("claims, thresholds and manuscript", r"evaluate_claims|scan_thresholds|build_manuscript"),
)


def jobs(results: Path) -> list[dict]:
    """One record per benchmark file: rule, job, wall seconds, start and end (epoch seconds)."""
    out = []
    for path in sorted((results / "benchmarks").glob("*/*.tsv")):
        rows = list(csv.DictReader(path.open(), delimiter="\t"))
        seconds = float(rows[-1]["s"])
        end = path.stat().st_mtime
        out.append({"rule": path.parent.name, "job": path.stem, "s": seconds, "start": end - seconds, "end": end})
    return out


def part_of(rule: str, job: str = "") -> str:
    for name, pattern in PARTS:
        if re.fullmatch(f"(?:{pattern}).*", f"{rule}/{job}"):
            return name
    return "other"


def machine(results: Path) -> str:
    """The machine that wrote the results, from the provenance of the first scene file."""
    for path in sorted((results / "scenes").glob("*.nc")):
        with xr.open_dataset(path) as ds:
            return machine_line(ds.attrs)
    return "unknown (no scene file)"


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", nargs="?", default="results", type=Path)
    ap.add_argument("--json", help="also write the table here")
    a = ap.parse_args(argv)
    records = jobs(a.results)
    if not records:
        raise SystemExit(f"no benchmark files under {a.results / 'benchmarks'}: run the pipeline first")
    span = max(r["end"] for r in records) - min(r["start"] for r in records)
    total = sum(r["s"] for r in records)
    parts = {name: [] for name, _ in PARTS}
    for r in records:
        parts.setdefault(part_of(r["rule"], r["job"]), []).append(r)
    machine_of_results = machine(a.results)
    print(machine_of_results)
    print(f"{len(records)} jobs, {total / 60:.1f} min of job time, span {span / 60:.1f} min "
          f"(first job start to last job end; {total / span:.2f} jobs running on average)\n")
    print("| part | jobs | job time, min | longest job, s | share |")
    print("|---|---:|---:|---:|---:|")
    table = []
    for name, rs in parts.items():
        if not rs:
            continue
        s = sum(r["s"] for r in rs)
        table.append({"part": name, "jobs": len(rs), "seconds": s, "longest": max(r["s"] for r in rs)})
        print(f"| {name} | {len(rs)} | {s / 60:.1f} | {max(r['s'] for r in rs):.0f} | {s / total:.0%} |")
    summary = {"machine": machine_of_results, "jobs": len(records), "job_seconds": total, "span_seconds": span,
               "parts": table}
    if a.json:
        Path(a.json).write_text(json.dumps(summary, indent=1))
    return summary


if __name__ == "__main__":
    main()
