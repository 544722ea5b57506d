"""Run a benchmark and keep what it measured as a machine-readable record in benchmarks/results/.

    python benchmarks/record.py batch_throughput [--note TEXT] [-- OPTIONS of the benchmark]
    python benchmarks/record.py pipeline --note TEXT -- [--configfile F] [--config K=V ...] [--warm] TARGET ...

Writes ``benchmarks/results/<benchmark>-<UTC date>-<commit>.json`` (``-2``, ``-3``, ... for further
runs of the commit that day, so that no run replaces another): the benchmark and the command that
ran it, the commit (and whether the package's sources differed from it), the UTC date, the CPU
(``lscpu``: model name and flags; the vector extensions, Numba's target the engines compile for,
their SIMD width and square root), the load of the machine (``os.getloadavg`` before and after, the
number of CPUs, the share of the CPUs other work kept busy in the second before the start, and a
note: a benchmark on a machine shared with other work measures less than the CPU can do), the
benchmark's parameters and its table (``columns``: the keys of ``rows`` in order, each with a
label; ``rows``: one dict per row).

The documentation's performance page (docs/explanation/performance.md) is generated from every
record in that folder when the site builds (docs/hooks.py), so the figures it shows are those of
the files, with their commit, CPU and date, and no measured time is written by hand.
"""

import argparse
import datetime as dt
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
RESULTS = HERE / "results"


#: What a record says of the commit where the code is not a git checkout (a downloaded archive).
NOT_A_CHECKOUT = "not a git checkout"


def _git(*args: str) -> str:
    """git's answer in the project, or :data:`NOT_A_CHECKOUT` where there is no git or no checkout."""
    try:
        done = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return NOT_A_CHECKOUT
    return done.stdout.strip()


def lscpu() -> dict:
    """``lscpu``'s model name and flags (empty strings where lscpu is missing)."""
    try:
        text = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return {"model_name": "", "flags": ""}
    fields = dict(line.split(":", 1) for line in text.splitlines() if ":" in line)
    fields = {key.strip(): value.strip() for key, value in fields.items()}
    return {"model_name": fields.get("Model name", ""), "flags": fields.get("Flags", "")}


