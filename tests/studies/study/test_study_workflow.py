"""Studies through the workflow: the worked example of the docs (studies/hertz100.yaml and
studies/fput100.yaml, which compares with it) end to end, and a small study whose files equal
chainchaos.run_study's numbers to the bit, that resumes from its finished jobs and plans nothing
of the paper."""

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.image import imread
from project.test_pipeline import planned_jobs, snakemake

from chainchaos import run_study

ROOT = Path(__file__).resolve().parents[3]
# One worker runs this module's tests (its module-scoped runs happen once under pytest-xdist).
pytestmark = [pytest.mark.pipeline, pytest.mark.xdist_group("study_workflow")]  # every test here runs Snakemake

SMALL = """\
title: a small Hertz study of the tests
lattice: {model: [hertz, fput], N: 24, alpha: 3.0, realizations: 3}
excitation: {energies: [0.5, 2.0]}
integration: {dt: 0.02, t_final: 200.0}
observables: [participation, second_moment, mlce, log_gali]
ensemble: {lanes: 2}
jobs: {orbits_per_job: 8}
"""


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    base = tmp_path_factory.mktemp("small_study")
    (base / "small.yaml").write_text(SMALL)
    results = base / "results"
    code, out = snakemake("study", "--config", f"study={base / 'small.yaml'}", f"results={results}")
    assert code == 0, out[-6000:]
    return base, results / "studies" / "small"


def test_the_workflow_writes_run_studys_numbers(small):
    base, out = small
    ds = run_study(base / "small.yaml")
    stats = xr.load_dataset(out / "statistics.nc")
    for name in stats.data_vars:
        np.testing.assert_array_equal(stats[name].values, ds[name].values, err_msg=name)
    for model in ("hertz", "fput"):
        for energy in (0.5, 2.0):
            scene = xr.load_dataset(out / f"{model}_H{energy:g}.nc")
            expected = ds.sel(model=model, energy=energy)
            assert scene.sizes["realization"] == 3 and scene.sizes["lane"] == 2
            for name in scene.data_vars:
                np.testing.assert_array_equal(scene[name].values, expected[name].values, err_msg=name)
            assert scene.attrs["model"] == model and scene.attrs["energy"] == energy


def test_a_study_resumes_from_its_finished_jobs_and_plans_nothing_of_the_paper(small, tmp_path):
    """As after a run interrupted in its second job: the finished groups are not run again."""
    base, out = small
    copy = tmp_path / "results" / "studies" / "small"
    shutil.copytree(out / "groups", copy / "groups")
    shutil.copytree(out.parents[1] / "kernels", tmp_path / "results" / "kernels")
    (copy / "groups" / "0001.nc").unlink()
    code, plan = snakemake("-n", "study", "--config", f"study={base / 'small.yaml'}", f"results={tmp_path / 'results'}")
    assert code == 0, plan
    jobs = planned_jobs(plan)
    assert jobs["study_group"] == 1 and jobs["study_statistics"] == 1, jobs
    assert not {"search_seeds", "select_chain", "evaluate_claims", "build_manuscript", "simulate_scenes"} & set(jobs)


def test_a_changed_key_reruns_the_study(small, tmp_path):
    _, out = small
    changed = tmp_path / "small.yaml"
    changed.write_text(SMALL.replace("t_final: 200.0", "t_final: 300.0"))
    code, plan = snakemake("-n", "study", "--config", f"study={changed}", f"results={out.parents[1]}")
    assert code == 0, plan
    assert planned_jobs(plan)["study_group"] == 3  # 24 orbits, 8 a job: every job again


