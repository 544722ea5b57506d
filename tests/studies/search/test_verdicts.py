"""Time-weighted reductions, the chaos criterion, ensemble verdicts and the realization search.

The chaos criterion is checked on orbits whose answer is known: the harmonic chain is regular by
construction (its tangent dynamics is the dynamics itself, |v| grows at most linearly), and the
Hertz chain at H = 3 spreads and is strongly chaotic."""

import numpy as np
import pytest

from chainchaos import random_chain
from chainchaos.errors import ParameterError
from chainchaos.observe.reductions import (
    final_average,
    is_chaotic,
    log_time_median,
    loglog_slope,
    sustained_onset,
    time_average,
)
from chainchaos.paper import statements, verdicts
from chainchaos.paper.criteria import Criteria
from chainchaos.run.orbits import Orbit, OrbitSettings, integrate, lane_factor, sample_schedule
from chainchaos.run.scenes import SceneParameters, simulate
from chainchaos.studies.search import stages as search
from chainchaos.studies.search.selection import SelectionCriteria
from chainchaos.studies.study.runs import run_group
from chainchaos.studies.study.spec import load_study


@pytest.fixture(scope="module")
def chain():
    return random_chain(5346, 5.0)


def test_time_average_weights_by_time_not_by_sample():
    t = np.concatenate([np.logspace(0, 3, 31)])
    y = np.where(t < 500, 2.0, 4.0)
    # exact: 2 on [100, 500), 4 on [500, 1000]; the trapezoid smears the jump over the one sample
    # interval that contains it, an error of at most half that interval x the jump / the window
    exact = (2 * 400 + 4 * 500) / 900
    k = np.searchsorted(t, 500)
    bound = (t[k] - t[k - 1]) / 2 * 2.0 / 900
    assert abs(time_average(t, y, 100, 1000) - exact) <= bound + 1e-12
    log_mean = y[t >= 100].mean()  # the old reduction: a mean over log-spaced samples
    assert abs(log_mean - exact) > abs(time_average(t, y, 100, 1000) - exact)
    assert final_average(np.linspace(0, 10, 101), np.linspace(0, 10, 101), 1.0) == pytest.approx(5.5)
    assert np.isnan(time_average(t, y, 2000, 3000))


def test_sustained_onset_ignores_a_single_peak():
    t = np.logspace(0, 4, 81)
    y = np.where(t > 1e3, 10.0, 1.0)
    y[20] = 10.0  # one oscillation peak at t = 10
    assert sustained_onset(t, y, 5.0, 0.5) == pytest.approx(t[t > 1e3][0])
    assert sustained_onset(t, y, 5.0, 0.0) == pytest.approx(t[20])  # no hold: the first sample
    assert np.isnan(sustained_onset(t, np.ones_like(t), 5.0))
    # a crossing in the last half decade counts when it lasts to the end
    late = np.where(t > 5e3, 10.0, 1.0)
    assert sustained_onset(t, late, 5.0, 0.5) == pytest.approx(t[t > 5e3][0])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_harmonic_chain_is_regular_for_every_deviation_vector(chain, seed):
    params = SceneParameters(model="harmonic", energy=1.0, t_final=1e4, dt=0.05, observables=("mlce",), deviation_seed=seed,
                             samples_per_decade=20, t_first_sample=1.0)
    ds = simulate(chain, params)
    t, L = ds.time.values, ds.mlce.values
    assert not is_chaotic(t, t * L)
    assert loglog_slope(t, L, 1e3, 1e4) < -0.5


def test_a_spreading_hertz_orbit_is_chaotic(chain):
    params = SceneParameters(model="hertz", energy=3.0, t_final=1e4, dt=0.02, observables=("mlce",), samples_per_decade=20,
                             t_first_sample=1.0)
    ds = simulate(chain, params)
    t, L = ds.time.values, ds.mlce.values
    assert is_chaotic(t, t * L)
    assert loglog_slope(t, L, 1e3, 1e4) > -0.3


@pytest.mark.parametrize("key, value", [("final_samples", -1), ("perturbation", 1e-2),
                                        ("perturbation", -1e-9), ("perturbation", float("nan"))])
