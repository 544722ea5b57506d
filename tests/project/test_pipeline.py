"""The pipeline end to end at quick scale, its incremental behaviour, and config validation.

The quick run writes into a temporary results directory (config key `results`), so it neither
needs nor touches the project's own results/.
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.image import imread

from chainchaos.paper import panels, statements

ROOT = Path(__file__).resolve().parents[2]
QUICK = ["--configfile", "config/quick.yaml"]

pytestmark = pytest.mark.pipeline  # every test here runs Snakemake


def snakemake(*args, timeout=1500):
    done = subprocess.run([sys.executable, "-m", "snakemake", "--cores", "2", "--nolock", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=timeout)
    return done.returncode, done.stdout + done.stderr


def planned_jobs(output: str) -> dict[str, int]:
    """Job counts from the 'Job stats' table of a (dry) run."""
    table = output.split("Job stats:")[-1]
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+)\s+(\d+)$", table, re.M) if m.group(1) != "total"}


# The `quick` fixture (the whole quick-scale pipeline in a temporary results directory) is in
# conftest.py, shared with tests/paper/test_claims.py.


def test_every_panel_and_figure_exists_and_is_not_blank(quick):
    names = [f"fig{p}" for p in panels.PANELS] + [f"fig{n}" for n in panels.LAYOUTS]
    for name in names:
        pdf, png = quick / "figures" / f"{name}.pdf", quick / "figures" / f"{name}.png"
        assert pdf.stat().st_size > 1000 and pdf.read_bytes()[:5] == b"%PDF-", name
        pixels = imread(png)
        assert pixels.std() > 0.01, f"{name}.png is blank"


def test_each_scene_holds_what_its_panels_asked_for(quick):
    for name, scene in panels.scenes().items():
        with xr.open_dataset(quick / "scenes" / f"{name}.nc") as ds:
            asked = set(panels.scene_observables(name))
            written = {v for v in ds.data_vars if v in _contract_variables()}
            assert written == asked | {"energy_error"}, name
            assert ds.attrs["model"] == scene.model and ds.attrs["energy"] == scene.energy
            assert ds.attrs["final_energy_error"] < 1e-2
            assert np.all(np.isin(10.0 ** np.arange(0, 4), ds.time.values))


def _contract_variables():
    from chainchaos.observe.registry import OBSERVABLES

    return set(OBSERVABLES)


def test_deleted_panel_reruns_only_its_drawing_job(quick):
    (quick / "figures" / "fig4d.pdf").unlink()
    code, out = snakemake(str(quick / "figures" / "fig4d.pdf"), *QUICK, "--config", f"results={quick}", "-n")
    assert code == 0, out
    assert planned_jobs(out) == {"plot_panel": 1} and "wildcards: panel=4d" in out


def test_deleted_study_figure_reruns_only_its_drawing_job(quick, tmp_path):
    figure = quick / "studies" / "kg_weak_chaos" / "figures" / "chaos.pdf"
    kept = shutil.copy2(figure, tmp_path / "chaos.pdf")
    figure.unlink()
    try:
        code, out = snakemake(str(figure), *QUICK, "--config", f"results={quick}", "-n")
    finally:
        shutil.copy2(kept, figure)  # the other tests of the quick run read it
    assert code == 0, out
    assert planned_jobs(out) == {"plot_study": 1}


def test_changed_scene_parameter_reruns_only_its_scene(quick, tmp_path):
    """A changed setting of one scene reruns that scene, the panels drawn from it and their
    figures; nothing else."""
    override = tmp_path / "override.yaml"
    override.write_text("scenes:\n  hertz_H1.8:\n    dt: 0.005\n")
    code, out = snakemake(*QUICK, str(override), "--config", f"results={quick}", "-n")
    assert code == 0, out
    jobs = planned_jobs(out)
    assert jobs["simulate_scene"] == 1 and "/scenes/hertz_H1.8.nc" in out
    affected = {p for p, panel in panels.PANELS.items() if "hertz_H1.8" in {s.name for s in panel.scenes}}
    assert jobs["plot_panel"] == len(affected)
    assert jobs["plot_figure"] == len({p[:-1] for p in affected})
    assert "compute_ensemble" not in jobs and "select_chain" not in jobs


def test_paper_scale_dry_run_plans_every_scene(tmp_path):
    code, out = snakemake("-n", "--config", f"results={tmp_path}")
    assert code == 0, out[-4000:]
    jobs = planned_jobs(out)
    # one job per scene, per panel and per composite
    assert set(re.findall(r"/scenes/(\w+_H[\d.]+)\.nc", out)) == set(panels.scenes())
    assert jobs["simulate_scene"] == len(panels.scenes())
    assert (jobs["plot_panel"], jobs["plot_figure"]) == (len(panels.PANELS), len(panels.LAYOUTS))
    # the realization search: stage 0 (its size decides stage 1: a checkpoint), the verdicts one job per scene
    assert jobs["search_seeds"] == 1 and jobs["search_candidates"] == 1 and jobs["search_merge"] == 1
    assert jobs["ensemble_verdicts"] == len(statements.statement_scenes())


def test_an_archived_full_search_pins_its_chain_and_none_searches(tmp_path):
    """With search.archive named, `all` re-scores the archive's chain (search.pinned_seed) alone;
    with none and no pinned seed it searches, its filter planned once stage 0 has run."""
    for archive, seed, pinned in (("data/search/search_full.nc", 879, True), ("", "", False)):
        config = tmp_path / "archive.yaml"
        config.write_text(f"search:\n  archive: '{archive}'\n  pinned_seed: {seed}\n")
        code, out = snakemake("-n", "--configfile", "config/config.yaml", str(config),
                              "--config", f"results={tmp_path / 'results'}")
        assert code == 0, out[-4000:]
        jobs = planned_jobs(out)
        # the filter studies' chains are known once stage 0 has run; a pinned seed's score studies at once
        assert "/search-filter-" not in out and jobs["search_candidates"] == 1
        assert ("search_filter" in jobs) != pinned and ("/search-score-" in out) == pinned, (archive, jobs)
        assert ("kept/search_full.txt" in out) == pinned


def test_a_pinned_seed_rescores_that_chain_without_a_search(tmp_path):
    pinned = tmp_path / "pinned.yaml"
    pinned.write_text("search:\n  archive:\n  pinned_seed: 879\n")
    code, out = snakemake(str(tmp_path / "search" / "search.nc"), "--configfile", "config/config.yaml",
                          str(pinned), "--config", f"results={tmp_path}", "-n")
    assert code == 0, out[-4000:]
    jobs = planned_jobs(out)
    assert "search_filter" not in jobs and jobs["search_merge"] == 1
    assert set(re.findall(r"/search-score-(\w+)/groups/(\d+)\.nc", out)) == {("hertz", "0000"), ("fput", "0000")}
    assert jobs["search_candidates"] == 1


def test_the_search_chooses_the_chain_and_the_verdicts_run_on_it(quick):
    found = xr.load_dataset(quick / "search" / "search.nc")
    chain = xr.load_dataset(quick / "chain" / "chain.nc")
    assert int(chain.attrs["seed"]) == found.attrs["chosen_seed"] == int(chain.attrs["selection_seed"])
    assert found.sizes["statement"] == len(statements.STATEMENTS) and found.attrs["n_scored"] >= 1
    for name in statements.statement_scenes():
        v = xr.load_dataset(quick / "verdicts" / f"{name}.nc")
        assert int(v.attrs["seed"]) == found.attrs["chosen_seed"]
        assert v.sizes["lane"] >= 2 and set(v.statement.values) == {s.id for s in statements.statements_of_scene(name)}
        u0 = v["u0"].values
        assert np.all(np.abs(u0[1:] / u0[0] - 1) <= 1e-9) and len(set(u0)) == u0.size
    image = imread(quick / "figures" / "search.png")
    assert image.std() > 0.01


def test_the_readme_s_one_panel_commands_run_at_the_scale_they_say(quick):
    """The README's one-panel command as written (results/ moved to the quick run's directory):
    its quick form after a quick run integrates nothing again; without --configfile it is the paper
    scale, whose scenes it would integrate again."""
    readme = (ROOT / "README.md").read_text()
    command = re.search(r"`(snakemake --cores 2 results/figures/fig4d\.pdf --configfile config/quick\.yaml)`",
                        readme).group(1).split()
    assert command[:3] == ["snakemake", "--cores", "2"]
    args = [a.replace("results/", f"{quick}/", 1) for a in command[3:]]
    code, out = snakemake("-n", *args, "--config", f"results={quick}")
    # nothing but the panel's own drawing job (another test may have deleted a panel of it)
    assert code == 0 and set(planned_jobs(out)) <= {"plot_panel"}, out[-3000:]
    paper = [a for a in args if a not in QUICK]
    code, out = snakemake("-n", *paper, "--config", f"results={quick}")
    jobs = planned_jobs(out)
    assert code == 0 and jobs["plot_panel"] == 1 and jobs.get("simulate_scene", 0) >= 1, out[-3000:]


# Reproducibility (bit for bit), not physics: these digests are this code's own quick-scale output
# (AMD EPYC Zen 4, AVX-512; every x86-64 with FMA gives the same bits, tests/kernels/
# test_machine_independence.py). A change to how the work is cut into jobs must leave them as they
# are; a deliberate change of the numerics changes them: write the new ones then, and say so in the
# commit.
QUICK_CLAIMS_SHA256 = "75b54c5550a1ac1e07c15e7630fa8b12c5e3867749ad48bcd4517f71f965f202"
QUICK_SCENES_SHA256 = "6222633d30e6178d862ffec21503bca9e1740eecb18d78a2bb37d68752057051"


def test_quick_claims_and_scenes_bit_for_bit(quick):
    import hashlib

    assert hashlib.sha256((quick / "claims" / "claims.csv").read_bytes()).hexdigest() == QUICK_CLAIMS_SHA256
    scenes = hashlib.sha256()
    for path in sorted((quick / "scenes").glob("*.nc")):
        ds = xr.load_dataset(path)
        for name in sorted(ds.data_vars):
            scenes.update(f"{path.name}:{name}".encode())
            scenes.update(ds[name].values.tobytes())
    assert scenes.hexdigest() == QUICK_SCENES_SHA256