def test_a_wrong_study_stops_with_one_line_per_key(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(SMALL.replace("excitation: {energies: [0.5, 2.0]}", "excitation: {energies: [1.0], site: 30}"))
    code, out = snakemake("-n", "study", "--config", f"study={bad}", f"results={tmp_path / 'r'}")
    assert code != 0
    assert "study key excitation.site = 30: allowed is beads within 1..N = 24" in out


def test_the_target_study_needs_a_study():
    code, out = snakemake("-n", "study")
    assert code != 0 and "the target study needs a study: --config study=<name>" in out and "hertz100" in out


@pytest.fixture(scope="module")
def worked(tmp_path_factory):
    """The worked example of the docs, as a user runs it: the FPUT study, which compares with the
    Hertz one and so runs both (16 realizations x 3 energies each, N = 100, to t = 1e4)."""
    results = tmp_path_factory.mktemp("worked")
    code, out = snakemake("study", "--config", "study=fput100", f"results={results}", timeout=1500)
    assert code == 0, out[-6000:]
    return results / "studies"


def test_the_worked_study_makes_every_product(worked):
    fput = worked / "fput100"
    for energy in ("0.5", "1.8", "3"):
        with xr.open_dataset(fput / f"fput_H{energy}.nc") as ds:
            assert ds.sizes["realization"] == 16 and (ds["valid"] == 1).all()
            assert float(ds["energy_error_max"].max()) < 1e-3
            assert {"second_moment", "mlce", "log_gali", "mean_log10_second_moment", "fraction_chaotic"} <= set(ds)
    for figure in ("spreading", "chaos", "fractions", "comparison"):
        assert imread(fput / "figures" / f"{figure}.png").std() > 0.01, figure
        assert (fput / "figures" / f"{figure}.pdf").read_bytes()[:5] == b"%PDF-"
    with xr.open_dataset(worked / "hertz100" / "statistics.nc") as ds:
        assert ds.model.values.tolist() == ["hertz"] and ds.sizes["realization"] == 16


def test_the_worked_studys_files_pass_the_cf_checker(worked):
    from records.test_compliance import cf_problems

    for path in ("fput100/fput_H1.8.nc", "fput100/statistics.nc", "fput100/groups/0000.nc"):
        assert cf_problems(worked / path) == [], path


@pytest.mark.browser
def test_the_report_shows_the_studys_figures(worked, tmp_path):
    report = tmp_path / "report.html"
    code, out = snakemake("--report", str(report), "study", "--config", "study=fput100", f"results={worked.parent}")
    assert code == 0, out[-4000:]
    assert "ERROR" not in out and "WARNING" not in out.replace("WARNING: Location", ""), out[-4000:]
    html = report.read_text()
    for figure in ("spreading.png", "chaos.png", "fractions.png", "comparison.png"):
        assert figure in html, figure
    assert "Studies" in html and "fput100" in html
    from browser import console_errors

    assert console_errors([report]) == {str(report): []}  # it loads in Chromium without errors


TINY = """\
title: a tiny study kept as data
lattice: {model: fput, N: 16, realizations: 2}
excitation: {energies: [1.0]}
integration: {dt: 0.05, t_final: 50.0}
figures: [chaos]
jobs: {orbits_per_job: 1}
"""


def test_a_kept_study_is_read_not_run_and_a_changed_key_stops_the_jobs_that_read_it(tmp_path):
    """`keep --config keep=<study>` keeps each group with its key; with the study in config
    use_kept_studies it then plans no group job, and a changed key plans the same jobs: a key its
    numbers do not depend on (its figures) runs, a changed step stops the jobs that read the groups
    with one line naming it and the two ways out (and so does keep). Not used, the study is
    computed."""
    study, results, kept = tmp_path / "tiny.yaml", tmp_path / "results", tmp_path / "kept"
    study.write_text(TINY)
    config = ("--config", f"study={study}", f"results={results}", f"kept_studies={kept}")
    code, out = snakemake("keep", *config, "keep=tiny")
    assert code == 0, out[-4000:]
    files = sorted((kept / "tiny" / "groups").glob("*.nc"))
    assert [f.name for f in files] == ["0000.nc", "0001.nc"]
    key = xr.open_dataset(files[0]).attrs
    assert len(key["kept_settings_digest"]) == 64 and key["result_version"] >= 1
    assert not (results / "studies" / "tiny" / "groups").exists()  # computed straight into the kept files
    used = (*config, "use_kept_studies=[tiny]")
    code, plan = snakemake("-n", "study", *used)
    assert code == 0 and "study_group" not in planned_jobs(plan), plan[-3000:]
    study.write_text(TINY.replace("figures: [chaos]", "figures: [chaos, spreading]"))
    code, out = snakemake("study", *used)
    assert code == 0, out[-3000:]
    study.write_text(TINY.replace("dt: 0.05", "dt: 0.04"))
    code, changed = snakemake("-n", "study", *used)
    assert code == 0 and "study_group" not in planned_jobs(changed), changed[-3000:]
    line = (f"kept file {files[0]}: integration.dt is 0.05 in the file, 0.04 in this run; remake it with "
            f"'rm -r {kept / 'tiny'} && snakemake --cores 2 keep --config keep=tiny', or take tiny out of config "
            "use_kept_studies to compute it in this run")
    code, out = snakemake("study", *used)
    log = (results / "logs" / "study_statistics" / "tiny.log").read_text()
    assert code != 0 and log == f"study_statistics: {line}\n", log
    code, out = snakemake("keep", *config, "keep=tiny")
    assert code != 0 and line in out, out[-3000:]
    code, plan = snakemake("-n", "study", *config)
    assert code == 0 and planned_jobs(plan)["study_group"] == 2, plan[-3000:]