def test_orbit_settings_name_a_bad_sample_count_or_perturbation(key, value):
    with pytest.raises(ParameterError, match=f"invalid {key} = "):
        OrbitSettings(t_final=10.0, dt=0.05, **{key: value})


def test_lanes_perturb_u0_at_the_set_level_and_lane_zero_is_the_scene(chain):
    s = OrbitSettings(t_final=10.0, dt=0.05, perturbation=1e-9)
    assert lane_factor(0, s) == 1.0
    f = [lane_factor(j, s) for j in range(1, 8)]
    assert all(0 < abs(x - 1) <= 1e-9 for x in f) and len(set(f)) == 7
    t, runs = integrate([Orbit(model="fput", energy=0.25, chain=chain, site=21, lane=j) for j in range(3)], s)
    u0 = [r["u0"] for r in runs]
    assert u0[1] != u0[0] and abs(u0[1] / u0[0] - 1) <= 1e-9
    # the schedule: log-spaced samples plus the dense tail over the last decade
    dense = OrbitSettings(t_final=100.0, dt=0.05, samples_per_decade=5, final_samples=45)
    steps = sample_schedule(dense)
    assert steps[-1] == 2000 and np.count_nonzero(steps >= 200) >= 45 and np.all(np.diff(steps) > 0)


def test_ensemble_verdicts_need_agreement():
    assert verdicts.ensemble_verdict([1] * 7 + [0], 0.875)[2] == verdicts.HOLDS
    assert verdicts.ensemble_verdict([1] * 6 + [0] * 2, 0.875)[2] == verdicts.UNDECIDED
    assert verdicts.ensemble_verdict([0] * 7 + [1], 0.875)[2] == verdicts.FAILS
    frac, n, code = verdicts.ensemble_verdict([np.nan, 1, 1], 0.875)
    assert (frac, n, code) == (1.0, 2, verdicts.HOLDS)
    assert verdicts.ensemble_verdict([np.nan] * 3, 0.875)[2] == verdicts.UNTESTABLE


def test_two_indicators_decide_together_and_disagreement_is_undecided():
    both = verdicts.two_indicator_verdict([1] * 8, [1] * 7 + [0], 0.875)
    assert both["verdict"] == both["verdict_lambda"] == both["verdict_gali"] == verdicts.HOLDS
    assert both["fraction"] == 7 / 8 and both["n_decided"] == 8  # the orbits on which both say it holds
    split = verdicts.two_indicator_verdict([1] * 8, [0] * 8, 0.875)
    assert (split["verdict_lambda"], split["verdict_gali"], split["verdict"]) == (
        verdicts.HOLDS, verdicts.FAILS, verdicts.UNDECIDED)
    assert split["fraction"] == 0.0
    fails = verdicts.two_indicator_verdict([0] * 8, [0] * 8, 0.875)
    assert fails["verdict"] == verdicts.FAILS
    alone = verdicts.two_indicator_verdict([1, 1, np.nan], [np.nan] * 3, 0.875, read=False)
    assert (alone["verdict"], alone["fraction"], alone["n_decided"]) == (verdicts.HOLDS, 1.0, 2)
    assert alone["verdict_gali"] == verdicts.NOT_READ and np.isnan(alone["fraction_gali"])
    # the orbits both decide: an orbit one indicator leaves undecided is not counted
    partial = verdicts.two_indicator_verdict([1, 1, 1], [1, 1, np.nan], 0.6)
    assert partial["n_decided"] == 2 and partial["verdict"] == verdicts.HOLDS