def busy_share(seconds: float = 1.0) -> float | None:
    """The share of all CPUs that were busy during ``seconds`` (``/proc/stat``; None elsewhere).

    Taken before a benchmark starts, it says whether other work shares the machine: the load
    average cannot, as it still holds the previous minute's runs, and after a run holds the
    run's own processes."""
    def ticks():
        fields = [int(x) for x in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
        return sum(fields), fields[3] + fields[4]  # all, idle + iowait

    try:
        total0, idle0 = ticks()
        time.sleep(seconds)
        total1, idle1 = ticks()
    except (OSError, ValueError, IndexError):
        return None
    return round(1 - (idle1 - idle0) / max(total1 - total0, 1), 3)


def batch_throughput(argv: list[str]) -> dict:
    """benchmarks/batch_throughput.py: trajectory-steps per second of both engines, N = 40."""
    sys.path.insert(0, str(HERE))
    import batch_throughput as bench

    rows = bench.main(argv)
    ap = argparse.ArgumentParser(add_help=False)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--dt", type=float, default=5e-3)
    ap.add_argument("--integrator", default="SRKN6b")
    ap.add_argument("--no-tangent", action="store_true")
    known, _ = ap.parse_known_args(argv)
    parameters = {"N": 40, "chain": "alpha = 5, seed 879", "integrator": known.integrator, "dt": known.dt,
                  "steps": known.steps, "repeats": known.repeats, "tangent_map": not known.no_tangent,
                  "timer": "process CPU time, best of the repeats"}
    columns = [("model", "model"), ("lanes", "trajectories B"), ("batch_us", "batch engine: µs per trajectory-step"),
               ("single_us", "single engine: µs per trajectory-step"), ("ratio", "batch / single throughput")]
    table = [{"model": r["model"], "lanes": r["lanes"], "batch_us": 1e6 / r["rate"],
              "single_us": 1e6 / r["single_rate"], "ratio": r["ratio"]} for r in rows]
    return {"title": "Batch engine against the single-trajectory engine (Hertz with gap counting; FPUT)",
            "parameters": parameters, "columns": [{"key": k, "label": label} for k, label in columns], "rows": table}


def pipeline(argv: list[str]) -> dict:
    """A Snakemake run timed from the shell's side, into a fresh results directory, with a cold
    Numba cache unless ``--warm``: its wall time, and its job time per part
    (benchmarks/pipeline_cost.py)."""
    import shutil
    import tempfile

    sys.path.insert(0, str(HERE))
    import pipeline_cost

    ap = argparse.ArgumentParser(prog="record.py pipeline")
    ap.add_argument("--configfile", default=None)
    ap.add_argument("--config", nargs="*", default=[], help="KEY=VALUE overrides (results is set here)")
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--warm", action="store_true", help="keep the Numba cache (default: compile from scratch)")
    ap.add_argument("--keep", default=None, help="write the results to this new directory and keep them "
                    "(default: a scratch directory, deleted)")
    ap.add_argument("targets", nargs="*")
    a = ap.parse_args(argv)
    scratch = Path(tempfile.mkdtemp(prefix="chainchaos-pipeline-"))
    results = Path(a.keep).resolve() if a.keep else scratch / "results"
    if results.exists():
        raise SystemExit(f"record.py pipeline: --keep {a.keep} exists; a timed run starts from no results")
    env = dict(os.environ) if a.warm else {**os.environ, "NUMBA_CACHE_DIR": str(scratch / "numba_cache")}
    cmd = [sys.executable, "-m", "snakemake", "--cores", str(a.cores), "--nolock",
           *(["--configfile", a.configfile] if a.configfile else []),
           "--config", f"results={results}", *a.config, "--", *a.targets]
    start = time.perf_counter()
    done = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, check=False)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit((done.stdout + done.stderr)[-4000:])
    cost = pipeline_cost.main([str(results)])
    shutil.rmtree(scratch, ignore_errors=True)
    shown = [x for x in cmd[2:] if not x.startswith("results=")]
    parameters = {"snakemake": " ".join(shown), "numba_cache": "warm" if a.warm else "cold (compiled in the run)",
                  "cores": a.cores}
    rows = [{"part": "the whole run (wall)", "jobs": cost["jobs"], "seconds": round(wall, 1)},
            *({"part": p["part"], "jobs": p["jobs"], "seconds": round(p["seconds"], 1)} for p in cost["parts"])]
    label = "-".join([*(Path(a.configfile).stem for _ in [0] if a.configfile), *a.targets, *a.config]) or "all"
    return {"label": re.sub(r"[^A-Za-z0-9_.]+", "_", label),
            "title": f"Pipeline run: snakemake {' '.join(a.targets) or 'all'}", "parameters": parameters,
            "columns": [{"key": "part", "label": "part"}, {"key": "jobs", "label": "jobs"},
                        {"key": "seconds", "label": "seconds (wall for the run; job time for a part)"}],
            "rows": rows}


