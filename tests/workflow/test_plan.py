"""The workflow's decisions (chainchaos.workflow.plan), without Snakemake; and what they mean for
the workflow: the same jobs at every SIMD width, no kept result remade on the way to a target, a
run of a second clone using that clone's code."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import netCDF4
import pytest
import yaml

from chainchaos.errors import KeptFileError
from chainchaos.paper import panels
from chainchaos.records import kept
from chainchaos.run.scenes import SceneParameters
from chainchaos.workflow import plan

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())


def config(**overrides):
    return {**CONFIG, **overrides}


# ---- scenes: one job each, from the config --------------------------------------------------


def test_scene_run_takes_the_simulation_block_and_the_scene_override():
    overridden = config(scenes={"hertz_H1.8": {"dt": 2.5e-4}})
    for name, scene in panels.scenes().items():
        run = SceneParameters(**plan.scene_run(overridden, name))
        assert (run.name, run.model, run.energy) == (name, scene.model, scene.energy)
        assert run.dt == (2.5e-4 if name == "hertz_H1.8" else CONFIG["simulation"]["dt"])
        assert set(panels.scene_observables(name)) <= set(run.observables)


def job_list(lanes: int) -> list[str]:
    """The jobs (rule, output) of a dry run of `all` at a chosen SIMD width."""
    done = subprocess.run([sys.executable, "-m", "snakemake", "-n", "--nolock", "all"], cwd=ROOT, text=True,
                          capture_output=True, env={**os.environ, "CHAINCHAOS_SIMD_LANES": str(lanes)}, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    jobs = re.findall(r"^(?:local)?rule (\w+):\n(?:    .*\n)*?    output: (.*)$", done.stdout, re.M)
    assert len(jobs) > 50
    return sorted(map(str, jobs))


@pytest.mark.pipeline
def test_the_same_config_gives_the_same_jobs_at_4_and_8_lanes():
    assert job_list(4) == job_list(8)


# ---- kept results --------------------------------------------------------------------------------


def kept_file(path: Path, settings: dict, version: int = 1) -> Path:
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("candidate", 3)
        nc.createVariable("x", "f8", ("candidate",))[:] = [1.0, 2.0, 3.0]
        nc.setncatts({**kept.kept_attrs(settings, version), "chosen_seed": 879})
    return path


def test_a_chosen_kept_file_that_does_not_match_stops_with_one_line_and_the_two_ways_out(tmp_path):
    path = kept_file(tmp_path / "k.nc", {"chain": {"N": 40}, "t": 1.0})
    kept.seal(path)
    used = kept.check_kept(path, {"chain": {"N": 40}, "t": 1}, 1, "remake", "compute")
    assert used[kept.DIGEST_ATTR] == kept.digest({"chain": {"N": 40}, "t": 1})
    with pytest.raises(KeptFileError) as error:
        kept.check_kept(path, {"chain": {"N": 41}, "t": 1.0}, 1, "keep it", "empty config x")
    assert str(error.value) == (f"kept file {path}: chain.N is 40 in the file, 41 in this run; remake it with "
                                "'keep it', or empty config x")
    assert kept.check_kept(path, {"chain": {"N": 41}, "t": 1.0}, 1, "remake", "compute", keys=("t",))
    with pytest.raises(KeptFileError, match="result_version is 1 in the file, 2 in this code; remake it"):
        kept.check_kept(path, {"chain": {"N": 40}, "t": 1.0}, 2, "remake", "compute")
    with pytest.raises(KeptFileError, match=r"absent\.nc is absent; remake it with 'remake', or compute$"):
        kept.check_kept(tmp_path / "absent.nc", {}, 1, "remake", "compute")


def test_a_chosen_kept_file_that_cannot_be_read_stops_its_check(tmp_path):
    path = kept_file(tmp_path / "k.nc", {"a": 1})
    path.write_bytes(path.read_bytes()[:200])
    with pytest.raises(KeptFileError, match=f"kept file {re.escape(str(path))} cannot be read .*git checkout -- "):
        kept.check_kept(path, {"a": 1}, 1, "snakemake --cores 2 keep --config keep=x", "compute")


def test_keep_names_a_kept_product_or_a_study():
    assert plan.kept_product(None, ["a"]) is None and plan.kept_product("", ["a"]) is None
    assert plan.kept_product("search_full", []) == "search_full"
    assert plan.kept_product("kg", ["kg"]) == "kg"
    with pytest.raises(ValueError, match=r"config keep is 'serch_full': one of search_full, search_rejudge, "
                                         r"disorder_full or a study of studies/ \(kg\)"):
        plan.kept_product("serch_full", ["kg"])


def test_the_config_alone_says_which_kept_results_a_run_uses():
    """The paper's config uses the kept full search (its chosen seed pinned in the config, which
    the archive's check compares) and the kept disorder statistics; an empty key computes."""
    assert plan.archive_path("search_full", CONFIG) == "data/search/search_full.nc"
    assert plan.archive_path("disorder_full", CONFIG) == "data/disorder/disorder_full.nc"
    plans = plan.search_plans(CONFIG)
    assert plans["search"].pinned and plans["search"].pinned_seed == CONFIG["search"]["pinned_seed"]
    assert not plans["search_full"].pinned
    check = plan.archive_check("search_full", CONFIG)
    assert check["attrs"] == {"chosen_seed": ["search.pinned_seed", CONFIG["search"]["pinned_seed"]]}
    assert check["keys"] is None and "empty config search.archive" in check["compute"]
    quick = {**CONFIG, "search": {**CONFIG["search"], "reuse_archive_chain": True}}
    assert plan.archive_check("search_full", quick)["keys"] == ["chain"]
    empty = {**CONFIG, "scan": {**CONFIG["scan"], "disorder": {**CONFIG["scan"]["disorder"], "archive": None}}}
    assert plan.archive_path("disorder_full", empty) is None


