"""Re-judging a kept search (chainchaos.studies.search.rejudge) gives what a full search gives.

A small search is run in full; its merged result, with the columns of two statements spoiled and
one survivor marked as never scored, stands for a kept search made by other judging code.
Re-judging those statements (integrating only their scenes again, and scoring the unscored
survivor in full) must return the full search to the bit; a spoiled column of a statement that
was not re-judged must be caught."""

import numpy as np
import pytest

from chainchaos.errors import ParameterError
from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.records import kept as kept_files
from chainchaos.records.io import write_netcdf
from chainchaos.run.orbits import OrbitSettings
from chainchaos.studies.search import rejudge
from chainchaos.studies.search import stages as search
from chainchaos.studies.search.selection import SelectionCriteria
from chainchaos.studies.study.runs import run_group
from chainchaos.studies.study.spec import load_study
from chainchaos.workflow.tasks.keep import _stage_files

IDS = ["spread-level-H1.8-hertz", "eta-H4-fput"]
SITE = 21


@pytest.fixture(scope="module")
def full():
    selection = SelectionCriteria(n_seeds=1000)
    # filter_t_final past 2e2: the short run decides spread-level-H1.8-hertz
    plan = search.SearchPlan(candidates=4, candidates_per_job=2, survivors=2, lanes=2, filter_t_final=250.0)
    settings = OrbitSettings(t_final=400.0, dt=0.05, samples_per_decade=5, final_samples=10)
    c = Criteria()
    found = search.candidates(selection, plan)
    rows = search.candidate_rows(found)
    assert len(rows) == 4
    filtered = search.filter_dataset(plan, settings, c, found, _groups("filter", selection, plan, settings, c,
                                                                        found["seed"].values))
    ranked = filtered["survivor"].values
    scores = search.score_datasets(plan, settings, c, found, ranked, _groups("score", selection, plan, settings, c,
                                                                             found["seed"].values[ranked]))
    return selection, plan, settings, c, search.merge(selection, plan, settings, c, found, [filtered], scores)


def _groups(stage, selection, plan, settings, c, seeds) -> dict:
    """Every group of a search stage's studies (stages.stage_studies), run in this process."""
    studies = {model: load_study(keys) for model, keys in
               search.stage_studies("search", stage, selection, plan, settings, c, SITE, seeds).items()}
    return {model: [run_group(study, g) for g in range(study.n_groups)] for model, study in studies.items()}


def _column(name):
    return [st.id for st in statements.STATEMENTS].index(name)


def _spoiled(ds, unscored: int, also=()):
    kept = ds.copy(deep=True)
    kept.attrs.update(kept_files.kept_attrs({"search": "made by older judging code"}, 1))
    for name in [*IDS, *also]:
        k = _column(name)
        kept["filter_outcome"].values[:, k] = np.where(np.isfinite(kept["filter_outcome"].values[:, k]),
                                                       1 - kept["filter_outcome"].values[:, k], 0.0)
        for key in ("fraction", "fraction_lambda", "measured_median"):
            kept[key].values[:, k] = 0.123
        kept["verdict"].values[:, k] = -1
    kept["scored"].values[unscored] = 0
    for key in rejudge.SCORE_COLUMNS:
        kept[key].values[unscored] = np.nan if kept[key].dtype.kind == "f" else -3
    return kept


def _rejudge(kept, selection, plan, settings, c):
    fplan = rejudge.filter_plan(plan, IDS)
    groups = [rejudge.filter_group(kept, selection, plan, settings, c, IDS, g, SITE)
              for g in range(fplan.n_filter_jobs(kept.sizes["candidate"]))]
    filtered = rejudge.rejudged_filter(kept, groups, IDS, plan)
    ranks = search.survivors([filtered], plan)
    scores = [rejudge.score_candidate(kept, selection, plan, settings, c, IDS, rejudge.survivor(kept, filtered, plan, r),
                                      SITE) for r in range(ranks.size)]
    return rejudge.rejudged_search(kept, selection, plan, settings, c, filtered, scores)


def test_only_the_scenes_a_short_run_decides_are_filtered_again():
    assert rejudge.filter_scenes(IDS, 1e4) == ["hertz_H1.8"]  # eta-H4-fput needs t = 1e5
    assert rejudge.scenes_of(IDS) == ["hertz_H1.8", "fput_H4"]
    with pytest.raises(Exception, match="no-such-statement"):
        rejudge.check_ids(["no-such-statement"])


def test_a_rejudged_search_equals_the_full_search(full):
    selection, plan, settings, c, ds = full
    unscored = int(np.flatnonzero(ds["scored"].values)[0])
    again = _rejudge(_spoiled(ds, unscored), selection, plan, settings, c)
    for name, var in ds.data_vars.items():
        a, b = var.values, again[name].values
        assert a.dtype == b.dtype or a.dtype.kind == b.dtype.kind, name
        if a.dtype.kind == "f":
            assert np.array_equal(a, b, equal_nan=True), name
        else:
            assert np.array_equal(a, b), name
    assert again.attrs["chosen_seed"] == ds.attrs["chosen_seed"]


def test_a_kept_column_the_recomputed_orbits_contradict_stops_the_merge(full):
    selection, plan, settings, c, ds = full
    scored = np.flatnonzero(ds["scored"].values)
    kept = _spoiled(ds, int(scored[0]))
    kept["fraction"].values[scored[1], _column("spread-onset-H1.8-hertz")] = 0.123  # not re-judged, same scene
    with pytest.raises(rejudge.RejudgeMismatch, match="spread-onset-H1.8-hertz"):
        _rejudge(kept, selection, plan, settings, c)


def test_a_stage_file_of_another_rejudging_is_not_read(full, tmp_path):
    selection, plan, settings, c, ds = full
    kept = _spoiled(ds, int(np.flatnonzero(ds["scored"].values)[0]))
    path = tmp_path / "000.nc"
    write_netcdf(rejudge.filter_group(kept, selection, plan, settings, c, IDS, 0, SITE), path, seal=True)
    assert _stage_files([path], kept, list(reversed(IDS)))[0]["outcome"].shape[1] == len(statements.STATEMENTS)
    with pytest.raises(ParameterError, match=r"rejudge is \[\"eta-H4-fput\",\"spread-level-H1.8-hertz\"\] in the file"):
        _stage_files([path], kept, IDS[:1])
    other = kept.copy()
    other.attrs.update(kept_files.kept_attrs({"search": "another kept search"}, 1))
    with pytest.raises(ParameterError, match="kept_search_digest"):
        _stage_files([path], other, IDS)
