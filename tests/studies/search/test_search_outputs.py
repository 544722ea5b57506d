"""The realization search's outputs read from a quick run: its LaTeX table and numbers
(studies.search.report) and its figure (output.plotting.search); the benchmark problem of the
engine timings (studies.numerics.bench)."""

import re

import numpy as np
import pytest
import xarray as xr

from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.verdicts import HOLDS, NOT_READ, UNDECIDED
from chainchaos.studies.numerics import bench
from chainchaos.studies.search import joint, report
from chainchaos.system.chain import random_chain
from chainchaos.system.models import get_model, total_energy


@pytest.fixture(scope="module")
def search_results(quick):
    search = xr.load_dataset(quick / "search" / "search.nc")
    verdicts = {p.stem: xr.load_dataset(p) for p in sorted((quick / "verdicts").glob("*.nc"))}
    return search, verdicts, xr.load_dataset(quick / "scan" / "energy_scan.nc"), \
        xr.load_dataset(quick / "scan" / "disorder_statistics.nc")


def test_the_search_table_has_a_row_per_statement_with_its_counts(search_results):
    search, verdicts, _, _ = search_results
    tex = report.search_table_tex(search, search, verdicts)
    rows = re.findall(r"\\texttt\{([^}]+)\} & (\d+)/(\d+) & (\d+)/(\d+)(?: \((\d+), (\d+)\))? &", tex)
    assert [r[0] for r in rows] == [s.id for s in statements.STATEMENTS]
    scored = search["scored"].values == 1
    for sid, unbroken, n_c, held, n_s, by_lambda, by_gali in rows:
        assert int(n_c) == search.sizes["candidate"] and int(n_s) == scored.sum()
        assert int(unbroken) == (search["filter_outcome"].sel(statement=sid).values != 0).sum()
        assert int(held) == (search["verdict"].sel(statement=sid).values[scored] == HOLDS).sum()
        gali = search["verdict_gali"].sel(statement=sid).values[scored]
        assert bool(by_gali) == (gali != NOT_READ).any()
        if by_gali:  # a chaos statement: each indicator's count, and both hold where it holds
            assert int(by_lambda) == (search["verdict_lambda"].sel(statement=sid).values[scored] == HOLDS).sum()
            assert int(by_gali) == (gali == HOLDS).sum()
            assert int(held) <= min(int(by_lambda), int(by_gali))


def test_the_search_numbers_are_those_of_the_file(search_results):
    search, verdicts, energy_scan, disorder = search_results
    macros = report.search_macros(search, search, verdicts, energy_scan, disorder, Criteria(agreement=0.75))
    assert macros["search.seed"] == str(int(search.attrs["chosen_seed"]))
    assert macros["search.candidates"] == str(search.sizes["candidate"])
    same, total = (int(macros["search.stepsame"]), int(macros["search.steptotal"]))
    assert 0 <= same <= total <= len(statements.STATEMENTS)
    for model in energy_scan.model.values:
        for key in ("deloc", "chaos"):
            assert macros[f"search.{model}.{key}.sentence"][0].isupper()


def test_the_merged_search_keeps_both_indicators_and_is_undecided_where_they_differ(search_results):
    search = search_results[0]
    scored = search["scored"].values == 1
    lam, gali, both = (search[key].values[scored] for key in ("verdict_lambda", "verdict_gali", "verdict"))
    read = gali != NOT_READ
    assert read.any(), "the quick search judges chaos by GALI_k too"
    assert (both[read & (lam != gali)] == UNDECIDED).all()
    assert (both[read & (lam == gali)] == lam[read & (lam == gali)]).all()
    assert (both[~read] == lam[~read]).all()


def test_the_indicator_sentence_counts_the_pairs_on_which_lambda_and_gali_differ():
    verdicts = {"verdict_lambda": [[1, 0, 1], [1, 1, 0], [0, 0, 0]],
                "verdict_gali": [[1, 1, NOT_READ], [0, NOT_READ, NOT_READ], [1, 1, 1]]}
    population = xr.Dataset({key: (("candidate", "statement"), np.array(v, dtype=np.int8))
                             for key, v in verdicts.items()} | {"scored": ("candidate", np.array([1, 1, 0]))},
                            attrs={"gali_order": 4})
    sentence = report.indicator_sentence(population)
    assert "on 2 of the 3 (candidate, statement) pairs" in sentence and "on 2 candidates" in sentence
    assert "GALI$_{4}$" in sentence and "2 scored candidates" in sentence
    population["verdict_gali"][:] = NOT_READ
    assert "alone" in report.indicator_sentence(population)
    assert "alone" in report.indicator_sentence(population.drop_vars(["verdict_gali", "verdict_lambda"]))