def test_gali_decides_the_chaos_statements_and_reports_the_onset():
    """Per orbit GALI_k gives its own outcome for the chaos statements (below the threshold by the
    end: chaotic; by ``until``: not regular up to it) and only reports its crossing time for an
    onset; without a log_gali series no statement is read by it."""
    c = Criteria()
    t = np.concatenate([[0.0], np.logspace(0, 5, 101)])
    by_id = {s.id: s for s in statements.STATEMENTS}
    crossing = 3e3
    with np.errstate(divide="ignore"):
        run = synthetic_run(t, np.full(t.size, 2.0), np.log1p(t))
    run["log_gali"] = np.where(t < crossing, -1.0, np.log(c.gali_threshold) - 1.0)
    assert verdicts.gali_outcome(by_id["chaos-H3-hertz"], t, run, c)[1] == 1.0
    assert verdicts.gali_outcome(by_id["regular-H0.25-hertz"], t, run, c)[1] == 0.0
    assert verdicts.gali_outcome(by_id["chaos-late-H0.5-hertz"], t, run, c)[1] == 0.0  # chaotic before 1e4
    late = dict(run, log_gali=np.where(t < 2e4, -1.0, np.log(c.gali_threshold) - 1.0))
    assert verdicts.gali_outcome(by_id["chaos-late-H0.5-hertz"], t, late, c)[1] == 1.0
    assert verdicts.gali_outcome(by_id["chaos-late-H0.5-hertz"], t, late, c)[0] == 0.0  # not below by 1e4
    value, out = verdicts.gali_outcome(by_id["chaos-onset-H1.8-hertz"], t, run, c)
    assert value == pytest.approx(t[t >= crossing][0]) and np.isnan(out)  # reported, not judged
    assert np.isnan(verdicts.gali_outcome(by_id["loc-H0.25-hertz"], t, run, c)[1])
    plain = {k: v for k, v in run.items() if k != "log_gali"}
    assert np.isnan(verdicts.gali_outcome(by_id["chaos-H3-hertz"], t, plain, c)[1])
    ev = verdicts.evaluate([by_id["chaos-H3-hertz"], by_id["deloc-H3-hertz"]], t, [run, run], c)
    assert list(ev["read_gali"]) == [True, False]
    assert not verdicts.evaluate([by_id["chaos-H3-hertz"]], t, [plain], c)["read_gali"][0]


def synthetic_run(t, P, log_growth, eta=None):
    return {"participation": P, "log_growth": log_growth, "eta": np.ones_like(t) if eta is None else eta,
            "energy_error": np.zeros_like(t), "valid": True}


def test_statements_are_decided_per_orbit_and_an_early_break_counts():
    c = Criteria()
    t = np.concatenate([[0.0], np.logspace(0, 5, 101)])
    with np.errstate(divide="ignore"):
        regular_growth = np.log1p(t)
    loc = next(s for s in statements.STATEMENTS if s.id == "loc-H0.25-hertz")
    reg = next(s for s in statements.STATEMENTS if s.id == "regular-H0.25-hertz")
    localized = synthetic_run(t, np.full(t.size, 2.0), regular_growth)
    spread = synthetic_run(t, np.where(t > 1e2, 20.0, 2.0), 1e-2 * t)
    assert verdicts.outcome(loc, t, localized, c)[1] == 1.0
    assert verdicts.outcome(loc, t, spread, c)[1] == 0.0
    assert verdicts.outcome(reg, t, localized, c)[1] == 1.0
    assert verdicts.outcome(reg, t, spread, c)[1] == 0.0
    short = t[t <= 1e3]
    cut = {k: (v[: short.size] if isinstance(v, np.ndarray) else v) for k, v in spread.items()}
    assert verdicts.outcome(loc, short, cut, c)[1] == 0.0  # already spread: broken early
    cut_ok = {k: (v[: short.size] if isinstance(v, np.ndarray) else v) for k, v in localized.items()}
    assert np.isnan(verdicts.outcome(loc, short, cut_ok, c)[1])  # not yet decided
    assert np.isnan(verdicts.outcome(loc, t, localized, c, valid=False)[1])


def test_the_log_time_median_counts_a_densely_sampled_decade_once():
    # four decades, 10 samples each, and 30 more packed into the last one (a run's final_samples)
    t = np.concatenate([np.logspace(1, 5, 41), np.linspace(1.1e4, 9.9e4, 30)])
    t.sort()
    late = (t > 1e4).astype(float)
    assert np.median(late[t >= 10]) == 1.0  # by sample count the last decade wins
    assert log_time_median(t, late, 10.0) == 0.0  # over log time it is one decade of four
    assert log_time_median(t, np.log10(t), 10.0) == pytest.approx(3.0, abs=0.1)  # the middle of [1, 5]
    assert np.isnan(log_time_median(t, late, 2e5))