def kept_study(argv: list[str]) -> dict:
    """What a kept study cost (``snakemake --cores 2 keep --config keep=<study>``): per group its
    wall and CPU seconds (the CPU from the group's Snakemake benchmark file, of the rule
    keep_study_group, when it is still in results/, else from the group file) and the CPU time per
    orbit, lattice site and step. Read from the files: nothing is run."""
    import csv

    import xarray as xr

    from chainchaos.studies.study.spec import kept_group_path, load_study

    ap = argparse.ArgumentParser(prog="record.py kept_study")
    ap.add_argument("study")
    ap.add_argument("--benchmarks", default=str(ROOT / "results" / "benchmarks" / "keep_study_group"))
    a = ap.parse_args(argv)
    study = load_study(a.study)
    steps = study.settings.t_final / study.settings.dt
    rows, machines = [], set()
    for g in range(study.n_groups):
        path = kept_group_path(study.name, g)
        with xr.open_dataset(path) as ds:
            attrs, orbits = dict(ds.attrs), ds.sizes["orbit"]
        machines.add(f"{attrs.get('cpu_model', '?')} ({attrs.get('numba_target_cpu', '?')}), {attrs.get('git_commit', '?')[:7]}")
        tsv = Path(a.benchmarks, f"{study.name}-{g:04d}.tsv")
        cpu = float(attrs["cpu_time_s"]) if "cpu_time_s" in attrs else None
        if tsv.exists():
            with open(tsv, newline="") as fh:
                cpu = float(list(csv.DictReader(fh, delimiter="\t"))[-1]["cpu_time"])
        rows.append({"group": g, "orbits": orbits, "wall_seconds": round(float(attrs["wall_time_s"]), 1),
                     "cpu_seconds": None if cpu is None else round(cpu, 1),
                     "ns_per_orbit_site_step": None if cpu is None else round(cpu / (orbits * study.N * steps) * 1e9, 3)})
    known = [r for r in rows if r["cpu_seconds"] is not None]
    rows.append({"group": "total", "orbits": sum(r["orbits"] for r in rows),
                 "wall_seconds": round(sum(r["wall_seconds"] for r in rows), 1),
                 "cpu_seconds": round(sum(r["cpu_seconds"] for r in known), 1) if known else None,
                 "ns_per_orbit_site_step": None})
    spec = study.spec
    return {"label": study.name, "title": f"Kept study {study.name}: {study.title}",
            "parameters": {"models": study.models, "N": study.N, "realizations": study.realizations,
                           "integrator": spec["integration"]["integrator"], "dt": spec["integration"]["dt"],
                           "t_final": spec["integration"]["t_final"], "observables": study.observables,
                           "machines_and_commits": sorted(machines)},
            "columns": [{"key": "group", "label": "group"}, {"key": "orbits", "label": "orbits"},
                        {"key": "wall_seconds", "label": "wall s"}, {"key": "cpu_seconds", "label": "CPU s"},
                        {"key": "ns_per_orbit_site_step", "label": "CPU ns per orbit, site and step (with the tangent map)"}],
            "rows": rows}


def kg_kernel(argv: list[str]) -> dict:
    """benchmarks/kg_kernel.py, one of its parts (``--parts``, one per record): ns per site and
    step against the C loop, peak memory at N = 4096, or the spreading run's cost against N."""
    sys.path.insert(0, str(HERE))
    import kg_kernel as bench

    measured = bench.main(argv)
    if len(measured) != 1:
        raise SystemExit("record.py kg_kernel: name one part, e.g. -- --parts per_site")
    (part, rows), = measured.items()
    titles = {"per_site": "Klein-Gordon kernels: ns per site and step against a C loop",
              "memory": "Klein-Gordon: peak memory of 64 realizations",
              "spreading": "Klein-Gordon spreading run: cost against N, whole chain and growing window",
              "square": "Klein-Gordon: the square lattice's engines beside the chain's at as many sites"}
    return {"label": part, "title": titles[part], "parameters": {"argv": argv},
            "columns": [{"key": k, "label": k} for k in rows[0]], "rows": rows}


def dnls_norm_table(schemes: list[dict], t_final: float) -> dict:
    """The table of benchmarks/dnls_norm_error.py's measurements (its ``run`` per scheme)."""
    rows = []
    for r in schemes:
        at = {t: (n, e) for t, n, e in zip(r["t"], r["norm_error"], r["energy_error"])}
        rows.append({"scheme": r["scheme"], "order": r["order"], "norm_1": at[1.0][0], "norm_1e3": at[1e3][0],
                     "norm_end": r["norm_error"][-1], "norm_exponent": r["norm_slope_last_3_decades"],
                     "energy_1": at[1.0][1], "energy_1e3": at[1e3][1], "energy_end": r["energy_error"][-1],
                     "energy_exponent": r["energy_slope_last_3_decades"], "cpu_s": r["cpu_s"]})
    labels = {"scheme": "scheme", "order": "order", "norm_1": "norm error t = 1", "norm_1e3": "t = 1e3",
              "norm_end": f"t = {t_final:g}", "norm_exponent": "growth exponent (last 3 decades)",
              "energy_1": "energy error t = 1", "energy_1e3": "t = 1e3", "energy_end": f"t = {t_final:g}",
              "energy_exponent": "growth exponent", "cpu_s": "CPU s"}
    return {"columns": [{"key": k, "label": v} for k, v in labels.items()], "rows": rows}


