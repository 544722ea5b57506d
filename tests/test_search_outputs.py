"""The realization search's outputs read from a quick run: its LaTeX table and numbers
(studies.search.report) and its figure (studies.search.plots); the benchmark problem of the
engine timings (studies.numerics.bench)."""

import re

import numpy as np
import pytest
import xarray as xr

from chainchaos.paper import statements
from chainchaos.paper.verdicts import HOLDS
from chainchaos.studies.numerics import bench
from chainchaos.studies.search import report
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
    tex = report.search_table_tex(search, verdicts)
    rows = re.findall(r"\\texttt\{([^}]+)\} & (\d+)/(\d+) & (\d+)/(\d+) &", tex)
    assert [r[0] for r in rows] == [s.id for s in statements.STATEMENTS]
    scored = search["scored"].values == 1
    for sid, unbroken, n_c, held, n_s in rows:
        assert int(n_c) == search.sizes["candidate"] and int(n_s) == scored.sum()
        assert int(unbroken) == (search["filter_outcome"].sel(statement=sid).values != 0).sum()
        assert int(held) == (search["verdict"].sel(statement=sid).values[scored] == HOLDS).sum()


def test_the_search_numbers_are_those_of_the_file(search_results):
    search, verdicts, energy_scan, disorder = search_results
    macros = report.search_macros(search, verdicts, energy_scan, disorder, agreement=0.75)
    assert macros["search.seed"] == str(int(search.attrs["chosen_seed"]))
    assert macros["search.candidates"] == str(search.sizes["candidate"])
    same, total = (int(macros["search.stepsame"]), int(macros["search.steptotal"]))
    assert 0 <= same <= total <= len(statements.STATEMENTS)
    for model in energy_scan.model.values:
        for key in ("deloc", "chaos"):
            assert macros[f"search.{model}.{key}.sentence"][0].isupper()


def test_the_search_figure_shows_every_statement_and_boxes_the_chosen_chain(search_results, tmp_path):
    from matplotlib.patches import Rectangle

    from chainchaos.studies.search import plots

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