def test_the_search_figure_shows_every_statement_and_boxes_the_chosen_chain(search_results, tmp_path):
    from matplotlib.patches import Rectangle

    from chainchaos.output.plotting import search as plots

    search = search_results[0]
    fig = plots.search_figure(search)
    left, right = fig.axes[:2]
    assert [t.get_text() for t in left.get_yticklabels()] == [str(s) for s in search.statement.values]
    boxes = [p for p in right.patches if isinstance(p, Rectangle)]
    assert len(boxes) == int(int(search.attrs["chosen_candidate"]) in np.flatnonzero(search["scored"].values == 1))
    for stem in ("a", "b"):
        plots.plot_search(search, tmp_path / f"{stem}.pdf", tmp_path / f"{stem}.png")
    assert (tmp_path / "a.pdf").read_bytes() == (tmp_path / "b.pdf").read_bytes()
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()
    with pytest.raises(ValueError, match="share a stem"):
        plots.plot_search(search, tmp_path / "c.pdf", tmp_path / "d.png")


def test_the_search_figure_of_many_scored_candidates_labels_the_chosen_seed_only(search_results):
    from chainchaos.output.plotting import search as plots

    first = search_results[0]
    n = plots.LABELLED_COLUMNS + 1  # more scored columns than can be labelled: the first one, repeated
    search = first.isel(candidate=np.full(n, int(np.flatnonzero(first["scored"].values == 1)[0])))
    search = search.assign_coords(candidate=np.arange(n))
    search["seed"] = ("candidate", 1000 + np.arange(n))
    search.attrs["chosen_candidate"] = 2
    right = plots.search_figure(search).axes[1]
    assert [t.get_text() for t in right.get_xticklabels()] == ["1002"]
    left = plots.search_figure(search).axes[0]
    assert left.get_xlim() == (0.0, 1.0)  # fractions of each stage's candidates


@pytest.mark.parametrize("model", ["hertz", "fput"])
def test_the_benchmark_problem_is_a_production_one(model):
    problem = bench.benchmark_problem(model)
    chain = random_chain(bench.CHAIN_SEED, bench.ALPHA)
    law = get_model(model)
    H0 = float(total_energy(law, chain, problem["q"], problem["p"]))
    assert H0 == pytest.approx(bench.ENERGY, rel=1e-12)
    q0 = problem["q"].copy()
    state, growth, seconds = bench.run_kernel(problem, "SRKN6b", 2000, tangent=True)
    assert np.array_equal(problem["q"], q0)  # the kernel ran on a copy
    H = float(total_energy(law, chain, state["q"], state["p"]))
    assert abs(H - H0) / H0 < 1e-9 and np.isfinite(growth) and seconds > 0
    assert bench.time_kernel(model, "SRKN6b", n_steps=200, repeats=1) > 0


def _population(verdicts: np.ndarray, scores, onset, level) -> xr.Dataset:
    """A merged search of len(scores) scored candidates over the first verdicts.shape[1] statements
    (the rest untestable), with Hertz H = 1.8's onset and level medians."""
    ids = [st.id for st in statements.STATEMENTS]
    C, S = verdicts.shape
    v = np.full((C, len(ids)), -2, dtype=np.int8)
    v[:, :S] = verdicts
    median = np.full((C, len(ids)), np.nan)
    median[:, ids.index(joint.ONSET)], median[:, ids.index(joint.LEVEL)] = onset, level
    best = int(np.argmax(scores))
    return xr.Dataset({"scored": ("candidate", np.ones(C, dtype=np.int8)),
                       "verdict": (("candidate", "statement"), v),
                       "score": ("candidate", np.asarray(scores, dtype=float)),
                       "measured_median": (("candidate", "statement"), median)},
                      coords={"candidate": np.arange(C), "statement": ids},
                      attrs={"chosen_score": float(scores[best]), "chosen_candidate": best})