def dnls_norm_error(argv: list[str]) -> dict:
    """benchmarks/dnls_norm_error.py: how the DNLS norm and energy errors grow, per split scheme."""
    sys.path.insert(0, str(HERE))
    import dnls_norm_error as bench

    ap = argparse.ArgumentParser(prog="record.py dnls_norm_error")
    ap.add_argument("--t-final", type=float, default=1e6)
    ap.add_argument("--schemes", nargs="*", default=None)
    a = ap.parse_args(argv)
    from chainchaos import SPLIT_SCHEMES

    measured = [bench.run(s, a.t_final) for s in (a.schemes or list(SPLIT_SCHEMES))]
    return {"title": "DNLS: growth of the norm and energy errors per split scheme",
            "parameters": {"N": bench.N, "block": bench.L, "lanes": bench.LANES, "dt": bench.DT, "t_final": a.t_final},
            **dnls_norm_table(measured, a.t_final)}


def window_2d(argv: list[str]) -> dict:
    """benchmarks/window_2d.py: the growing window's cost on square DNLS or KG lattices of growing size."""
    sys.path.insert(0, str(HERE))
    import window_2d as bench

    return bench.main(argv)


def work_precision_2d(argv: list[str]) -> dict:
    """benchmarks/work_precision_2d.py: error against CPU time and extreme cases on square lattices."""
    sys.path.insert(0, str(HERE))
    import work_precision_2d as bench

    return bench.main(argv)


BENCHMARKS = {"batch_throughput": batch_throughput, "pipeline": pipeline, "kept_study": kept_study,
              "kg_kernel": kg_kernel, "dnls_norm_error": dnls_norm_error, "window_2d": window_2d,
              "work_precision_2d": work_precision_2d}


def record(name: str, argv: list[str], note: str = "") -> Path:
    """Run benchmark ``name`` with ``argv`` and write its record; return the record's path."""
    from chainchaos.kernels.simd import LANES
    from chainchaos.records.provenance import (
        cpu_vector_extensions,
        numba_target_cpu,
    )

    commit = _git("rev-parse", "HEAD")  # the code that runs: a commit made during a long run is not it
    status = _git("status", "--porcelain", "--", "src", f"benchmarks/{name}.py")
    sources_differ = None if commit == NOT_A_CHECKOUT else bool(status)
    busy_before = busy_share()
    load_before = os.getloadavg()
    started = dt.datetime.now(dt.UTC)
    measured = BENCHMARKS[name](argv)
    load_after = os.getloadavg()
    out = {
        "benchmark": name,
        "command": " ".join(["python", "benchmarks/record.py", name, "--", *argv]),
        "commit": commit,
        "sources_differ_from_commit": sources_differ,
        "date": started.replace(microsecond=0).isoformat(),
        "cpu": {**lscpu(), "vector_extensions": cpu_vector_extensions(), "numba_target": numba_target_cpu(),
                "simd_width_doubles": LANES, "cpus": os.cpu_count()},
        "load_average_1min": {"before": round(load_before[0], 2), "after": round(load_after[0], 2)},
        "busy_share_before": busy_before,
        # other work at the start (a quarter of the CPUs or more); the load average after the run
        # is the run's own
        "loaded_machine": busy_before is None or busy_before >= 0.25,
        "note": note,
        **measured,
    }
    RESULTS.mkdir(exist_ok=True)
    label = measured.pop("label", "")
    stem = f"{name}{'-' + label if label else ''}-{started:%Y-%m-%d}-{'nogit' if commit == NOT_A_CHECKOUT else commit[:7]}"
    path = RESULTS / f"{stem}.json"
    runs = 1
    while path.exists():
        runs += 1
        path = RESULTS / f"{stem}-{runs}.json"
    path.write_text(json.dumps(out, indent=1, ensure_ascii=False) + "\n")
    return path


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("benchmark", choices=sorted(BENCHMARKS))
    ap.add_argument("--note", default="", help="what a reader should know about the run (e.g. the machine was loaded)")
    argv = list(sys.argv[1:] if argv is None else argv)
    ours, theirs = (argv[:argv.index("--")], argv[argv.index("--") + 1:]) if "--" in argv else (argv, [])
    a = ap.parse_args(ours)
    print(f"wrote {record(a.benchmark, theirs, a.note)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