# ---- what a run asks for -----------------------------------------------------------------------


def test_paper_targets_are_every_panel_and_figure_as_pdf_and_png():
    targets = plan.paper_targets("out")
    assert "out/figures/fig4d.pdf" in targets and "out/figures/fig4.png" in targets
    assert len(targets) == 2 * (len(panels.PANELS) + len(panels.LAYOUTS))


def test_a_panel_and_a_figure_read_their_scenes_and_only_them():
    for panel_id, panel in panels.PANELS.items():
        files = plan.panel_inputs(panel_id, "out")
        assert {k for k in files if k not in ("chain", "ensemble")} == {s.name for s in panel.scenes}
    for number in panels.LAYOUTS:
        files = plan.figure_inputs(number, "out")
        scenes = {s.name for p in panels.panels_of_figure(number) for s in panels.PANELS[p].scenes}
        assert {k for k in files if k not in ("chain", "ensemble")} == scenes
        assert all(path.startswith("out/") for path in files.values())


def test_beyond_entries():
    figures = {"a": ["spreading", "chaos"], "b": ["spreading"]}.__getitem__
    entries = plan.beyond_entries(["a", {"b": []}], figures)
    assert entries == {"a": ["spreading", "chaos"], "b": []}
    with pytest.raises(ValueError, match="study a has no figure maps; its figures"):
        plan.beyond_entries([{"a": ["maps"]}], figures)
    with pytest.raises(ValueError, match="study a is named twice"):
        plan.beyond_entries(["a", "a"], figures)


def test_study_name_and_cluster_minutes():
    assert plan.study_name("studies/my.v2.yaml") == "my.v2" and plan.study_name("fput100") == "fput100"
    assert plan.cluster_minutes(1, 1e3, 1e-2, 1.0) == 11  # 0.1 s of steps: a minute of margin and ten
    assert plan.cluster_minutes(8, 1e6, 1e-3, 2.0) == 3 * 8 * 1e9 * 2e-6 / 60 + 10


# ---- a second clone runs its own code ------------------------------------------------------------


@pytest.mark.pipeline
def test_a_second_clone_runs_its_own_package_not_the_installed_one(tmp_path):
    """The installed chainchaos is this checkout's (editable): a clone elsewhere must still plan
    with, and run the jobs of, its own src/."""
    clone = tmp_path / "clone"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
    task_file = clone / "src" / "chainchaos" / "workflow" / "tasks" / "chain.py"
    task_file.write_text(task_file.read_text().replace(  # the module imports sys
        '    e = params["ensemble"]', '    print("task of", __file__, file=sys.stderr)\n    e = params["ensemble"]'))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    snakemake = [sys.executable, "-m", "snakemake", "--cores", "1", "--configfile", "config/quick.yaml"]
    # the kernels' sources, inputs of compile_kernels, are the clone's own (the target after "--":
    # --configfile takes several files)
    done = subprocess.run([*snakemake, "-n", "--", "results/kernels/hertz.txt"], cwd=clone, env=env, text=True,
                          capture_output=True, timeout=300)
    assert done.returncode == 0, done.stdout[-3000:]
    assert "input: src/chainchaos/" in done.stdout and "../" not in done.stdout
    done = subprocess.run([*snakemake, "--", "results/ensemble/participation_stats.nc"], cwd=clone, env=env,
                          text=True, capture_output=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    log = (clone / "results" / "logs" / "compute_ensemble" / "run.log").read_text()
    assert f"task of {clone.resolve()}/src/chainchaos/workflow/tasks/chain.py" in log
    shutil.rmtree(clone)
