"""The full realization search at a small scale: its stages run as chunks, a killed run resumes
without redoing a finished chunk, and `snakemake keep --config keep=search_full` writes the archive
that `all` pins."""

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from chainchaos.studies.search.archive import STAGES, chosen_seed
from records.test_compliance import cf_problems

ROOT = Path(__file__).resolve().parents[3]

# 2 chunks of seeds, every qualifying chain filtered 2 to a job, 2 scored on 2 lanes (quick times).
SMALL = """search:
  archive: {archive}
search_full:
  n_seeds: 1500
  seeds_per_job: 750
  candidates:
  candidates_per_job: 2
  survivors: 2
  lanes: 2
  filter_t_final: 100.0
"""


def _snakemake(config: Path, results: Path, *args, keep: bool = False):
    """A run with the small config; ``keep``: the run that makes the kept full search."""
    return [sys.executable, "-m", "snakemake", "--cores", "1", "--nolock", *args, "--configfile",
            "config/quick.yaml", str(config), "--config", f"results={results}",
            *(["keep=search_full"] if keep else [])]


def _finished(results: Path) -> dict:
    """Every stage file written so far (its own and its studies' groups), with its modification
    time and inode."""
    files = [*(results / "search_full").rglob("*.nc"), *(results / "studies").glob("search_full-*/groups/*.nc")]
    return {p: (p.stat().st_mtime_ns, p.stat().st_ino) for p in sorted(files)}


def _incomplete(dry_run: str) -> set[Path]:
    """The outputs a dry run plans to redo because Snakemake did not record their jobs done."""
    jobs = re.findall(r"output: (.*)\n(?:.*\n)*?\s+reason: (.*)", dry_run)
    return {Path(out) for outputs, reason in jobs if "ncomplete" in reason for out in outputs.split(", ")}


def _filter_groups(paths) -> list[Path]:
    """The groups of the full search's filter studies (search_full-filter-<model>) among ``paths``."""
    return [p for p in paths if p.parent.parent.name.startswith("search_full-filter-")]


@pytest.mark.pipeline
def test_a_killed_full_search_resumes_without_redoing_a_finished_chunk(tmp_path):
    results, archive = tmp_path / "results", tmp_path / "data" / "search_full.nc"
    config = tmp_path / "small.yaml"
    config.write_text(SMALL.format(archive=archive))
    run = subprocess.Popen(_snakemake(config, results, "keep", keep=True), cwd=ROOT, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + 600
    while len(_filter_groups(_finished(results))) < 2 and time.monotonic() < deadline:
        assert run.poll() is None, "the search ended before it could be killed"
        time.sleep(0.2)
    os.killpg(run.pid, signal.SIGKILL)  # no clean shutdown: as a node failure or a killed session
    run.wait()
    before = _finished(results)
    assert len(_filter_groups(before)) >= 2 and not archive.exists()
    # the job killed may have written its file before Snakemake recorded it done: that one is redone
    dry = subprocess.run(_snakemake(config, results, "keep", "-n", "--rerun-incomplete", keep=True), cwd=ROOT,
                         capture_output=True, text=True, timeout=600)
    assert dry.returncode == 0, dry.stdout[-4000:]
    incomplete = _incomplete(dry.stdout)
    assert len(incomplete & set(before)) <= 1  # one job at a time (--cores 1)
    finished = {p: v for p, v in before.items() if p not in incomplete}
    assert len(_filter_groups(finished)) >= 1

    done = subprocess.run(_snakemake(config, results, "keep", "--rerun-incomplete", keep=True), cwd=ROOT,
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, (done.stdout + done.stderr)[-4000:]
    after = _finished(results)
    assert {p: after[p] for p in finished} == finished  # no finished chunk was rewritten
    assert len(after) > len(before)

    # the archive: every qualifying chain filtered, the survivors scored, the cost of every stage
    ds = xr.load_dataset(archive)
    candidates = xr.load_dataset(results / "search_full" / "candidates.nc")
    assert ds.sizes["candidate"] == candidates.sizes["candidate"] == ds.attrs["n_qualifying"]
    assert ds.attrs["seeds_scanned"] == 1500 and int(ds["scored"].sum()) == 2
    filters = _filter_groups(after)
    for model in ("hertz", "fput"):  # every candidate ran stage 1, once per scene of each model
        groups = [xr.load_dataset(f) for f in filters if f.parent.parent.name.endswith(f"-{model}")]
        ran = np.concatenate([g["realization"].values[g["energy_index"].values == 0] for g in groups])
        assert sorted(ran) == list(range(ds.sizes["candidate"])), model
    for stage in STAGES:
        assert ds.attrs[f"cost_{stage}_jobs"] >= 1 and ds.attrs[f"cost_{stage}_cpu_seconds"] > 0, stage
    assert ds.attrs["cost_search_seeds_jobs"] == 2
    n_filter, n_score = 2 * -(-candidates.sizes["candidate"] // 2), 2 * 2  # per model: groups of 2 chains; 2 survivors
    resumed = n_filter - len(_filter_groups(finished))
    # a killed job may leave no benchmark
    assert resumed + n_score <= ds.attrs["cost_study_group_jobs"] <= n_filter + n_score
    assert ds.attrs["stage_cpus"] and ds.attrs["stage_commits"]
    # the files a pinned run does not write pass the CF checker here (tests/records/test_compliance.py)
    assert cf_problems(archive) == [] and cf_problems(results / "search_full" / "filter.nc") == []
    assert cf_problems(filters[0]) == []

    # `all` pins the archive's chain (its chosen seed named in the config, which the archive's check
    # compares): its search's candidates are that chain alone, and no filter runs
    pinned = tmp_path / "all"
    config.write_text(SMALL.format(archive=archive).replace("search:\n", f"search:\n  pinned_seed: {chosen_seed(archive)}\n"))
    dry = subprocess.run(_snakemake(config, pinned, "-n"), cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert dry.returncode == 0, dry.stdout[-4000:]
    planned = dry.stdout.split("Job stats:")[-1]
    assert "search_filter" not in planned and "/studies/search-score-hertz/groups/" in dry.stdout
    stage0 = subprocess.run(_snakemake(config, pinned, str(pinned / "search" / "candidates.nc")), cwd=ROOT,
                            capture_output=True, text=True, timeout=600)
    assert stage0.returncode == 0, (stage0.stdout + stage0.stderr)[-4000:]
    found = xr.load_dataset(pinned / "search" / "candidates.nc")
    assert found.attrs["pinned"] == 1 and list(found["seed"].values) == [chosen_seed(archive)]