def test_the_joint_analysis_finds_exclusive_statements_and_ranks_the_chosen_chain():
    # statements 0 and 1 never hold together, 2 always holds, 3 never: one exclusive pair
    verdicts = np.array([[1, 0, 1, 0], [0, 1, 1, 0], [1, 0, 1, 0], [1, 1, 1, -1]])
    verdicts[3, 1] = 0
    ds = _population(verdicts, [2.5, 2.0, 2.5, 1.0], onset=[2e2, 3e2, 1e3, np.nan], level=[5e-3, 1e-3, 1e-3, 1e-3])
    j = joint.joint_statements(ds)
    ids = [st.id for st in statements.STATEMENTS]
    assert j.exclusive_pairs() == [(ids[0], ids[1])]
    assert j.both[0, 2] == 3 and j.both[2, 2] == 4 and j.both[3, 3] == 0
    assert j.all_held() == 0 and j.at_least_as_good() == 2
    assert joint.paper_onset_and_level() == (2e2, 1e-3)  # the paper: chaotic from t ~ 2e2, Lambda ~ 1e-3
    c = joint.onset_level_consistency(ds, 2.0, 3.0)
    # onsets within x2 of 2e2: candidates 0 and 1; levels within x3 of 1e-3: 1 and 2 (3 has no onset)
    assert c == {"onset_near": 2, "level_near": 3, "both": 1, "lowest_level_with_onset": 1e-3, "decided": 3}


def test_the_joint_figure_marks_every_exclusive_pair(tmp_path):
    from chainchaos.output.plotting import search as plots

    verdicts = np.array([[1, 0, 1], [0, 1, 1]])
    ds = _population(verdicts, [2.0, 2.0], onset=[2e2, 1e3], level=[1e-2, 1e-3])
    fig = plots.joint_figure(ds)
    matrix = fig.axes[0]
    crosses = [line for line in matrix.lines if line.get_marker() == "x"]
    assert len(crosses) == 1 and sorted(crosses[0].get_xdata()) == [0, 1]
    assert matrix.get_xlabel() == "" and fig.axes[2].get_xlabel() and fig.axes[3].get_yscale() == "log"


def test_the_archive_sums_the_jobs_costs_per_stage_and_names_its_machines(tmp_path):
    from chainchaos.studies.search import archive

    header = "s\th:m:s\tmax_rss\tmax_vms\tmax_uss\tmax_pss\tio_in\tio_out\tmean_load\tcpu_time\n"

    def row(wall, cpu):
        return header + f"{wall}\t0\t0\t0\t0\t0\t0\t0\t0\t{cpu}\n"

    runs = {"search_seeds": [(2.0, 1.5), (3.0, 2.5)], "search_filter": [(10.0, 9.0)], "search_merge": [(1.0, 0.5)]}
    for stage, rows in runs.items():
        (tmp_path / stage).mkdir()
        for k, (wall, cpu) in enumerate(rows):
            (tmp_path / stage / f"search_full-{k:03d}.tsv").write_text(row(wall, cpu))
        (tmp_path / stage / "search-000.tsv").write_text(row(99, 99))  # the other search's job
    costs = archive.job_costs(tmp_path)
    assert costs["search_seeds"] == {"jobs": 2, "wall_seconds": 5.0, "cpu_seconds": 4.0}
    assert costs["study_group"] == {"jobs": 0, "wall_seconds": 0.0, "cpu_seconds": 0.0}
    assert costs["total"]["jobs"] == 4 and costs["total"]["cpu_seconds"] == 13.5
    assert costs["total"]["span_seconds"] >= 10.0  # the longest job at least

    stage_file = tmp_path / "stage.nc"
    xr.Dataset(attrs={"git_commit": "abc", "cpu_model": "CPU X", "numba_target_cpu": "znver4"}).to_netcdf(stage_file)
    machines = archive.stage_machines([stage_file, stage_file])
    assert machines == {"stage_commits": "abc", "stage_cpus": "CPU X (znver4)"}
    ds = archive.archive_dataset(xr.Dataset(attrs={"chosen_seed": 7}), costs, machines)
    assert ds.attrs["cost_search_seeds_jobs"] == 2 and ds.attrs["cost_total_cpu_seconds"] == 13.5
    assert ds.attrs["chosen_seed"] == 7 and ds.attrs["stage_cpus"] == "CPU X (znver4)"