def test_p_below_until_reads_every_smoothed_sample_not_the_mean():
    c = Criteria()
    level = next(s for s in statements.STATEMENTS if s.id == "spread-level-H1.8-hertz")
    t = np.concatenate([[0.0], np.logspace(0, 5, 201)])
    low = synthetic_run(t, np.full(t.size, 2.0), np.log1p(t))
    # below 3 on average over [10, 2e2], yet above 3 (smoothed) just before 2e2
    bump = synthetic_run(t, np.where((t > 150) & (t <= 2e2), 6.0, 1.8), np.log1p(t))
    assert time_average(t, bump["participation"], 10.0, 2e2) < 3.0
    assert verdicts.outcome(level, t, low, c)[1] == 1.0
    value, out = verdicts.outcome(level, t, bump, c)
    assert out == 0.0 and value > 3.0
    # a rise after 2e2 (the paper's onset of spreading) does not count
    late = synthetic_run(t, np.where(t > 2e2, 20.0, 2.0), np.log1p(t))
    assert verdicts.outcome(level, t, late, c)[1] == 1.0


def test_search_filters_scores_and_chooses_the_best(tmp_path):
    selection = SelectionCriteria(n_seeds=1000)
    plan = search.SearchPlan(candidates=3, candidates_per_job=2, survivors=2, lanes=2, filter_t_final=20.0)
    settings = OrbitSettings(t_final=50.0, dt=0.05, samples_per_decade=5, final_samples=10)
    c = Criteria()
    found = search.candidates(selection, plan)
    rows = search.candidate_rows(found)
    assert len(rows) == 3 and [r["score"] for r in rows] == sorted(r["score"] for r in rows)
    assert found.attrs["n_qualifying"] >= 3
    filter_studies = search.stage_studies("search", "filter", selection, plan, settings, c, 21, found["seed"].values)
    assert sorted(filter_studies) == ["fput", "hertz"]
    groups = {}
    for model, keys in filter_studies.items():
        study = load_study(keys)
        assert study.n_groups == plan.n_filter_jobs(len(rows)) and study.lanes == 1  # candidates_per_job per job
        assert study.settings.t_final == plan.filter_t_final and not study.settings.alignment
        groups[model] = [run_group(study, g) for g in range(study.n_groups)]
    filtered = search.filter_dataset(plan, settings, c, found, groups)
    filters = [filtered]
    kept = filtered["survivor"].values
    assert len(kept) == 2 and list(kept) == list(search.survivors(filters, plan))
    score_studies = search.stage_studies("search", "score", selection, plan, settings, c, 21, found["seed"].values[kept])
    groups = {model: [run_group(study, g) for g in range(study.n_groups)]
              for model, study in ((m, load_study(keys)) for m, keys in score_studies.items())}
    scores = search.score_datasets(plan, settings, c, found, kept, groups)
    # the score of a survivor integrated in one process (as the re-judging of a kept search does) is the same
    alone = search.score_candidate(selection, plan, settings, c, rows, int(kept[1]), 21)
    for key in ("fraction", "verdict", "measured", "energy_error_max"):
        assert alone[key].values.tobytes() == scores[1][key].values.tobytes(), key
    ds = search.merge(selection, plan, settings, c, found, filters, scores)
    assert ds.sizes == {"candidate": 3, "statement": len(statements.STATEMENTS)}
    scored = np.flatnonzero(ds["scored"].values == 1)
    assert set(scored) == set(int(k) for k in kept)
    best = ds.attrs["chosen_candidate"]
    assert ds["score"].values[best] == np.nanmax(ds["score"].values)
    assert ds.attrs["chosen_seed"] == rows[best]["seed"]
    # pinned: one candidate, no filter jobs
    pinned = search.SearchPlan(pinned_seed=int(rows[1]["seed"]), lanes=2)
    assert pinned.n_filter_jobs(1) == 0 and pinned.n_score_jobs(1) == 1
    only = search.candidates(selection, pinned)
    assert list(only["seed"].values) == [rows[1]["seed"]] and only.attrs["n_qualifying"] == found.attrs["n_qualifying"]
    with pytest.raises(Exception, match="pinned_seed"):
        search.SearchPlan(pinned_seed=-3)
